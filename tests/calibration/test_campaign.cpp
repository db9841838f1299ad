// Campaign reader: a good manifest, and each bad input raising an InputError that names the file and
// the line/column or key.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "calibration/campaign.hpp"
#include "io/input_error.hpp"

namespace cal = cushion::calibration;
namespace fs = std::filesystem;

namespace {

class Campaign : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("cushion_campaign_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    std::string qs = "time_s,displacement_mm,force_N\n";
    for (int i = 0; i <= 40; ++i) {
      const double u = i <= 20 ? 3.0 * i : 3.0 * (40 - i);
      qs += std::to_string(i) + "," + std::to_string(u) + "," + std::to_string(0.05 * u * u + (i <= 20 ? 5 : 0)) + "\n";
    }
    write("qs_120.csv", qs);
    write("dyn_25.csv", "# dynamic test\nfrequency_Hz,storage_modulus_kPa,loss_modulus_kPa\n1,40,10\n2,45,12\n3,48,13\n");
  }
  void TearDown() override { fs::remove_all(dir_); }
  void write(const std::string& name, const std::string& text) { std::ofstream(dir_ / name) << text; }
  fs::path manifest(const std::string& text) {
    write("campaign.json", text);
    return dir_ / "campaign.json";
  }
  std::string error_of(const std::string& text) {
    try {
      cal::read_campaign(manifest(text));
    } catch (const cushion::InputError& e) {
      return e.what();
    }
    return "(no error)";
  }
  static std::string good(const std::string& dyn_extra = "") {
    return R"({"specimen": {"length_mm": 80, "width_mm": 80, "thickness_mm": 80, "density_kg_m3": 65},
      "tests": [{"kind": "quasi_static", "file": "qs_120.csv", "rate_mm_min": 120},
                {"kind": "dynamic", "file": "dyn_25.csv", "preload_strain": 0.25,
                 "acceleration_amplitude_m_s2": 0.25)" + dyn_extra + "}]}";
  }
  fs::path dir_;
};

}  // namespace

TEST_F(Campaign, ReadsGoodManifest) {
  const auto c = cal::read_campaign(manifest(good()));
  EXPECT_DOUBLE_EQ(c.specimen.area(), 6400.0);
  EXPECT_DOUBLE_EQ(c.specimen.density, 6.5e-11);
  ASSERT_EQ(c.quasi_static.size(), 1u);
  ASSERT_EQ(c.dynamic.size(), 1u);
  EXPECT_EQ(c.quasi_static_calibration(), &c.quasi_static[0]);
  EXPECT_EQ(c.dynamic_calibration(), &c.dynamic[0]);
  EXPECT_DOUBLE_EQ(c.quasi_static[0].rate, 2.0);  // mm/s
  EXPECT_DOUBLE_EQ(c.quasi_static[0].record.strain[20], 60.0 / 80.0);
  EXPECT_DOUBLE_EQ(c.quasi_static[0].record.stress[20], (0.05 * 3600 + 5) / 6400.0);
  EXPECT_EQ(c.quasi_static[0].record.line[0], 2);  // first data row is line 2
  EXPECT_DOUBLE_EQ(c.dynamic[0].moduli.storage[1], 0.045);  // MPa
  EXPECT_DOUBLE_EQ(c.dynamic[0].acceleration_amplitude, 250.0);  // mm/s^2
}

TEST_F(Campaign, ConvertsStiffnessAndPhase) {
  write("dyn_25.csv", "frequency_Hz,dynamic_stiffness_N_per_mm,phase_deg\n1,4,10\n2,5,12\n4,6,14\n");
  const auto c = cal::read_campaign(manifest(good()));
  // E = k t / A = 5 * 80 / 6400 MPa; E' = E cos(12 deg).
  EXPECT_NEAR(c.dynamic[0].moduli.storage[1], 5.0 * 80 / 6400 * std::cos(12 * std::numbers::pi / 180), 1e-15);
  EXPECT_NEAR(c.dynamic[0].moduli.loss[1], 5.0 * 80 / 6400 * std::sin(12 * std::numbers::pi / 180), 1e-15);
}

TEST_F(Campaign, DefaultAndExplicitUse) {
  const std::string text = R"({"specimen": {"length_mm": 80, "width_mm": 80, "thickness_mm": 80, "density_kg_m3": 65},
      "tests": [{"kind": "quasi_static", "file": "qs_120.csv", "rate_mm_min": 120, "name": "a"},
                {"kind": "quasi_static", "file": "qs_120.csv", "rate_mm_min": 120, "use": "calibration", "lateral": "constrained"}]})";
  const auto c = cal::read_campaign(manifest(text));
  EXPECT_EQ(c.quasi_static[0].use, cal::TestUse::validation);
  EXPECT_EQ(c.quasi_static_calibration(), &c.quasi_static[1]);
  EXPECT_EQ(c.quasi_static[1].lateral, cal::Lateral::constrained);
  EXPECT_EQ(c.dynamic_calibration(), nullptr);
}

TEST_F(Campaign, SeveralQuasiStaticCalibrationTestsOneDynamic) {
  // Several rates may calibrate (the first listed carries the paper's method); a second dynamic one is an error.
  const std::string text = R"({"specimen": {"length_mm": 80, "width_mm": 80, "thickness_mm": 80, "density_kg_m3": 65},
      "tests": [{"kind": "quasi_static", "file": "qs_120.csv", "rate_mm_min": 120, "name": "v"},
                {"kind": "quasi_static", "file": "qs_120.csv", "rate_mm_min": 120, "use": "calibration", "name": "a"},
                {"kind": "quasi_static", "file": "qs_120.csv", "rate_mm_min": 30, "use": "calibration", "name": "b"}]})";
  const auto c = cal::read_campaign(manifest(text));
  EXPECT_EQ(c.quasi_static_calibration(), &c.quasi_static[1]);
  const auto all = c.quasi_static_calibration_tests();
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0], &c.quasi_static[1]);
  EXPECT_EQ(all[1], &c.quasi_static[2]);
  EXPECT_EQ(c.quasi_static[0].use, cal::TestUse::validation);
  const std::string two_dynamic = R"({"specimen": {"length_mm": 80, "width_mm": 80, "thickness_mm": 80, "density_kg_m3": 65},
      "tests": [{"kind": "dynamic", "file": "dyn_25.csv", "preload_strain": 0.25, "acceleration_amplitude_m_s2": 0.25, "use": "calibration"},
                {"kind": "dynamic", "file": "dyn_25.csv", "preload_strain": 0.4, "acceleration_amplitude_m_s2": 0.25, "use": "calibration"}]})";
  const std::string m = error_of(two_dynamic);
  EXPECT_NE(m.find("a second dynamic calibration test"), std::string::npos) << m;
  EXPECT_NE(m.find("campaign.json"), std::string::npos) << m;
}

TEST_F(Campaign, BadManifestKeysNameFileAndKey) {
  auto expect = [&](const std::string& text, const std::string& key) {
    const std::string m = error_of(text);
    EXPECT_NE(m.find("campaign.json"), std::string::npos) << m;
    EXPECT_NE(m.find(key), std::string::npos) << m;
  };
  std::string t = good();
  expect(std::string(t).replace(t.find("thickness_mm"), 12, "height_mm"), "height_mm");   // mismatched specimen key
  expect(std::string(t).replace(t.find("\"tests\""), 7, "\"test\""), "test");              // misspelt top-level key
  expect(std::string(t).replace(t.find("\"rate_mm_min\": 120"), 18, "\"rate_mm_min\": -1"), "rate_mm_min");
  expect(good(R"(, "lateral": "free")"), "lateral");                                        // not for dynamic tests
  expect(good(R"(, "use": "both")"), "use");
  expect(std::string(t).replace(t.find("quasi_static"), 12, "quasistatic"), "kind");
  expect("{\"specimen\": {,}", "campaign.json:1:");                                         // JSON syntax: line 1
}

TEST_F(Campaign, BadCsvNamesFileAndLine) {
  auto expect = [&](const std::string& file, const std::string& text, const std::vector<std::string>& parts) {
    write(file, text);
    const std::string m = error_of(good());
    for (const auto& p : parts) EXPECT_NE(m.find(p), std::string::npos) << m;
    SetUp();  // restore the good files
  };
  expect("qs_120.csv", "time_s,displacement_mm,force_kN\n0,0,0\n1,1,1\n", {"qs_120.csv", "force_kN"});  // other unit
  expect("qs_120.csv", "time_s,displacment_mm,force_N\n0,0,0\n", {"qs_120.csv", "displacment_mm"});   // misspelt
  expect("qs_120.csv", "time_s,displacement_mm,force_N\n0,0,0\n1,,1\n", {"qs_120.csv", ":3"});        // empty cell
  expect("qs_120.csv", "time_s,displacement_mm,force_N\n0,0,0\n1,nan,1\n", {"qs_120.csv", ":3"});     // NaN
  expect("qs_120.csv", "time_s,displacement_mm,force_N\n0,0,0\n0,1,1\n", {"qs_120.csv", "line 3"});   // time not increasing
  expect("dyn_25.csv", "frequency_Hz,storage_modulus_kPa,loss_modulus_kPa\n1,40,10\n2,45,12\n",
         {"dyn_25.csv", "at least 3"});
  expect("dyn_25.csv", "frequency_Hz,storage_modulus_kPa,loss_modulus_kPa\n1,40,10\n-2,45,12\n3,48,13\n",
         {"dyn_25.csv:3", "frequency_Hz"});
  expect("dyn_25.csv", "frequency_Hz,dynamic_modulus_kPa,phase_deg\n1,40,10\n2,45,95\n3,48,13\n",
         {"dyn_25.csv:3", "phase_deg"});
  expect("dyn_25.csv", "frequency_Hz,dynamic_modulus_MPa,phase_deg\n1,40,10\n2,45,9\n3,48,13\n",
         {"dyn_25.csv", "dynamic_modulus_MPa"});
}

TEST_F(Campaign, MissingTestFileIsNamed) {
  fs::remove(dir_ / "dyn_25.csv");
  const std::string m = error_of(good());
  EXPECT_NE(m.find("dyn_25.csv"), std::string::npos) << m;
}

// Protocol keys (README "Protocol keys"): absent -> documented defaults; given -> read in their units.
TEST_F(Campaign, ProtocolKeysDefaultsAndValues) {
  const auto d = cal::read_campaign(manifest(good()));
  EXPECT_EQ(d.quasi_static[0].prior.preflex_cycles, 0);
  EXPECT_TRUE(d.quasi_static[0].lift_off);
  const cal::DynamicTest& dd = d.dynamic[0];
  EXPECT_EQ(dd.cycles, 20);
  EXPECT_EQ(dd.fit_cycles, 10);
  EXPECT_DOUBLE_EQ(dd.dwell_s, 0.0);
  EXPECT_TRUE(dd.amplitude_peak_to_peak);
  EXPECT_FALSE(dd.lift_off);
  EXPECT_EQ(dd.prior.preflex_cycles, 0);
  const auto c = cal::read_campaign(manifest(good(
      R"(, "amplitude_convention": "peak", "dwell_before_sweep_s": 5, "cycles": 8, "fit_cycles": 4, "preflex_cycles": 3,
         "preflex_strain": 0.6, "rest_between_tests_s": 60, "lift_off": true, "preload_rate_mm_min": 12)")));
  const cal::DynamicTest& t = c.dynamic[0];
  EXPECT_FALSE(t.amplitude_peak_to_peak);
  EXPECT_DOUBLE_EQ(t.dwell_s, 5.0);
  EXPECT_EQ(t.cycles, 8);
  EXPECT_EQ(t.fit_cycles, 4);
  EXPECT_EQ(t.prior.preflex_cycles, 3);
  EXPECT_DOUBLE_EQ(t.prior.preflex_strain, 0.6);
  EXPECT_DOUBLE_EQ(t.prior.rest_s, 60.0);
  EXPECT_TRUE(t.lift_off);
  EXPECT_DOUBLE_EQ(t.preload_rate_mm_min, 12.0);
  EXPECT_FALSE(cal::read_campaign(manifest(good(R"(, "amplitude_is": "peak")"))).dynamic[0].amplitude_peak_to_peak);
}

TEST_F(Campaign, BadProtocolKeysNameTheKey) {
  auto expect = [&](const std::string& extra, const std::string& key) {
    const std::string m = error_of(good(extra));
    EXPECT_NE(m.find("campaign.json"), std::string::npos) << m;
    EXPECT_NE(m.find(key), std::string::npos) << extra << " -> " << m;
  };
  expect(R"(, "amplitude_convention": "rms")", "amplitude_convention");
  expect(R"(, "amplitude_convention": "peak", "amplitude_is": "peak")", "amplitude_is");
  expect(R"(, "dwell_before_sweep_s": -1)", "dwell_before_sweep_s");
  expect(R"(, "cycles": 0)", "cycles");
  expect(R"(, "cycles": 2.5)", "cycles");
  expect(R"(, "cycles": 8, "fit_cycles": 9)", "fit_cycles");
  expect(R"(, "cycles": 8)", "cycles");  // fewer than the default fit_cycles 10
  expect(R"(, "preflex_cycles": -1)", "preflex_cycles");
  expect(R"(, "preflex_cycles": 2, "preflex_strain": 1.2)", "preflex_strain");
  expect(R"(, "preflex_strain": 0.5)", "preflex_strain");  // without preflex cycles
  expect(R"(, "rest_between_tests_s": -3)", "rest_between_tests_s");
  expect(R"(, "lift_off": "yes")", "lift_off");
  expect(R"(, "dwell_s": 5)", "dwell_s");  // unknown key
  const std::string t = good();
  const std::string qs = std::string(t).replace(t.find("\"rate_mm_min\": 120"), 18, "\"rate_mm_min\": 120, \"lift_off\": 1");
  EXPECT_NE(error_of(qs).find("lift_off"), std::string::npos) << error_of(qs);
  const std::string qs_dwell =
      std::string(t).replace(t.find("\"rate_mm_min\": 120"), 18, "\"rate_mm_min\": 120, \"dwell_before_sweep_s\": 1");
  EXPECT_NE(error_of(qs_dwell).find("dwell_before_sweep_s"), std::string::npos) << error_of(qs_dwell);
}
