// Test-data generation for the diagnose benchmark, independent of cushion's material/ and calibration/:
// truths, effect scaling against the noise, and campaign files in cushion's format (written with std
// streams and nlohmann-json; nothing of cushion's io/ is used).
#include "foreign_campaign.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace foreign_bench {

namespace fs = std::filesystem;

namespace {

std::string join(const std::vector<std::string>& items, const std::string& separator) {
  std::string s;
  for (std::size_t i = 0; i < items.size(); ++i) s += (i ? separator : "") + items[i];
  return s;
}

void write_csv(const fs::path& file, const std::vector<std::string>& comments, const std::vector<std::string>& columns,
               const std::vector<const std::vector<double>*>& data) {
  std::ofstream out(file);
  if (!out) throw std::runtime_error("cannot write " + file.string());
  for (const auto& c : comments) out << "# " << c << "\n";
  out << join(columns, ",") << "\n" << std::setprecision(10);
  for (std::size_t k = 0; k < data.front()->size(); ++k) {
    for (std::size_t c = 0; c < data.size(); ++c) out << (c ? "," : "") << (*data[c])[k];
    out << "\n";
  }
  if (!out) throw std::runtime_error("error writing " + file.string());
}

void write_json(const fs::path& file, const nlohmann::json& j) {
  std::ofstream out(file);
  out << j.dump(2) << "\n";
  if (!out) throw std::runtime_error("error writing " + file.string());
}

nlohmann::json base_json(const BaseFoam& foam) {
  nlohmann::json j{{"family", foam.family},
                   {"density_kg_m3", foam.density_kg_m3},
                   {"stress_50_kPa", foam.elastic_stress_kPa(0.5)},
                   {"stress_75_kPa", foam.elastic_stress_kPa(0.75)},
                   {"prony_sum_g", foam.prony_sum()},
                   {"form", "s_e = -sum 2 mu_i/alpha_i (l^(alpha_i-1) - 1/l), l = 1 - e (nu = 0); "
                            "s = l (s_e/l + sum h_j), h_j <- exp(-x) h_j + a_j (1 - exp(-x))/x d(s_e/l), x = dt/tau_j, "
                            "a_j = g_j/(1 - sum g)"}};
  j["hyperfoam"] = nlohmann::json::array();
  for (const auto& t : foam.hyperfoam) j["hyperfoam"].push_back({{"mu_kPa", t.mu_kPa}, {"alpha", t.alpha}});
  j["prony"] = nlohmann::json::array();
  for (std::size_t k = 0; k < foam.prony.size(); ++k)
    j["prony"].push_back({{"g", foam.prony[k].g}, {"a_long_term", foam.decorator_weight(k)}, {"tau_s", foam.prony[k].tau_s}});
  return j;
}

}  // namespace

TestPlan standard_plan() {
  TestPlan plan;
  for (double rate : {12.0, 120.0, 600.0}) {
    QuasiStaticProtocol p;
    p.name = "qs_" + std::to_string(static_cast<int>(rate));
    p.rate_mm_min = rate;
    p.sample_hz = rate > 300.0 ? 50.0 : 10.0;  // 0.2 mm a sample at 600 mm/min
    p.use = rate == 120.0 ? "calibration" : "validation";
    plan.quasi_static.push_back(p);
  }
  for (double preload : {0.25, 0.5}) {
    DynamicProtocol p;
    p.name = "dyn_" + std::to_string(static_cast<int>(std::lround(preload * 100)));
    p.preload_strain = preload;
    p.frequencies_Hz = {1, 1.5, 2, 3, 4, 6, 8, 11, 15, 20};
    p.use = preload == 0.25 ? "calibration" : "validation";
    plan.dynamic.push_back(p);
  }
  return plan;
}

QuasiStaticProtocol extra_rate(double rate_mm_min) {
  QuasiStaticProtocol p;
  std::ostringstream name;
  name << "qs_" << rate_mm_min << "_extra";
  p.name = name.str();
  p.rate_mm_min = rate_mm_min;
  p.sample_hz = std::max(10.0, rate_mm_min / 12.0);  // 0.2 mm a sample
  p.use = "validation";
  return p;
}

QuasiStaticProtocol extra_hold(double hold_s) {
  QuasiStaticProtocol p = extra_rate(120.0);
  std::ostringstream name;
  name << "qs_120_hold" << hold_s << "_extra";
  p.name = name.str();
  p.hold_s = hold_s;
  return p;
}

DynamicProtocol extra_preload(const TestPlan& plan, double preload_strain) {
  if (plan.dynamic.empty()) throw std::invalid_argument("extra_preload: the plan has no dynamic test");
  DynamicProtocol p = plan.dynamic.front();
  p.name = "dyn_" + std::to_string(static_cast<int>(std::lround(preload_strain * 100))) + "_extra";
  p.preload_strain = preload_strain;
  p.use = "validation";
  return p;
}

TestPlan drawn_protocol(const TestPlan& plan, Random& random) {
  TestPlan out = plan;
  out.unrecorded_protocol = true;
  static const int cycle_counts[] = {5, 10, 20, 50};
  const int cycles = cycle_counts[random.index(4)];
  const double rate = random.log_uniform(10.0, 100.0);
  const double dwell = random.unit() < 1.0 / 3.0 ? 0.0 : random.log_uniform(10.0, 300.0);
  out.amplitude_written_as_peak = random.unit() < 0.5;
  for (auto* tests : {&out.dynamic, &out.extra_dynamic})
    for (auto& p : *tests) {
      p.cycles = cycles;
      p.fit_cycles = cycles / 2;
      p.preload_rate_mm_min = rate;
      p.dwell_s = dwell;
    }
  return out;
}

std::map<std::string, double> effect_over_noise(const BaseFoam& foam, const std::vector<EffectSpec>& effects,
                                                const TestPlan& plan) {
  return ratios_between(simulate_noise_free(foam, {}, plan), simulate_noise_free(foam, effects, plan), plan);
}

double largest(const std::map<std::string, double>& ratios) {
  double m = 0.0;
  for (const auto& [name, r] : ratios) m = std::max(m, r);
  return m;
}

EffectSpec scale_effect(EffectSpec shape, const BaseFoam& foam, const TestPlan& plan, double target) {
  const EffectForm& form = find_form(shape.family, shape.form);
  const PlanRecords base = simulate_noise_free(foam, {}, plan);
  // f(x) = ln(largest ratio) - ln(target) at x = ln(magnitude): Illinois regula falsi on a bracket.
  auto f = [&](double x) {
    shape.parameters[form.magnitude] = std::exp(x);
    const double r = largest(ratios_between(base, simulate_noise_free(foam, {shape}, plan), plan));
    return std::log(std::max(r, 1e-300)) - std::log(target);
  };
  double a = std::log(form.magnitude_lo), b = std::log(form.magnitude_hi);
  double fa = f(a), fb = f(b);
  if (fa > 0.0 || fb < 0.0)
    throw std::runtime_error(form.family + "/" + form.form + ": cannot reach " + std::to_string(target) +
                             " x noise within the magnitude range");
  const double tolerance = std::log(1.25);
  int side = 0;
  for (int iteration = 0; iteration < 60; ++iteration) {
    double x = b - fb * (b - a) / (fb - fa);
    x = std::clamp(x, a + 0.01 * (b - a), b - 0.01 * (b - a));
    const double fx = f(x);
    if (std::abs(fx) < tolerance) return shape;  // parameters hold exp(x)
    if (fx > 0.0) {
      b = x, fb = fx;
      if (side == 1) fa *= 0.5;
      side = 1;
    } else {
      a = x, fa = fx;
      if (side == -1) fb *= 0.5;
      side = -1;
    }
  }
  throw std::runtime_error(form.family + "/" + form.form + ": scaling did not converge");
}

EffectSpec scale_effect_beyond_base_refit(EffectSpec shape, const BaseFoam& foam, const TestPlan& plan, double target) {
  const EffectForm& form = find_form(shape.family, shape.form);
  EffectSpec effect = scale_effect(std::move(shape), foam, plan, target);
  BaseFoam start = foam;
  for (int round = 0; round < 8; ++round) {
    const BaseRefit refit = refit_base(foam, {effect}, plan, &start);
    const double left = largest(refit.ratio_after);
    if (std::abs(std::log(left / target)) < std::log(1.25)) return effect;
    double& magnitude = effect.parameters[form.magnitude];
    if (left < target && (magnitude >= form.magnitude_hi || largest(refit.ratio_before) > largest_effect_over_noise))
      break;
    magnitude = std::clamp(magnitude * target / std::max(left, 1e-3), form.magnitude_lo, form.magnitude_hi);
    start = refit.base;
  }
  throw std::runtime_error(form.family + "/" + form.form + ": what a refitted base leaves cannot reach " +
                           std::to_string(target) + " x noise within the magnitude range");
}

CampaignTruth draw_truth(const std::string& name, const CampaignKind& kind, std::uint64_t seed, const TestPlan& plan,
                         BaseRefitUse refit) {
  CampaignTruth truth;
  truth.name = name;
  truth.seed = seed;
  Random base_random(mix_seed(seed, 0));
  truth.base = draw_base_foam(draw_base_family(base_random), base_random);
  for (std::size_t k = 0; k < kind.families.size(); ++k) {
    Random random(mix_seed(seed, 1 + k));
    const EffectForm& form = find_form(kind.families[k], kind.forms[k]);
    const double target = random.log_uniform(14.0, 36.0);
    EffectSpec effect;
    bool beyond_refit = refit == BaseRefitUse::scale;
    std::map<std::string, double> failed_shape;  // the last shape whose refit-proof part could not reach the target
    for (int draw = 0;; ++draw) {                // scale: such a shape is drawn again
      const EffectSpec shape = draw_effect_shape(form, truth.base, random);
      // A form with no random shape parameter (stiffness-proportional damping, the power-law and exponential
      // strain-dependent Prony) draws the same shape again: what failed once would fail again, at the same cost.
      if (beyond_refit && shape.parameters == failed_shape) beyond_refit = false;
      try {
        effect = beyond_refit ? scale_effect_beyond_base_refit(shape, truth.base, plan, target)
                              : scale_effect(shape, truth.base, plan, target);
        break;
      } catch (const std::runtime_error&) {
        if (!beyond_refit) throw;
        failed_shape = shape.parameters;
        if (draw + 1 == shape_draws_beyond_base_refit) beyond_refit = false;  // then sized against the true base
      }
    }
    truth.sized_by[effect.family] = beyond_refit ? sized_by_base_refit : sized_by_true_base;
    truth.effect_over_noise[effect.family] = effect_over_noise(truth.base, {effect}, plan);
    if (refit != BaseRefitUse::none)
      truth.effect_after_base_refit[effect.family] = refit_base(truth.base, {effect}, plan).ratio_after;
    add_derived_parameters(effect);
    truth.equations.push_back(form.equation);
    truth.effects.push_back(effect);
  }
  if (refit != BaseRefitUse::none && !truth.effects.empty())  // one effect: its own refit is the campaign's
    truth.all_effects_after_base_refit = truth.effects.size() == 1
                                             ? truth.effect_after_base_refit.at(truth.effects.front().family)
                                             : refit_base(truth.base, truth.effects, plan).ratio_after;
  if (refit != BaseRefitUse::none && truth.effects.size() == 2)
    for (std::size_t k = 0; k < 2; ++k)
      truth.member_beyond_partner[truth.effects[k].family] =
          refit_base(truth.base, truth.effects, plan, nullptr, base_refit_iterations, {truth.effects[1 - k]})
              .ratio_after;
  return truth;
}

void write_campaign(const CampaignTruth& truth, const TestPlan& plan, const fs::path& dir) {
  fs::create_directories(dir);
  const Specimen& sp = plan.specimen;
  nlohmann::json manifest;
  manifest["description"] = "SYNTHETIC campaign " + truth.name +
                            " from foreign_campaigns (tests/foreign: a 1D test machine independent of cushion), seed " +
                            std::to_string(truth.seed);
  manifest["specimen"] = {{"length_mm", sp.length_mm}, {"width_mm", sp.width_mm}, {"thickness_mm", sp.thickness_mm},
                          {"density_kg_m3", truth.base.density_kg_m3}};
  manifest["tests"] = nlohmann::json::array();
  std::uint64_t stream = 100;
  std::uint64_t extra_stream = 200;
  std::vector<std::pair<const QuasiStaticProtocol*, std::uint64_t>> quasi_static;
  for (const auto& p : plan.quasi_static) quasi_static.push_back({&p, stream++});
  std::vector<std::pair<const DynamicProtocol*, std::uint64_t>> dynamic;
  nlohmann::json dynamic_sd = nlohmann::json::object();  // drawn_noise.json: the noise each sweep was drawn with
  for (const auto& p : plan.dynamic) dynamic.push_back({&p, stream++});
  for (const auto& p : plan.extra_quasi_static) quasi_static.push_back({&p, extra_stream++});
  for (const auto& p : plan.extra_dynamic) dynamic.push_back({&p, extra_stream++});
  for (const auto& [pp, own_stream] : quasi_static) {
    const QuasiStaticProtocol& p = *pp;
    QuasiStaticRecord rec = run_quasi_static(truth.base, truth.effects, sp, p);
    Random noise(mix_seed(truth.seed, own_stream));
    add_quasi_static_noise(rec, plan.noise, noise);
    const std::string file = p.name + ".csv";
    write_csv(dir / file, {"SYNTHETIC quasi-static record from foreign_campaigns: " + p.name, "compression positive"},
              {"time_s", "displacement_mm", "force_N"}, {&rec.time_s, &rec.displacement_mm, &rec.force_N});
    manifest["tests"].push_back({{"kind", "quasi_static"}, {"name", p.name}, {"file", file},
                                 {"rate_mm_min", p.rate_mm_min}, {"lateral", "free"}, {"use", p.use},
                                 {"preflex_cycles", 0}, {"lift_off", true}});
  }
  for (const auto& [pp, own_stream] : dynamic) {
    const DynamicProtocol& p = *pp;
    Random noise(mix_seed(truth.seed, own_stream));
    const DynamicRecord rec = run_dynamic(truth.base, truth.effects, sp, p, plan.noise, &noise);
    nlohmann::json& sd = dynamic_sd[p.name];
    sd["frequency_Hz"] = rec.frequency_Hz;
    for (std::size_t i = 0; i < rec.frequency_Hz.size(); ++i) {
      sd["modulus_sd_kPa"].push_back(rec.modulus_sd_kPa(i));
      sd["phase_sd_deg"].push_back(rec.phase_sd_deg(i));
    }
    const std::string file = p.name + ".csv";
    write_csv(dir / file,
              {"SYNTHETIC dynamic record from foreign_campaigns: " + p.name,
               "nominal stress amplitude over nominal strain amplitude; phase of stress relative to strain"},
              {"frequency_Hz", "dynamic_modulus_kPa", "phase_deg"},
              {&rec.frequency_Hz, &rec.dynamic_modulus_kPa, &rec.phase_deg});
    nlohmann::json test{{"kind", "dynamic"}, {"name", p.name}, {"file", file}, {"preload_strain", p.preload_strain},
                        {"acceleration_amplitude_m_s2", p.acceleration_peak_to_peak_m_s2}, {"preflex_cycles", 0},
                        {"lift_off", false}, {"use", p.use}};
    if (plan.unrecorded_protocol) {
      if (plan.amplitude_written_as_peak) test["acceleration_amplitude_m_s2"] = 0.5 * p.acceleration_peak_to_peak_m_s2;
    } else {
      test.update({{"amplitude_convention", "peak_to_peak"}, {"preload_rate_mm_min", p.preload_rate_mm_min},
                   {"dwell_before_sweep_s", p.dwell_s}, {"cycles", p.cycles}, {"fit_cycles", p.fit_cycles}});
    }
    manifest["tests"].push_back(test);
  }
  write_json(dir / "campaign.json", manifest);

  nlohmann::json t;
  t["families"] = nlohmann::json::array();
  t["forms"] = nlohmann::json::array();
  t["parameters"] = nlohmann::json::object();
  for (std::size_t k = 0; k < truth.effects.size(); ++k) {
    const EffectSpec& e = truth.effects[k];
    t["families"].push_back(e.family);
    t["forms"].push_back(e.form);
    nlohmann::json p{{"form", e.form}, {"equation", truth.equations[k]}};
    for (const auto& [key, value] : e.parameters) p[key] = value;
    p["effect_over_noise"] = truth.effect_over_noise.at(e.family);
    if (truth.effect_after_base_refit.count(e.family)) {
      p["after_base_refit"] = truth.effect_after_base_refit.at(e.family);
      p["sized_against"] = truth.sized_by.at(e.family);
    }
    if (truth.member_beyond_partner.count(e.family))
      p["beyond_partner_refit"] = truth.member_beyond_partner.at(e.family);
    t["parameters"][e.family] = p;
  }
  if (!truth.all_effects_after_base_refit.empty())
    t["after_base_refit"] = {
        {"what", "per test, what a base of the generator's own family (term counts of the truth's base, every mu_i, "
                 "alpha_i, Prony a_j and tau_j refitted by Levenberg-Marquardt on the noise-free records) leaves of "
                 "all the effects together, in noise units (RMS difference over RMS noise)"},
        {"ratios", truth.all_effects_after_base_refit},
        {"largest", largest(truth.all_effects_after_base_refit)}};
  if (plan.unrecorded_protocol && !plan.dynamic.empty()) {
    const DynamicProtocol& d = plan.dynamic.front();
    t["protocol"] = {{"recorded", false}, {"cycles", d.cycles}, {"fit_cycles", d.fit_cycles},
                     {"preload_rate_mm_min", d.preload_rate_mm_min}, {"dwell_before_sweep_s", d.dwell_s},
                     {"amplitude_convention", plan.amplitude_written_as_peak ? "peak" : "peak_to_peak"},
                     {"acceleration_peak_to_peak_m_s2", d.acceleration_peak_to_peak_m_s2}};
  }
  t["base"] = base_json(truth.base);
  t["seed"] = truth.seed;
  t["noise"] = {{"force_relative", plan.noise.force_relative},
                {"force_floor_N", plan.noise.force_floor_N},
                {"dynamic", plan.noise.dynamic_relative_to_reading ? "relative to the whole reading"
                                                                    : "relative to the oscillating force amplitude"}};
  t["generator"] = "foreign_campaigns (tests/foreign): own 1D forms, independent of cushion's material/ and calibration/";
  write_json(dir / "truth.json", t);
  // Per sweep and frequency, the standard deviation of |E*| and phase the force noise gave (least squares over the fit
  // window): read only to score, like truth.json; apart from it so that the truth does not depend on the extra tests.
  write_json(dir / "drawn_noise.json", {{"dynamic", dynamic_sd}});
}

std::vector<CampaignKind> campaign_mix(int count, int pairs, int controls, std::uint64_t seed) {
  const int singles = count - pairs - controls;
  if (count < 1 || pairs < 0 || controls < 0 || singles < 0)
    throw std::invalid_argument("campaign_mix: need count >= pairs + controls >= 0");
  const auto& families = effect_families();
  std::vector<CampaignKind> kinds;
  for (int i = 0; i < singles; ++i) {
    const std::string& family = families[i % families.size()];
    const auto forms = forms_of_family(family);
    kinds.push_back({{family}, {forms[(i / families.size()) % forms.size()]->form}});
  }
  std::vector<std::pair<std::size_t, std::size_t>> family_pairs;
  for (std::size_t a = 0; a < families.size(); ++a)
    for (std::size_t b = a + 1; b < families.size(); ++b) family_pairs.push_back({a, b});
  Random random(mix_seed(seed, 7777));
  for (int k = 0; k < pairs; ++k) {
    const auto [a, b] = family_pairs[k % family_pairs.size()];
    CampaignKind kind;
    for (std::size_t f : {a, b}) {
      const auto forms = forms_of_family(families[f]);
      kind.families.push_back(families[f]);
      kind.forms.push_back(forms[random.index(forms.size())]->form);
    }
    kinds.push_back(kind);
  }
  for (int k = 0; k < controls; ++k) kinds.push_back({});
  Random shuffle(mix_seed(seed, 9999));
  for (std::size_t i = kinds.size(); i > 1; --i) std::swap(kinds[i - 1], kinds[shuffle.index(i)]);
  return kinds;
}

void write_campaign_set(const fs::path& dir, int count, int pairs, int controls, std::uint64_t seed,
                        const TestPlan& plan, std::ostream& log, BaseRefitUse refit, const std::set<std::string>& only) {
  const std::vector<CampaignKind> kinds = campaign_mix(count, pairs, controls, seed);
  auto name_of = [](std::size_t i) {
    std::ostringstream name;
    name << "c" << std::setw(3) << std::setfill('0') << i;
    return name.str();
  };
  for (const std::string& n : only) {  // before anything is written
    std::size_t i = 0;
    while (i < kinds.size() && name_of(i) != n) ++i;
    if (i == kinds.size()) throw std::runtime_error("--only " + n + ": no such campaign in a set of " + std::to_string(count));
  }
  fs::create_directories(dir);
  std::ofstream index(dir / "index.csv");
  index << "campaign,families,forms\n";
  for (std::size_t i = 0; i < kinds.size(); ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::string name = name_of(i);
    if (!only.empty() && !only.count(name)) continue;
    Random protocol_random(mix_seed(mix_seed(seed, i), 4242));
    const TestPlan campaign_plan = plan.unrecorded_protocol ? drawn_protocol(plan, protocol_random) : plan;
    const CampaignTruth truth = draw_truth(name, kinds[i], mix_seed(seed, i), campaign_plan, refit);
    write_campaign(truth, campaign_plan, dir / name);
    const std::string families = kinds[i].families.empty() ? "control" : join(kinds[i].families, "+");
    const std::string forms = kinds[i].forms.empty() ? "-" : join(kinds[i].forms, "+");
    index << name << "," << families << "," << forms << "\n";
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    log << name << ": " << families << " (" << forms << "), base " << truth.base.family << " "
        << std::setprecision(3) << truth.base.density_kg_m3 << " kg/m3, s_e(50%) "
        << truth.base.elastic_stress_kPa(0.5) << " kPa";
    for (const auto& [family, ratios] : truth.effect_over_noise) log << ", " << family << " " << largest(ratios) << "x noise";
    if (!truth.all_effects_after_base_refit.empty())
      log << ", " << largest(truth.all_effects_after_base_refit) << "x after a base refit";
    if (refit == BaseRefitUse::scale)
      for (const auto& [family, sized_by] : truth.sized_by)
        if (sized_by == sized_by_true_base)
          log << " (" << family
              << " sized against the true base: no shape drawn reached the target beyond a base refit)";
    log << " (" << seconds << " s)\n";
  }
  if (!index) throw std::runtime_error("error writing " + (dir / "index.csv").string());
}

}  // namespace foreign_bench
