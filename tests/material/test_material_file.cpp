// Material files: round trip, unit conversions, the shipped paper_table3.json, and every bad-input
// case of the issue (missing key, wrong type, N = 0 and 7, negative tau, NaN, unknown key, ...).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "io/input_error.hpp"
#include "material/io/material_file.hpp"
#include "material/io/protocol_file.hpp"
#include "material/stability.hpp"

namespace fs = std::filesystem;
namespace cm = cushion::material;

namespace {

fs::path scratch_dir() {
  const fs::path dir = fs::temp_directory_path() / ("cushion_test_material_file_" +
                                                    std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
  fs::create_directories(dir);
  return dir;
}

const std::string good_hyperfoam = R"({
  "name": "foam",
  "density_kg_m3": 65,
  "hyperfoam": {"terms": [{"mu_kPa": 10, "alpha": 10, "nu": 0.1}, {"mu_kPa": 0.1, "alpha": -2, "nu": 0.1}]},
  "viscoelastic": {"moduli": "long_term", "prony": [{"g": 0.3, "tau_s": 0.1}, {"g": 0.2, "tau_s": 10}]}
})";

/// The InputError message for material JSON `text` read from a file named foam.json ("" if accepted).
std::string error_of(const std::string& text) {
  try {
    cm::parse_material_json(text, "foam.json");
  } catch (const cushion::InputError& e) {
    return e.what();
  }
  return {};
}

/// Replaces the first occurrence of `from` in the good file by `to`.
std::string good_with(const std::string& from, const std::string& to) {
  std::string text = good_hyperfoam;
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

void expect_error(const std::string& text, const std::vector<std::string>& parts) {
  const std::string message = error_of(text);
  ASSERT_FALSE(message.empty()) << "accepted: " << text;
  EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
  EXPECT_EQ(message.rfind("foam.json", 0), 0u) << message;
  for (const auto& p : parts) EXPECT_NE(message.find(p), std::string::npos) << "'" << p << "' not in: " << message;
}

}  // namespace

TEST(MaterialFile, ReadsAndConvertsUnits) {
  const cm::MaterialDefinition d = cm::parse_material_json(good_hyperfoam, "foam.json");
  EXPECT_EQ(d.spec.name, "foam");
  EXPECT_DOUBLE_EQ(d.spec.density, 6.5e-11);  // 65 kg/m^3 in t/mm^3
  ASSERT_EQ(d.spec.hyperfoam.size(), 2u);
  EXPECT_DOUBLE_EQ(d.spec.hyperfoam[0].mu, 0.010);  // kPa -> MPa
  EXPECT_DOUBLE_EQ(d.spec.hyperfoam[1].alpha, -2.0);
  ASSERT_EQ(d.spec.prony.size(), 2u);
  EXPECT_DOUBLE_EQ(d.spec.prony[1].tau, 10.0);
  ASSERT_TRUE(d.model);
  EXPECT_EQ(d.model->state_size(), 18u);  // Viscoelastic: 6 (S_inf) + 6 per term
  EXPECT_DOUBLE_EQ(d.elastic->initial_shear_modulus(), 0.0101);
}

TEST(MaterialFile, AbsolutePronyIsConvertedToRelative) {
  const std::string text = R"({"neo_hookean": {"mu_kPa": 10, "lambda_kPa": 5},
    "viscoelastic": {"moduli": "instantaneous", "absolute": {"E_inf_kPa": 2, "terms": [{"E_kPa": 6, "tau_s": 1}, {"E_kPa": 2, "tau_s": 5}]}}})";
  const cm::MaterialDefinition d = cm::parse_material_json(text, "abs.json");
  ASSERT_EQ(d.spec.prony.size(), 2u);
  EXPECT_DOUBLE_EQ(d.spec.prony[0].g, 0.6);  // g_i = E_i / (E_inf + sum E)
  EXPECT_DOUBLE_EQ(d.spec.prony[1].g, 0.2);
  EXPECT_EQ(d.spec.moduli, cm::ModuliConvention::instantaneous);
  EXPECT_EQ(d.spec.base, cm::MaterialSpec::Base::neo_hookean);
  EXPECT_DOUBLE_EQ(d.spec.neo_lambda, 0.005);
}

TEST(MaterialFile, WriteReadRoundTrip) {
  cm::MaterialSpec spec;
  spec.name = "round trip";
  spec.description = "numbers with \"quotes\" and units";
  spec.density = 4.7e-11;
  spec.hyperfoam = {{0.0123456789, 9.87654321, 0.0}, {-0.001, -3.5, 0.0}, {0.02, 2.0, 0.0}};
  spec.prony = {{0.1, 0.01}, {0.25, 1.0}, {1.0 / 3.0, 100.0}};
  spec.moduli = cm::ModuliConvention::instantaneous;
  const fs::path file = scratch_dir() / "round.json";
  cm::write_material_file(spec, file);
  const cm::MaterialDefinition d = cm::read_material_file(file);
  EXPECT_EQ(d.spec.name, spec.name);
  EXPECT_EQ(d.spec.description, spec.description);
  EXPECT_NEAR(d.spec.density, spec.density, 1e-15 * spec.density);
  ASSERT_EQ(d.spec.hyperfoam.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {  // kPa conversion may cost one rounding
    EXPECT_NEAR(d.spec.hyperfoam[i].mu, spec.hyperfoam[i].mu, 1e-15 * std::abs(spec.hyperfoam[i].mu));
    EXPECT_EQ(d.spec.hyperfoam[i].alpha, spec.hyperfoam[i].alpha);
    EXPECT_EQ(d.spec.hyperfoam[i].nu, spec.hyperfoam[i].nu);
    EXPECT_EQ(d.spec.prony[i].g, spec.prony[i].g);
    EXPECT_EQ(d.spec.prony[i].tau, spec.prony[i].tau);
  }
  EXPECT_EQ(d.spec.moduli, spec.moduli);

  cm::MaterialSpec neo;
  neo.base = cm::MaterialSpec::Base::neo_hookean;
  neo.neo_mu = 0.01;
  neo.neo_lambda = 0.02;
  cm::write_material_file(neo, file);
  const cm::MaterialDefinition n = cm::read_material_file(file);
  EXPECT_NEAR(n.spec.neo_mu, 0.01, 1e-17);
  EXPECT_TRUE(n.spec.prony.empty());
  EXPECT_EQ(n.spec.density, 0.0);
}

TEST(MaterialFile, BadInputNamesFileAndKey) {
  // Missing field.
  expect_error(good_with(R"(, "nu": 0.1}, {"mu_kPa": 0.1)", R"(}, {"mu_kPa": 0.1)"), {"hyperfoam.terms[0].nu", "missing"});
  expect_error(R"({"name": "x"})", {"hyperfoam", "neo_hookean"});
  expect_error(good_with(R"("moduli": "long_term", )", ""), {"viscoelastic.moduli", "missing"});
  // Wrong type.
  expect_error(good_with(R"("alpha": 10)", R"("alpha": "10")"), {"hyperfoam.terms[0].alpha", "must be a number", "a string"});
  expect_error(good_with(R"("density_kg_m3": 65)", R"("density_kg_m3": [65])"), {"density_kg_m3", "must be a number"});
  expect_error(good_with(R"("terms": [)", R"("terms": {"a": [)") + "}", {"foam.json"});
  // N = 0 and N = 7.
  expect_error(R"({"hyperfoam": {"terms": []}})", {"hyperfoam.terms", "1..6", "found 0"});
  std::string seven = R"({"hyperfoam": {"terms": [)";
  for (int i = 0; i < 7; ++i) seven += std::string(i ? "," : "") + R"({"mu_kPa": 1, "alpha": 2, "nu": 0})";
  expect_error(seven + "]}}", {"hyperfoam.terms", "1..6", "found 7"});
  // Negative tau, sum g >= 1, out-of-range values.
  expect_error(good_with(R"("tau_s": 10)", R"("tau_s": -10)"), {"viscoelastic.prony[1].tau_s", "> 0"});
  expect_error(good_with(R"("g": 0.2)", R"("g": 0.7)"), {"viscoelastic.prony", "sum of g"});
  expect_error(good_with(R"("alpha": 10)", R"("alpha": 0)"), {"hyperfoam.terms[0].alpha", "non-zero"});
  expect_error(good_with(R"("nu": 0.1})", R"("nu": 0.5})"), {"hyperfoam.terms[0].nu", "[0, 0.5)"});
  expect_error(good_with(R"("density_kg_m3": 65)", R"("density_kg_m3": -65)"), {"density_kg_m3", "> 0"});
  expect_error(good_with(R"("long_term")", R"("longterm")"), {"viscoelastic.moduli", "did you mean 'long_term'"});
  // NaN (not JSON: a syntax error naming the line, column and key) and overflow to infinity.
  expect_error(good_with(R"("mu_kPa": 10)", R"("mu_kPa": NaN)"), {"foam.json:4:", "mu_kPa"});
  expect_error(good_with(R"("mu_kPa": 10)", R"("mu_kPa": 1e999)"), {"mu_kPa"});
  // Unknown key, with a suggestion.
  expect_error(good_with(R"("density_kg_m3")", R"("density_kg_m")"), {"density_kg_m", "unknown key", "did you mean 'density_kg_m3'"});
  expect_error(good_with(R"("alpha": 10)", R"("alpha": 10, "beta": 1)"), {"hyperfoam.terms[0].beta", "unknown key"});
  // Both bases, both Prony forms.
  expect_error(good_with(R"("hyperfoam")", R"("neo_hookean": {"mu_kPa": 1, "lambda_kPa": 1}, "hyperfoam")"), {"exactly one"});
  expect_error(good_with(R"("prony")", R"("absolute": {"E_inf_kPa": 1, "terms": [{"E_kPa": 1, "tau_s": 1}]}, "prony")"), {"viscoelastic", "exactly one"});
  try {
    cm::read_material_file(scratch_dir() / "nothing.json");
    FAIL();
  } catch (const cushion::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("nothing.json"), std::string::npos);
  }
}

TEST(MaterialFile, ShippedPaperTable3IsValidAndDruckerStable) {
  const cm::MaterialDefinition d = cm::read_material_file(fs::path(CUSHION_SOURCE_DIR) / "cases/materials/paper_table3.json");
  EXPECT_FALSE(d.spec.description.empty());
  EXPECT_NEAR(d.spec.density, 6.5e-11, 1e-20);
  ASSERT_EQ(d.spec.hyperfoam.size(), 3u);
  // Table 3: E_inf 3.05 kPa, E_i = 23.9, 19.7, 8.99, 12.4, 8.14 kPa: g_i = E_i / 76.18 kPa.
  const std::vector<double> E = {23.9, 19.7, 8.99, 12.4, 8.14}, tau = {0.01, 0.1, 1, 10, 100};
  ASSERT_EQ(d.spec.prony.size(), 5u);
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_NEAR(d.spec.prony[i].g, E[i] / 76.18, 1e-12);
    EXPECT_EQ(d.spec.prony[i].tau, tau[i]);
  }
  const cm::StabilityReport stability = cm::check_stability(*d.elastic);
  EXPECT_TRUE(stability.stable()) << stability.summary();
}

TEST(ProtocolFile, ReadsSegmentsAndRejectsBadOnes) {
  const cm::Protocol p = cm::parse_protocol_json(R"({"platen": true, "segments": [
      {"ramp": {"target": -0.75, "duration_s": 30, "steps": 300}}, {"hold": {"duration_s": 2}},
      {"sine": {"amplitude": 0.01, "frequency_Hz": 2, "cycles": 1.5, "steps_per_cycle": 10}}]})", "p.json");
  EXPECT_TRUE(p.platen);
  ASSERT_EQ(p.segments.size(), 3u);
  EXPECT_EQ(p.segments[0].kind, cm::Segment::Kind::ramp);
  EXPECT_EQ(p.segments[0].target, -0.75);
  EXPECT_EQ(p.segments[0].steps, 300);
  EXPECT_EQ(p.segments[1].steps, 0);
  EXPECT_EQ(p.segments[2].steps, 15);  // 10 per cycle x 1.5 cycles
  auto error = [](const std::string& text) {
    try {
      cm::parse_protocol_json(text, "p.json");
    } catch (const cushion::InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error(R"({"segments": [{"sine": {"amplitude": 0.1, "frequency_Hz": 0, "cycles": 1}}]})")
                .find("p.json: segments[0].sine.frequency_Hz: must be > 0"), std::string::npos);
  EXPECT_NE(error(R"({"segments": [{"ramp": {"target": -0.5, "duration": 3}}]})").find("did you mean 'duration_s'"),
            std::string::npos);
  EXPECT_NE(error(R"({"segments": [{"hold": {"duration_s": 1, "steps": 2.5}}]})").find("segments[0].hold.steps"),
            std::string::npos);
  EXPECT_NE(error(R"({"segments": []})").find("segments"), std::string::npos);
  EXPECT_NE(error(R"({"segments": [{"ramp": {"target": 0, "duration_s": 1}, "hold": {"duration_s": 1}}]})").find("exactly one"),
            std::string::npos);
}

// Issue 16 (known before fuzzing): values past a physical range overflowed later instead of being rejected with the key
// named (mu_kPa 1e308 ran `cushion point` to exit 0 with -inf stresses).
TEST(MaterialFile, ValuesPastPhysicalBoundsAreRejected) {
  expect_error(good_with(R"("mu_kPa": 10)", R"("mu_kPa": 1e308)"),
               {"foam.json: hyperfoam.terms[0].mu_kPa: must be in [-1e9, 1e9] kPa, found 1e+308"});
  expect_error(good_with(R"("alpha": 10)", R"("alpha": 1e300)"), {"hyperfoam.terms[0].alpha", "[-100, 100]"});
  expect_error(good_with(R"("tau_s": 10)", R"("tau_s": 1e300)"), {"viscoelastic.prony[1].tau_s", "<= 1e9 s"});
  expect_error(good_with(R"("density_kg_m3": 65)", R"("density_kg_m3": 1e300)"), {"density_kg_m3", "<= 1e7"});
  expect_error(R"({"neo_hookean": {"mu_kPa": 1e308, "lambda_kPa": 1}})", {"neo_hookean.mu_kPa", "<= 1e6 kPa"});
  expect_error(R"({"neo_hookean": {"mu_kPa": 1, "lambda_kPa": 1e308}})", {"neo_hookean.lambda_kPa", "[-1e9, 1e9]"});
  expect_error(good_with(R"("prony": [{"g": 0.3, "tau_s": 0.1}, {"g": 0.2, "tau_s": 10}])",
                         R"("absolute": {"E_inf_kPa": 1e308, "terms": [{"E_kPa": 1, "tau_s": 1}]})"),
               {"viscoelastic.absolute.E_inf_kPa", "<= 1e6 kPa"});
  expect_error(good_with(R"("prony": [{"g": 0.3, "tau_s": 0.1}, {"g": 0.2, "tau_s": 10}])",
                         R"("absolute": {"E_inf_kPa": 1, "terms": [{"E_kPa": 1e308, "tau_s": 1}]})"),
               {"viscoelastic.absolute.terms[0].E_kPa", "<= 1e6 kPa"});
  // The bounds are generous: large fitted terms (`cushion fit` wrote 6.7e6 kPa) and a day-long relaxation time.
  EXPECT_EQ(error_of(good_with(R"("mu_kPa": 10)", R"("mu_kPa": 6.7e6)")), "");
  EXPECT_EQ(error_of(good_with(R"("tau_s": 10)", R"("tau_s": 86400)")), "");
}

// Issue 16 (known before fuzzing): a 1e308 control in a protocol was accepted and failed later in the driver.
TEST(ProtocolFile, ValuesPastPhysicalBoundsAreRejected) {
  auto error = [](const std::string& text) {
    try {
      cm::parse_protocol_json(text, "p.json");
    } catch (const cushion::InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(error(R"({"segments": [{"ramp": {"target": 1e308, "duration_s": 1}}]})"),
            "p.json: segments[0].ramp.target: must be in [-10, 10], found 1e+308");
  EXPECT_EQ(error(R"({"segments": [{"hold": {"duration_s": 1e300}}]})"),
            "p.json: segments[0].hold.duration_s: must be > 0 and <= 1e9 s, found 1e+300");
  EXPECT_NE(error(R"({"segments": [{"sine": {"amplitude": 1e308, "frequency_Hz": 1, "cycles": 1}}]})")
                .find("p.json: segments[0].sine.amplitude: must be in [0, 10]"), std::string::npos);
  EXPECT_NE(error(R"({"segments": [{"sine": {"amplitude": 0.1, "frequency_Hz": 1e308, "cycles": 1}}]})")
                .find("p.json: segments[0].sine.frequency_Hz: must be > 0 and <= 1e6 Hz"), std::string::npos);
  EXPECT_NE(error(R"({"segments": [{"sine": {"amplitude": 0.1, "frequency_Hz": 1, "cycles": 1e300}}]})")
                .find("p.json: segments[0].sine.cycles"), std::string::npos);
  EXPECT_EQ(error(R"({"segments": [{"ramp": {"target": -0.9, "duration_s": 1e9}}]})"), "");
}
