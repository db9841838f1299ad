#include "calibration/protocol_search.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <sstream>
#include <thread>

namespace cushion::calibration {

namespace {

/// One searchable key: its values, the coarse subset the joint grid takes, and how a value is set on a dynamic test
/// (false: the value does not apply to that test).
struct KeyDefinition {
  std::string key;
  std::vector<std::string> labels;
  std::vector<std::size_t> coarse;  ///< indices into labels, the joint grid's values
  std::size_t default_index = 0;
  std::function<bool(DynamicTest&, std::size_t)> apply;
};

std::string label(double v, const std::string& unit) {
  std::ostringstream o;
  o << v << " " << unit;
  return o.str();
}

/// A key over numeric values (labels "v unit"); `set` stores one on a test.
KeyDefinition numeric_key(const std::string& key, std::vector<double> values, std::vector<double> coarse, double default_value,
                          const std::string& unit, void (*set)(DynamicTest&, double)) {
  KeyDefinition k{key, {}, {}, 0, nullptr};
  if (std::find(values.begin(), values.end(), default_value) == values.end()) values.push_back(default_value);
  if (std::find(coarse.begin(), coarse.end(), default_value) == coarse.end()) coarse.push_back(default_value);
  std::sort(values.begin(), values.end());
  for (std::size_t i = 0; i < values.size(); ++i) {
    k.labels.push_back(label(values[i], unit));
    if (values[i] == default_value) k.default_index = i;
    if (std::find(coarse.begin(), coarse.end(), values[i]) != coarse.end()) k.coarse.push_back(i);
  }
  k.apply = [values, set](DynamicTest& t, std::size_t i) {
    set(t, values[i]);
    return true;
  };
  return k;
}

bool leaves_out(const DynamicTest& t, const std::string& key) {
  return std::find(t.unrecorded.begin(), t.unrecorded.end(), key) != t.unrecorded.end();
}

std::vector<KeyDefinition> key_definitions(const CompareOptions& options) {
  std::vector<KeyDefinition> keys;
  {
    static const int cycles[] = {5, 10, 20, 50};
    KeyDefinition k{"cycles", {}, {0, 1, 2, 3}, 2, nullptr};
    for (int c : cycles) k.labels.push_back(std::to_string(c) + " (last " + std::to_string(std::max(1, c / 2)) + " fitted)");
    k.apply = [](DynamicTest& t, std::size_t i) {
      const int c = cycles[i];
      const bool fit_cycles_recorded = !leaves_out(t, "fit_cycles");
      if (fit_cycles_recorded && t.fit_cycles > c) return false;
      t.cycles = c;
      if (!fit_cycles_recorded) t.fit_cycles = std::max(1, c / 2);
      return true;
    };
    keys.push_back(k);
  }
  keys.push_back(numeric_key("preload_rate_mm_min", {10, 15, 20, 30, 50, 70, 100}, {10, 30, 100}, options.preload_rate_mm_min,
                             "mm/min", [](DynamicTest& t, double v) { t.preload_rate_mm_min = v; }));
  keys.push_back(numeric_key("dwell_before_sweep_s", {0, 3, 10, 20, 30, 60, 100, 200, 300}, {0, 10, 30, 100, 300}, 0.0, "s",
                             [](DynamicTest& t, double v) { t.dwell_s = v; }));
  keys.push_back({"amplitude_convention", {"peak_to_peak", "peak"}, {0, 1}, 0, [](DynamicTest& t, std::size_t i) {
                    t.amplitude_peak_to_peak = i == 0;
                    return true;
                  }});
  return keys;
}

/// The campaign's dynamic tests with the keys at `choice` (where a test leaves them out); false when a value does
/// not apply to some test.
bool apply_choice(std::vector<DynamicTest>& tests, const std::vector<KeyDefinition>& keys,
                  const std::vector<std::size_t>& choice) {
  for (auto& t : tests)
    for (std::size_t k = 0; k < keys.size(); ++k)
      if (leaves_out(t, keys[k].key) && !keys[k].apply(t, choice[k])) return false;
  return true;
}

/// The two tests are run alike as far as the searched keys go (a preload rate 0, "not given", is the default rate).
bool same_protocol(const DynamicTest& a, const DynamicTest& b, double default_rate) {
  auto rate = [&](const DynamicTest& t) { return t.preload_rate_mm_min > 0.0 ? t.preload_rate_mm_min : default_rate; };
  return a.cycles == b.cycles && a.fit_cycles == b.fit_cycles && rate(a) == rate(b) && a.dwell_s == b.dwell_s &&
         a.amplitude_peak_to_peak == b.amplitude_peak_to_peak;
}

double chi2_of(const CompareResult& r) {
  double s = 0.0;
  for (const auto& t : r.tests)
    if (!t.failure.empty()) return std::numeric_limits<double>::quiet_NaN();
  for (double x : normalised_residuals(r)) s += x * x;
  return s;
}

}  // namespace

double ProtocolKeySearch::chi2_range() const {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& v : tried)
    if (std::isfinite(v.chi2)) lo = std::min(lo, v.chi2), hi = std::max(hi, v.chi2);
  return hi >= lo ? hi - lo : 0.0;
}

bool ProtocolSearch::changed() const {
  for (const auto& k : keys)
    if (k.chosen != k.assumed) return true;
  return false;
}

ProtocolSearch search_protocol(const material::Material& model, const Campaign& campaign,
                               const std::vector<TestNoise>& noise, const CompareOptions& options, double min_gain) {
  const auto t0 = std::chrono::steady_clock::now();
  ProtocolSearch out;
  out.campaign = campaign;
  std::vector<KeyDefinition> keys;
  for (auto& k : key_definitions(options)) {
    ProtocolKeySearch s{k.key, {}, k.labels[k.default_index], k.labels[k.default_index], {}};
    for (const auto& t : campaign.dynamic)
      if (leaves_out(t, k.key)) s.tests.push_back(t.name);
    if (s.tests.empty()) continue;
    out.keys.push_back(s);
    keys.push_back(std::move(k));
  }
  if (keys.empty()) return out;

  // Only the dynamic tests: the keys do not touch the others.
  Campaign dynamic_only = campaign;
  dynamic_only.quasi_static.clear();
  dynamic_only.indentation.clear();
  dynamic_only.stiffness.clear();
  const std::size_t nq = campaign.quasi_static.size();
  const std::vector<TestNoise> dynamic_noise(noise.begin() + std::ptrdiff_t(nq),
                                             noise.begin() + std::ptrdiff_t(nq + campaign.dynamic.size()));
  // chi2 of the dynamic tests with the keys at `choice`; none when a value does not apply to some test. The model is
  // const: runs on two threads share it.
  auto run = [&](const std::vector<std::size_t>& choice) -> std::optional<double> {
    Campaign c = dynamic_only;
    if (!apply_choice(c.dynamic, keys, choice)) return std::nullopt;
    return chi2_of(compare_campaign(model, c, options, dynamic_noise));
  };
  std::map<std::vector<std::size_t>, double> cache;  // NaN: not applicable or a run failed
  auto remember = [&](const std::vector<std::size_t>& choice, const std::optional<double>& chi2) {
    out.runs += chi2.has_value();
    return cache[choice] = chi2.value_or(std::numeric_limits<double>::quiet_NaN());
  };
  auto chi2_at = [&](const std::vector<std::size_t>& choice) {
    const auto it = cache.find(choice);
    return it != cache.end() ? it->second : remember(choice, run(choice));
  };

  // chi2 with key k at each of its values, the others as in `choice`.
  auto values_of = [&](const std::vector<std::size_t>& choice, std::size_t k) {
    std::vector<ProtocolValue> tried;
    for (std::size_t v = 0; v < keys[k].labels.size(); ++v) {
      std::vector<std::size_t> trial = choice;
      trial[k] = v;
      tried.push_back({keys[k].labels[v], chi2_at(trial)});
    }
    return tried;
  };
  std::vector<std::size_t> choice;
  for (const auto& k : keys) choice.push_back(k.default_index);
  out.chi2_assumed = chi2_at(choice);
  // 1. The joint grid of the coarse values (the keys interact: cycles, ramp and dwell all set how far the slow terms
  //    have relaxed when a modulus is read).
  std::vector<std::vector<std::size_t>> combos;
  std::vector<std::size_t> trial(keys.size(), 0);
  std::function<void(std::size_t)> enumerate = [&](std::size_t k) {
    if (k == keys.size()) return combos.push_back(trial);
    for (std::size_t v : keys[k].coarse) trial[k] = v, enumerate(k + 1);
  };
  enumerate(0);
  std::vector<std::optional<double>> grid(combos.size());
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (std::size_t i = next++; i < combos.size(); i = next++) grid[i] = run(combos[i]);
  };
  std::thread second(worker);
  worker();
  second.join();
  std::vector<std::size_t> best = choice;
  double best_chi2 = out.chi2_assumed;
  for (std::size_t i = 0; i < combos.size(); ++i) {
    const double chi2 = remember(combos[i], grid[i]);
    if (std::isfinite(chi2) && !(chi2 >= best_chi2)) best = combos[i], best_chi2 = chi2;
  }
  // 2. Each key over its finer values from the grid's best, the others held, until none moves.
  for (int sweep = 0; sweep < 3; ++sweep) {
    bool moved = false;
    for (std::size_t k = 0; k < keys.size(); ++k) {
      const std::vector<ProtocolValue> tried = values_of(best, k);
      for (std::size_t v = 0; v < tried.size(); ++v)
        if (std::isfinite(tried[v].chi2) && tried[v].chi2 < best_chi2) best[k] = v, best_chi2 = tried[v].chi2, moved = true;
    }
    if (!moved) break;
  }
  if (!std::isfinite(out.chi2_assumed) || out.chi2_assumed - best_chi2 > min_gain) choice = best;
  for (std::size_t k = 0; k < keys.size(); ++k) {
    out.keys[k].chosen = keys[k].labels[choice[k]];
    out.keys[k].tried = values_of(choice, k);  // about the final choice
  }
  out.chi2_chosen = chi2_at(choice);
  apply_choice(out.campaign.dynamic, keys, choice);
  for (std::size_t t = 0; t < campaign.dynamic.size(); ++t)
    out.moved = out.moved || !same_protocol(campaign.dynamic[t], out.campaign.dynamic[t], options.preload_rate_mm_min);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace cushion::calibration
