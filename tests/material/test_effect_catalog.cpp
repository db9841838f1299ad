// Requirement: the effect catalogue is self-describing (every parameter has a unit-carrying name, a
// default inside its bounds), apply_effects converts file units and stacks effects in order, and bad
// input (unknown kind or parameter, out-of-range value, wrong order) is an InputError naming it.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "material/effect_catalog.hpp"
#include "material/effect_friction.hpp"
#include "material/effect_mullins.hpp"
#include "material/effect_pneumatic.hpp"
#include "io/input_error.hpp"
#include "tests/material/test_effect_support.hpp"

namespace cushion::material {
namespace {

/// The message of the InputError thrown by f ("" if none).
template <class Fn>
std::string input_error(Fn f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::vector<EffectSpec> all_effects() {
  return {{"strain_dependent_prony", {{"coefficient_c", 1.2}}},
          {"pneumatic", {{"drainage_length_mm", 40.0}, {"permeability_mm2", 2e-4}}},
          {"friction", {{"stiffness_kPa", 10.0}, {"yield_stress_kPa", 0.2}, {"hardening_kPa", 3.0}}},
          {"mullins", {{"r", 2.0}, {"m_kPa", 0.2}, {"beta", 0.2}}},
          {"stiffness_damping", {{"beta_s", 1e-3}}}};
}

TEST(EffectCatalog, EveryEntryIsSelfDescribing) {
  const std::set<std::string> expected{"pneumatic", "friction", "mullins", "strain_dependent_prony", "stiffness_damping"};
  std::set<std::string> kinds;
  for (const EffectInfo& e : effect_catalog()) {
    kinds.insert(e.kind);
    EXPECT_FALSE(e.description.empty()) << e.kind;
    EXPECT_FALSE(e.parameters.empty()) << e.kind;
    EXPECT_EQ(find_effect(e.kind), &e);
    // damage parameters: both or neither, each a parameter of the effect; a recoverable softening only beside them
    EXPECT_EQ(e.damage_limit_parameter.empty(), e.damage_strain_parameter.empty()) << e.kind;
    EXPECT_TRUE(e.recoverable_softening_parameter.empty() || !e.damage_limit_parameter.empty()) << e.kind;
    for (const std::string& name :
         {e.damage_limit_parameter, e.damage_strain_parameter, e.recoverable_softening_parameter})
      if (!name.empty()) {
        EXPECT_TRUE(
            std::any_of(e.parameters.begin(), e.parameters.end(), [&](const auto& p) { return p.name == name; }))
            << e.kind << ": " << name;
      }
    for (const EffectParameterInfo& p : e.parameters) {
      EXPECT_TRUE(p.min_exclusive ? p.default_value > p.min : p.default_value >= p.min) << p.name;
      EXPECT_LE(p.default_value, p.max) << p.name;
      if (p.log_scale) {  // positive, or 0 switches a branch off and a fit starts at a positive fit_start or second_start,
                          // or at diagnose's damage start
        EXPECT_TRUE(p.min > 0.0 || p.min_exclusive || p.fit_start > 0.0 || p.second_start.value_or(0.0) > 0.0 ||
                    p.name == e.damage_limit_parameter)
            << p.name;
      }
      if (p.fit_start > 0.0) {
        EXPECT_GT(p.fit_start, p.min) << p.name;
        EXPECT_LE(p.fit_start, p.max) << p.name;
      }
      EXPECT_FALSE(p.description.empty()) << p.name;
      if (p.diagnose_value) {  // held by diagnose at another admissible value than the default, not fitted
        EXPECT_FALSE(p.fit) << p.name;
        EXPECT_GE(*p.diagnose_value, p.min) << p.name;
        EXPECT_LE(*p.diagnose_value, p.max) << p.name;
        EXPECT_NE(*p.diagnose_value, p.default_value) << p.name;
      }
      if (p.polished_only) {
        EXPECT_FALSE(p.fit) << p.name;  // held by the singles, fitted in the polish only
      }
      if (p.named_value) {  // a held parameter's other admissible value, tried on the named single only
        EXPECT_FALSE(p.fit) << p.name;
        EXPECT_GE(*p.named_value, p.min) << p.name;
        EXPECT_LE(*p.named_value, p.max) << p.name;
        EXPECT_NE(*p.named_value, p.diagnose_value.value_or(p.default_value)) << p.name;
      }
      if (!p.scan_with.empty()) {  // a fitted partner of the same effect, not the parameter itself
        EXPECT_TRUE(p.fit) << p.name;
        EXPECT_NE(p.scan_with, p.name);
        const auto partner = std::find_if(e.parameters.begin(), e.parameters.end(),
                                          [&p](const EffectParameterInfo& q) { return q.name == p.scan_with; });
        ASSERT_NE(partner, e.parameters.end()) << p.name << " scan_with " << p.scan_with;
        EXPECT_TRUE(partner->fit) << p.scan_with;
      }
      for (const std::string* branch : {&p.fitted_only_without, &p.fitted_only_with}) {
        if (branch->empty()) continue;  // a fitted parameter held by a log-scale branch switch of the same effect
        EXPECT_TRUE(p.fit) << p.name;
        const auto other = std::find_if(e.parameters.begin(), e.parameters.end(),
                                        [branch](const EffectParameterInfo& q) { return q.name == *branch; });
        ASSERT_NE(other, e.parameters.end()) << p.name << " held by " << *branch;
        EXPECT_TRUE(other->log_scale && other->min == 0.0) << *branch << ": its 0 must switch a branch off";
      }
    }
  }
  EXPECT_EQ(kinds, expected);
  EXPECT_EQ(find_effect("nothing"), nullptr);
}

TEST(EffectCatalog, DefaultsBuildOnEveryBase) {
  // Each effect alone with its defaults builds on the viscoelastic model (and, except the Prony one,
  // on the elastic base) and integrates an increment.
  const auto foam = test::effect_test_foam();
  const auto visco = test::effect_test_visco();
  for (const EffectInfo& e : effect_catalog()) {
    for (bool on_visco : {true, false}) {
      if (e.needs_viscoelastic && !on_visco) continue;
      const std::shared_ptr<const Material> base = on_visco ? std::shared_ptr<const Material>(visco) : foam;
      const auto m = apply_effects(base, foam, {{e.kind, {}}});
      std::vector<double> state(m->state_size()), next(m->state_size());
      m->initial_state(state);
      const PointResponse r = m->integrate(Mat3::Identity(), Vec3(0.8, 1.0, 1.0).asDiagonal().toDenseMatrix(), 0.1,
                                           state, next);
      EXPECT_NE(r.status, Status::failed) << e.kind << ": " << r.message;
      EXPECT_NE(m->describe().find(base->describe()), std::string::npos) << e.kind;
    }
  }
}

TEST(EffectCatalog, FullStackHasConsistentStateAndTangent) {
  // All five effects on the Table 3 model: state = visco (36) + friction (6) + mullins (1) + pneumatic (1); the
  // increment tangent of the whole stack matches finite differences (1e-6 relative) at a random F
  // with a non-trivial state.
  const auto foam = test::effect_test_foam();
  const auto visco = test::effect_test_visco();
  const auto m = apply_effects(visco, foam, all_effects());
  EXPECT_EQ(m->state_size(), visco->state_size() + 6 + 1 + 1);
  std::mt19937 rng(8);
  std::vector<double> state(m->state_size()), next(m->state_size());
  m->initial_state(state);
  Mat3 F_old = Mat3::Identity();
  for (int k = 0; k < 3; ++k) {
    const Mat3 F = test::random_F(rng, 0.25);
    m->integrate(F_old, F, 0.02, state, next);
    state.swap(next), F_old = F;
  }
  EXPECT_LT(test::increment_tangent_error(*m, F_old, test::random_F(rng, 0.25), 0.02, state), 1e-6);
}

TEST(EffectCatalog, FileUnitsAreConverted) {
  // Pa s -> MPa s, kPa -> MPa, mm and mm^2 unchanged; omitted parameters take the defaults. 1e-15 relative.
  const auto foam = test::effect_test_foam();
  const auto air = apply_effects(foam, foam, {{"pneumatic", {{"drainage_length_mm", 25.0}}}});
  const auto& p = dynamic_cast<const PneumaticEffect&>(*air).parameters();
  EXPECT_DOUBLE_EQ(p.drainage_length, 25.0);
  EXPECT_NEAR(p.air_viscosity, 1.8e-11, 1e-26);
  EXPECT_DOUBLE_EQ(p.permeability, 1e-3);
  const auto slide = apply_effects(foam, foam, {{"friction", {{"stiffness_kPa", 12.0}, {"yield_stress_kPa", 0.3}}}});
  const auto& q = dynamic_cast<const FrictionEffect&>(*slide).parameters();
  EXPECT_NEAR(q.stiffness, 0.012, 1e-17);
  EXPECT_NEAR(q.yield_stress, 3e-4, 1e-19);
  const auto soft = apply_effects(foam, foam, {{"mullins", {{"m_kPa", 0.5}}}});
  EXPECT_NEAR(dynamic_cast<const MullinsEffect&>(*soft).parameters().m, 5e-4, 1e-19);
  EXPECT_EQ(apply_effects(foam, foam, {}), foam);  // no effects: the base model itself
}

TEST(EffectCatalog, DescriptionsUseTheFileUnits) {
  // describe() is printed to the user (cushion point): kPa and Pa s as in the material file, never MPa.
  const auto foam = test::effect_test_foam();
  const auto m = apply_effects(foam, foam, {{"friction", {{"stiffness_kPa", 12.0}, {"yield_stress_kPa", 0.3}}},
                                            {"mullins", {{"m_kPa", 0.5}}}, {"pneumatic", {}}});
  const std::string d = m->describe();
  EXPECT_EQ(d.find("MPa"), std::string::npos) << d;
  EXPECT_NE(d.find("k = 12 kPa, s_y = 0.3 kPa"), std::string::npos) << d;
  EXPECT_NE(d.find("m = 0.5 kPa"), std::string::npos) << d;
  EXPECT_NE(d.find("eta_air = 1.8e-05 Pa s"), std::string::npos) << d;
  EXPECT_NE(d.find(" kPa, alpha="), std::string::npos) << d;  // the hyperfoam base
}

TEST(EffectCatalog, EffectsWrapInListOrder) {
  // The first listed effect is innermost.
  const auto foam = test::effect_test_foam();
  const auto m = apply_effects(foam, foam, {{"friction", {}}, {"pneumatic", {}}});
  const auto& outer = dynamic_cast<const PneumaticEffect&>(*m);
  EXPECT_NE(dynamic_cast<const FrictionEffect*>(&outer.inner()), nullptr);
}

TEST(EffectCatalog, BadInputIsAnInputErrorNamingTheKey) {
  const auto foam = test::effect_test_foam();
  const auto visco = test::effect_test_visco();
  auto apply = [&](std::shared_ptr<const Material> base, std::vector<EffectSpec> effects) {
    return input_error([&] { apply_effects(base, foam, effects, "foam.json"); });
  };
  std::string e = apply(foam, {{"friction", {}}, {"pnuematic", {}}});
  EXPECT_NE(e.find("foam.json: effects[1].kind"), std::string::npos) << e;
  EXPECT_NE(e.find("pnuematic"), std::string::npos) << e;
  e = apply(foam, {{"pneumatic", {{"permeabilty_mm2", 1e-3}}}});
  EXPECT_NE(e.find("effects[0].permeabilty_mm2: unknown parameter"), std::string::npos) << e;
  EXPECT_NE(e.find("permeability_mm2"), std::string::npos) << e;  // the known names are listed
  e = apply(foam, {{"mullins", {{"r", 1.0}}}});
  EXPECT_NE(e.find("effects[0].r: must be > 1"), std::string::npos) << e;
  e = apply(foam, {{"friction", {{"yield_stress_kPa", -1.0}}}});
  EXPECT_NE(e.find("effects[0].yield_stress_kPa: must be > 0"), std::string::npos) << e;
  e = apply(foam, {{"stiffness_damping", {{"beta_s", std::nan("")}}}});
  EXPECT_NE(e.find("effects[0].beta_s"), std::string::npos) << e;
  e = apply(foam, {{"friction", {}}, {"friction", {}}});
  EXPECT_NE(e.find("effects[1].kind: effect 'friction' is listed twice"), std::string::npos) << e;
  e = apply(foam, {{"strain_dependent_prony", {}}});
  EXPECT_NE(e.find("effects[0].kind: 'strain_dependent_prony' needs a viscoelastic"), std::string::npos) << e;
  e = apply(visco, {{"friction", {}}, {"strain_dependent_prony", {}}});
  EXPECT_NE(e.find("effects[1].kind"), std::string::npos) << e;
  EXPECT_EQ(apply(visco, {{"strain_dependent_prony", {}}, {"friction", {}}}), "");
  // A Mullins relaxation share > 0 edits the Prony memory beneath it: mullins first, on a Prony material.
  e = apply(visco, {{"friction", {}}, {"mullins", {{"relaxation_share", 1.0}}}});
  EXPECT_NE(e.find("foam.json: effects[1].relaxation_share: > 0 needs a viscoelastic"), std::string::npos) << e;
  e = apply(foam, {{"mullins", {{"relaxation_share", 0.5}}}});
  EXPECT_NE(e.find("effects[0].relaxation_share: > 0"), std::string::npos) << e;
  e = apply(visco, {{"mullins", {{"relaxation_share", 1.5}}}});
  EXPECT_NE(e.find("effects[0].relaxation_share: must be >= 0 and <= 1"), std::string::npos) << e;
  EXPECT_EQ(apply(visco, {{"mullins", {{"relaxation_share", 1.0}}}, {"friction", {}}}), "");
  // ... or directly over strain_dependent_prony (itself first: a Prony memory), in composition_order's order.
  EXPECT_EQ(apply(visco, {{"strain_dependent_prony", {}}, {"mullins", {{"relaxation_share", 1.0}}}}), "");
  e = apply(visco, {{"mullins", {{"relaxation_share", 1.0}}}, {"strain_dependent_prony", {}}});
  EXPECT_NE(e.find("effects[1].kind: 'strain_dependent_prony' needs a viscoelastic"), std::string::npos) << e;
  const std::vector<EffectSpec> ordered =
      composition_order({{"friction", {}}, {"mullins", {{"relaxation_share", 1.0}}}, {"strain_dependent_prony", {}}});
  ASSERT_EQ(ordered.size(), 3u);
  EXPECT_EQ(ordered[0].kind, "strain_dependent_prony");
  EXPECT_EQ(ordered[1].kind, "mullins");
  EXPECT_EQ(apply(visco, ordered), "");
  // validate_effects alone (no model needed) gives the same messages.
  e = input_error([] { validate_effects({{"mullins", {{"m", 1.0}}}}, "x.json"); });
  EXPECT_NE(e.find("x.json: effects[0].m: unknown parameter of 'mullins'"), std::string::npos) << e;
}

}  // namespace
}  // namespace cushion::material
