// Effects in material files: parsed against the catalogue, built on the model, written back.
#include <gtest/gtest.h>

#include <filesystem>

#include "io/input_error.hpp"
#include "material/io/material_file.hpp"

namespace mat = cushion::material;

namespace {
const std::string base = R"("hyperfoam": {"terms": [{"mu_kPa": 10, "alpha": 8, "nu": 0}]},
  "viscoelastic": {"moduli": "long_term", "prony": [{"g": 0.5, "tau_s": 0.1}]})";

std::string error_of(const std::string& text) {
  try {
    mat::parse_material_json(text, "foam.json");
  } catch (const cushion::InputError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(MaterialFileEffects, EffectsWrapTheModelAndAddTheirState) {
  const auto plain = mat::parse_material_json("{" + base + "}", "foam.json");
  const auto with = mat::parse_material_json("{" + base + R"(, "effects": [
      {"kind": "strain_dependent_prony", "coefficient_c": 1.2},
      {"kind": "friction", "stiffness_kPa": 5, "yield_stress_kPa": 0.1},
      {"kind": "mullins"}]})", "foam.json");
  ASSERT_EQ(with.spec.effects.size(), 3u);
  EXPECT_EQ(with.spec.effects[1].parameters.at("yield_stress_kPa"), 0.1);
  // friction adds E_p (6 doubles), mullins W_max (1); strain_dependent_prony reuses the Prony state.
  EXPECT_EQ(with.model->state_size(), plain.model->state_size() + 7);
}

TEST(MaterialFileEffects, RoundTripThroughTheWriter) {
  const auto def = mat::parse_material_json("{" + base + R"(, "effects": [{"kind": "pneumatic", "drainage_length_mm": 40}]})",
                                            "foam.json");
  const auto file = std::filesystem::temp_directory_path() / "cushion_effects_roundtrip.json";
  mat::write_material_file(def.spec, file);
  const auto back = mat::read_material_file(file);
  ASSERT_EQ(back.spec.effects.size(), 1u);
  EXPECT_EQ(back.spec.effects[0].kind, "pneumatic");
  EXPECT_EQ(back.spec.effects[0].parameters.at("drainage_length_mm"), 40.0);
  std::filesystem::remove(file);
}

TEST(MaterialFileEffects, BadEffectsNameTheKey) {
  EXPECT_NE(error_of("{" + base + R"(, "effects": [{"kind": "magic"}]})").find("effects[0].kind"), std::string::npos);
  const std::string misspelt = error_of("{" + base + R"(, "effects": [{"kind": "friction", "yield_kPa": 1}]})");
  EXPECT_NE(misspelt.find("yield_kPa"), std::string::npos) << misspelt;
  EXPECT_NE(misspelt.find("foam.json"), std::string::npos) << misspelt;
  const std::string range = error_of("{" + base + R"(, "effects": [{"kind": "mullins", "r": -3}]})");
  EXPECT_NE(range.find("effects[0].r"), std::string::npos) << range;
}
