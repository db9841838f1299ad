// libFuzzer harness: campaign manifests (calibration/campaign.hpp read_campaign). The manifest is a
// per-process temporary file; valid quasi-static and dynamic CSV files lie beside it (qs.csv, dyn.csv)
// so that the fuzzer reaches the per-test keys.
#include "calibration/campaign.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const bool files = [] {
    std::string qs = "time_s,displacement_mm,force_N\n";
    for (int i = 0; i <= 20; ++i) qs += std::to_string(i) + "," + std::to_string(i) + "," + std::to_string(i * i) + "\n";
    for (int i = 19; i >= 0; --i)
      qs += std::to_string(40 - i) + "," + std::to_string(i) + "," + std::to_string(i * i / 2) + "\n";
    cushion::fuzz::write_file("qs.csv", qs);
    cushion::fuzz::write_file("dyn.csv", "frequency_Hz,dynamic_modulus_kPa,phase_deg\n1,50,10\n2,52,11\n5,55,12\n");
    cushion::fuzz::write_file("stiff.csv", "frequency_Hz,dynamic_stiffness_N_per_mm,phase_deg\n1,50,10\n2,52,11\n");
    cushion::fuzz::write_file("indent.csv", "indentation_mm,force_N\n0,0\n1,10\n2,30\n");
    return true;
  }();
  (void)files;
  const auto path = cushion::fuzz::write_file("campaign.json", cushion::fuzz::text(data, size));
  cushion::fuzz::expect_input_error_only([&] { cushion::calibration::read_campaign(path); });
  return 0;
}
