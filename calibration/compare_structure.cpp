#include "calibration/compare_structure.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "calibration/segments.hpp"

namespace cushion::calibration {

namespace fs = std::filesystem;

namespace {

std::string number(double v) {
  std::ostringstream o;
  o.precision(4);
  o << v;
  return o.str();
}

/// Sample ranges of a load/unload record: loading [0, first], unloading [last, n - 1], where first/last are
/// the first/last samples within 1e-3 x_max of the largest indentation x_max.
struct Branches {
  std::size_t first = 0, last = 0;
  double x_max = 0.0;
};

Branches branches(const std::vector<double>& x) {
  Branches b;
  b.x_max = *std::max_element(x.begin(), x.end());
  const double near = b.x_max - 1e-3 * std::abs(b.x_max);
  b.first = std::find_if(x.begin(), x.end(), [&](double v) { return v >= near; }) - x.begin();
  b.last = x.size() - 1 - (std::find_if(x.rbegin(), x.rend(), [&](double v) { return v >= near; }) - x.rbegin());
  return b;
}

/// A branch of the model as a monotone table (x strictly increasing) for linear interpolation.
struct Table {
  std::vector<double> x, y;
  bool covers(double v) const { return !x.empty() && v >= x.front() - 1e-9 && v <= x.back() + 1e-9; }
  double at(double v) const {
    if (x.size() == 1) return y.front();
    const auto k = std::clamp<std::size_t>(std::upper_bound(x.begin(), x.end(), v) - x.begin(), 1, x.size() - 1);
    const double t = (v - x[k - 1]) / (x[k] - x[k - 1]);
    return y[k - 1] + t * (y[k] - y[k - 1]);
  }
};

/// segments.hpp monotone_branch as a Table.
Table monotone_table(const std::vector<double>& x, const std::vector<double>& y, std::size_t a, std::size_t b,
                     bool loading) {
  MonotoneBranch m = monotone_branch(x, y, a, b, loading);
  return {std::move(m.x), std::move(m.y)};
}

}  // namespace

TestNoise indentation_noise(const IndentationCurve& record) {
  const Branches b = branches(record.indentation);
  TestNoise n;
  const std::vector<double> local =
      reading_noise(record.force, {{0, b.first}, {b.first, b.last}, {b.last, record.force.size() - 1}});
  n.stress = rms_of(local);
  n.known = n.stress > 0.0;
  if (n.known) n.stress_local = local;
  return n;
}

TestNoise stiffness_noise(const StiffnessSpectrum& record) {
  return TestNoise::of(spectrum_noise(record.frequency, record.amplitude, record.phase));
}

TestCompare compare_indentation(const IndentationTest& test, const IndentationCurve& model,
                                std::vector<std::string>& warnings) {
  TestCompare c;
  c.name = test.name;
  c.kind = "indentation";
  c.use = "validation";
  c.noise = indentation_noise(test.record);
  const auto& mx = test.record.indentation;
  const auto& mf = test.record.force;
  const Branches mb = branches(mx), rb = branches(model.indentation);
  const Table load = monotone_table(model.indentation, model.force, 0, rb.first, true);
  const Table unload = monotone_table(model.indentation, model.force, rb.last, model.indentation.size() - 1, false);
  std::size_t left_out = 0;
  auto take = [&](std::size_t a, std::size_t b, const Table& t) {
    std::size_t taken = 0;
    for (std::size_t i = a; i <= b; ++i) {
      if (!t.covers(mx[i])) {
        ++left_out;
        continue;
      }
      c.x.push_back(mx[i]);
      c.measured.push_back(mf[i]);
      c.model.push_back(t.at(mx[i]));
      if (c.noise.known) c.noise_local.push_back(c.noise.stress_local[i]);
      ++taken;
    }
    return taken;
  };
  const std::size_t loaded = take(0, mb.first, load);
  c.unload_begin = c.x.size();
  const std::size_t unloaded = take(mb.last, mx.size() - 1, unload);
  if (left_out > 0)
    warnings.push_back(test.name + ": " + std::to_string(left_out) + " measured samples outside the run's indentation range (" +
                       "run: up to " + number(rb.x_max) + " mm, measured: up to " + number(mb.x_max) +
                       " mm) are not compared" + (rb.x_max < 0.95 * mb.x_max ? ": the run does not reach the measured "
                                                                                "indentation (another protocol or specimen?)"
                                                                              : ""));
  if (loaded < 2 || unloaded < 2)
    throw std::runtime_error("fewer than 2 measured samples of the " + std::string(loaded < 2 ? "loading" : "unloading") +
                             " branch lie within the run's indentation range (run up to " + number(rb.x_max) +
                             " mm, measured up to " + number(mb.x_max) + " mm)");
  const double f_peak = *std::max_element(mf.begin(), mf.end());
  c.regions = curve_regions({c.x, c.measured, c.model, c.noise_local, c.unload_begin, mb.x_max, f_peak}, "indentation",
                            "N", "N mm", c.noise.known ? c.noise.stress : 0.0, 1.0);
  c.hysteresis_measured = loop_area(c.x, c.measured);
  c.hysteresis_model = loop_area(c.x, c.model);
  return c;
}

TestCompare compare_stiffness(const StiffnessTest& test, const StiffnessSpectrum& model, std::vector<std::string>& warnings) {
  TestCompare c;
  c.name = test.name;
  c.kind = "dynamic_stiffness";
  c.use = "validation";
  c.noise = stiffness_noise(test.record);
  Table amplitude, phase;  // the run's spectrum in log f
  for (std::size_t i = 0; i < model.frequency.size(); ++i) {
    amplitude.x.push_back(std::log(model.frequency[i]));
    amplitude.y.push_back(model.amplitude[i]);
    phase.y.push_back(model.phase[i]);
  }
  phase.x = amplitude.x;
  std::size_t left_out = 0;
  for (std::size_t i = 0; i < test.record.frequency.size(); ++i) {
    const double lf = std::log(test.record.frequency[i]);
    if (!amplitude.covers(lf)) {
      ++left_out;
      continue;
    }
    c.x.push_back(test.record.frequency[i]);
    c.measured.push_back(test.record.amplitude[i]);
    c.measured_phase.push_back(test.record.phase[i]);
    c.model.push_back(amplitude.at(lf));
    c.model_phase.push_back(phase.at(lf));
  }
  const std::string range = number(model.frequency.front()) + "-" + number(model.frequency.back()) + " Hz";
  if (c.x.empty()) throw std::runtime_error("no measured frequency lies within the run's sweep (" + range + ")");
  if (left_out > 0)
    warnings.push_back(test.name + ": " + std::to_string(left_out) + " measured frequencies outside the run's sweep (" +
                       range + ") are not compared");
  c.regions = spectrum_regions(c.measured, c.model, c.measured_phase, c.model_phase,
                               c.noise.spectrum(), "stiffness", "N/mm", 1.0);
  return c;
}

std::vector<TestCompare> compare_structure(const Campaign& campaign, const std::vector<fs::path>& runs,
                                           std::vector<std::string>& warnings) {
  std::vector<TestCompare> out;
  auto guarded = [&](const std::string& name, const std::string& kind, const TestNoise& noise, auto&& file_of,
                     auto&& run) {
    TestCompare failed;
    failed.name = name;
    failed.kind = kind;
    failed.use = "validation";
    failed.noise = noise;
    const auto found = std::find_if(runs.begin(), runs.end(), [&](const fs::path& r) { return fs::exists(file_of(r)); });
    try {
      if (found == runs.end()) {
        std::string searched;
        for (const auto& r : runs) searched += (searched.empty() ? "" : ", ") + file_of(r).string();
        throw std::runtime_error(runs.empty() ? "no run folder given (--run RUN_DIR)" : "no run output found (searched " + searched + ")");
      }
      out.push_back(run(*found));
    } catch (const std::exception& e) {
      failed.failure = e.what();
      warnings.push_back(name + ": cannot compare: " + failed.failure);
      out.push_back(failed);
    }
  };
  for (const auto& t : campaign.indentation)
    guarded(t.name, "indentation", indentation_noise(t.record), [&](const fs::path& r) { return model_file(r, t); },
            [&](const fs::path& r) { return compare_indentation(t, read_model_indentation(r, t), warnings); });
  for (const auto& t : campaign.stiffness)
    guarded(t.name, "dynamic_stiffness", stiffness_noise(t.record), [&](const fs::path& r) { return model_file(r, t); },
            [&](const fs::path& r) { return compare_stiffness(t, read_model_stiffness(r, t), warnings); });
  for (const auto& t : out)
    if (t.failure.empty() && !t.noise.known)
      warnings.push_back(t.name + ": too few samples to estimate the measurement noise");
  return out;
}

}  // namespace cushion::calibration
