// libFuzzer harness: CSV tables (io/csv.hpp read_csv, from a per-process temporary file), then the
// column-set check every CSV consumer makes.
#include "io/csv.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = cushion::fuzz::write_file("fuzz.csv", cushion::fuzz::text(data, size));
  cushion::fuzz::expect_input_error_only([&] {
    const cushion::CsvTable table = cushion::read_csv(path);
    cushion::require_columns(table, {{"time_s", "displacement_mm", "force_N"}, {"frequency_Hz", "phase_deg"}});
  });
  return 0;
}
