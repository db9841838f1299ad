// separating_test.hpp: the tests diagnose proposes to tell two equally good models apart. Checked on the shipped
// control campaign (cases/hidden_effects/campaign_control: rates 30/120/480 mm/min, preloads 25 % and 40 %):
//  - identical models give separation 0 on every proposal (exact), and every proposal the campaign allows is run;
//  - an elastic hyperfoam against the same foam with stiffness-proportional damping: the separation of the dynamic
//    proposals from the time-domain runs (lab.hpp run_dynamic) agrees with the one computed here from the
//    frequency-domain complex tangents (fit_model.hpp model_dynamic_moduli, an independent code path), within 5 %
//    (the time-domain test has a finite excitation, the complex tangent none); the quasi-static proposals rank the
//    faster rate first (the damping stress grows with the rate).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>

#include "calibration/fit_model.hpp"
#include "calibration/separating_test.hpp"
#include "material/io/material_file.hpp"

namespace cc = cushion::calibration;
namespace cm = cushion::material;
namespace fs = std::filesystem;

namespace {

fs::path control() {
  return fs::path(CUSHION_SOURCE_DIR) / "cases" / "hidden_effects" / "campaign_control" / "campaign.json";
}

cm::MaterialSpec elastic_base() {
  cm::MaterialSpec s =
      cm::read_material_file(fs::path(CUSHION_SOURCE_DIR) / "cases" / "hidden_effects" / "base_material.json").spec;
  s.prony.clear();
  return s;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

const cc::SeparatingTest& named(const std::vector<cc::SeparatingTest>& v, const std::string& start) {
  for (const auto& t : v)
    if (t.name.rfind(start, 0) == 0) return t;
  throw std::runtime_error("no proposal named " + start);
}

}  // namespace

TEST(SeparatingTests, IdenticalModelsAreNotSeparated) {
  const cc::Campaign c = cc::read_campaign(control());
  const auto noise = cc::estimate_noise(c);
  const cm::MaterialDefinition m = cm::build_material(elastic_base(), "foam");
  const auto tests = cc::separating_tests(*m.model, *m.model, c, noise, {}, 100);
  // 5 quasi-static proposals, preloads 12.5 % and 55 %, two amplitudes
  ASSERT_EQ(tests.size(), 9u);
  for (const auto& t : tests) {
    EXPECT_TRUE(t.failure.empty()) << t.name << ": " << t.failure;
    EXPECT_EQ(t.separation, 0.0) << t.name;
  }
}

TEST(SeparatingTests, DampingSeparationMatchesTheFrequencyDomain) {
  const cc::Campaign c = cc::read_campaign(control());
  const auto noise = cc::estimate_noise(c);
  const cm::MaterialSpec a_spec = elastic_base();
  cm::MaterialSpec b_spec = a_spec;
  b_spec.effects.push_back({"stiffness_damping", {{"beta_s", 2e-3}}});
  const cm::MaterialDefinition a = cm::build_material(a_spec, "foam"), b = cm::build_material(b_spec, "damped foam");
  const auto tests = cc::separating_tests(*a.model, *b.model, c, noise, {}, 100);
  for (const auto& t : tests) std::printf("  %-100s %.4g\n", t.name.c_str(), t.separation);

  // The campaign's noise scales, as separating_test.hpp states them.
  std::vector<double> relative, phase;
  for (std::size_t j = 0; j < c.dynamic.size(); ++j) {
    const cc::TestNoise& n = noise[c.quasi_static.size() + j];
    double mean = 0.0;
    const auto& m = c.dynamic[j].moduli;
    for (std::size_t k = 0; k < m.frequency.size(); ++k)
      mean += std::abs(std::complex<double>(m.storage[k], m.loss[k]));
    relative.push_back(n.modulus / (mean / m.frequency.size()));
    phase.push_back(n.phase);
  }
  const double rel = median(relative), ph = median(phase);
  const std::vector<double>& f = c.dynamic.front().moduli.frequency;
  for (const auto& [preload, label] : {std::pair{0.125, "12.5"}, std::pair{0.55, "55"}}) {
    const cc::DynamicModuli ma = cc::model_dynamic_moduli(*a.model, *a.elastic, preload, f);
    const cc::DynamicModuli mb = cc::model_dynamic_moduli(*b.model, *b.elastic, preload, f);
    double sm = 0.0, sp = 0.0;
    for (std::size_t k = 0; k < f.size(); ++k) {
      const std::complex<double> ea(ma.storage[k], ma.loss[k]), eb(mb.storage[k], mb.loss[k]);
      const double dm = (std::abs(eb) - std::abs(ea)) / (rel * 0.5 * (std::abs(ea) + std::abs(eb)));
      const double dp = (std::arg(eb) - std::arg(ea)) * 180.0 / M_PI / ph;
      sm += dm * dm, sp += dp * dp;
    }
    const double expected = std::sqrt((sm + sp) / (2.0 * f.size()));
    const cc::SeparatingTest& t = named(tests, std::string("dynamic sweep at ") + label + " %");
    std::printf("  preload %.3f: time domain %.4g, frequency domain %.4g\n", preload, t.separation, expected);
    EXPECT_GT(expected, 1.0);
    EXPECT_NEAR(t.separation, expected, 0.05 * expected) << t.name;
    EXPECT_EQ(t.residuals, 2 * static_cast<int>(f.size()));
    EXPECT_DOUBLE_EQ(t.delta_chi2(), t.residuals * t.separation * t.separation);
  }
  EXPECT_GT(named(tests, "quasi-static at 2400 mm/min").separation,
            named(tests, "quasi-static at 3 mm/min").separation);
}
