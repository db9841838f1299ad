#include "calibration/lab.hpp"

#include <cmath>
#include <fstream>
#include <numbers>
#include <ostream>
#include <random>

#include "calibration/sine_fit.hpp"
#include "io/input_error.hpp"
#include "io/csv.hpp"
#include "io/json_reader.hpp"

namespace cushion::calibration {

namespace {

using material::AxisControl;
using material::Segment;

/// Standard normal variates from mt19937_64 by Box-Muller: the same numbers on every platform
/// (std::normal_distribution is implementation-defined).
class Gaussian {
 public:
  Gaussian(unsigned long long seed, unsigned long long stream) : engine_(seed * 0x9E3779B97F4A7C15ULL + stream) {}
  double next() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    const double u1 = (static_cast<double>(engine_() >> 11) + 0.5) * 0x1.0p-53;  // (0, 1)
    const double u2 = static_cast<double>(engine_() >> 11) * 0x1.0p-53;          // [0, 1)
    const double r = std::sqrt(-2.0 * std::log(u1));
    spare_ = r * std::sin(2.0 * std::numbers::pi * u2);
    has_spare_ = true;
    return r * std::cos(2.0 * std::numbers::pi * u2);
  }

 private:
  std::mt19937_64 engine_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

Segment ramp(double target, double duration, int steps) {
  Segment s;
  s.kind = Segment::Kind::ramp;
  s.target = target;
  s.duration = duration;
  s.steps = std::max(1, steps);
  return s;
}

Segment hold(double duration, int steps) {
  Segment s;
  s.kind = Segment::Kind::hold;
  s.duration = duration;
  s.steps = std::max(1, steps);
  return s;
}

bool positive_value(double x) { return x > 0.0; }
bool non_negative_value(double x) { return x >= 0.0; }

/// Optional number with a range check; `fallback` when absent.
double optional_number(const io::JsonNode& node, const std::string& key, double fallback,
                       bool (*ok)(double) = nullptr, const std::string& what = "") {
  const auto v = node.find(key);
  if (!v) return fallback;
  return ok ? v->number_where(ok, what) : v->number();
}

int optional_integer(const io::JsonNode& node, const std::string& key, int fallback, int min, int max) {
  const auto v = node.find(key);
  return v ? static_cast<int>(v->integer(min, max)) : fallback;
}

std::string optional_choice(const io::JsonNode& node, const std::string& key, const std::vector<std::string>& choices,
                            const std::string& fallback) {
  const auto v = node.find(key);
  return v ? v->choice(choices) : fallback;
}

/// Quasi-static truth: the preflex from "preload_cycle" (older: true = one cycle to max_strain, the default) and
/// "rest_s", or from the protocol keys (not both).
PriorLoading read_legacy_preflex(const io::JsonNode& q, double max_strain) {
  for (const char* key : {"preflex_cycles", "rest_between_tests_s"})
    if (q.has(key) && (q.has("preload_cycle") || q.has("rest_s")))
      q.at(key).fail("give either the protocol keys or the older preload_cycle/rest_s, not both");
  PriorLoading legacy{1, max_strain, optional_number(q, "rest_s", 300.0, non_negative_value, ">= 0")};
  if (const auto b = q.find("preload_cycle")) legacy.preflex_cycles = b->boolean() ? 1 : 0;
  return read_prior_loading(q, legacy);
}

/// The preflex cycles (to prior.preflex_strain and back at speed_mm_s, `steps_per_s` increments a second) and
/// the rest after them; returns their duration [s] (0 without preflex).
double append_prior_loading(std::vector<Segment>& segments, const PriorLoading& prior, double thickness,
                            double speed_mm_s, double steps_per_s) {
  if (prior.preflex_cycles == 0) return 0.0;
  const double ramp_s = prior.preflex_strain * thickness / speed_mm_s;
  const int steps = static_cast<int>(std::ceil(ramp_s * steps_per_s));
  for (int c = 0; c < prior.preflex_cycles; ++c) {
    segments.push_back(ramp(-prior.preflex_strain, ramp_s, steps));
    segments.push_back(ramp(0.0, ramp_s, steps));
  }
  if (prior.rest_s > 0.0) segments.push_back(hold(prior.rest_s, static_cast<int>(std::ceil(prior.rest_s))));
  return 2.0 * ramp_s * prior.preflex_cycles + prior.rest_s;
}

/// The preflex keys of a campaign test (only when there is a preflex).
void write_prior_loading(const PriorLoading& prior, nlohmann::json& test) {
  if (prior.preflex_cycles == 0) return;
  test["preflex_cycles"] = prior.preflex_cycles;
  test["preflex_strain"] = prior.preflex_strain;
  test["rest_between_tests_s"] = prior.rest_s;
}

material::AxisControl axis_control(bool lift_off) {
  return lift_off ? AxisControl::platen : AxisControl::displacement;
}

}  // namespace

double DynamicProtocol::displacement_amplitude_mm(double f_Hz) const {
  const double peak = amplitude_peak_to_peak ? 0.5 * acceleration_amplitude : acceleration_amplitude;
  const double w = 2.0 * std::numbers::pi * f_Hz;
  return peak / (w * w) * 1000.0;  // m -> mm
}

LabTruth read_lab_truth(const std::filesystem::path& file) {
  const std::string src = file.string();
  const nlohmann::json j = io::parse_json(io::read_text_file(src), src);
  const io::JsonNode top(j, src);
  top.expect_object({"description", "material", "specimen", "noise", "quasi_static", "dynamic"});
  LabTruth truth;
  truth.file = file;
  if (const auto d = top.find("description")) truth.description = d->string();
  truth.material_file = file.parent_path() / top.at("material").string();
  {
    const io::JsonNode s = top.at("specimen");
    s.expect_object({"length_mm", "width_mm", "thickness_mm", "density_kg_m3"});
    truth.specimen.length = s.at("length_mm").number_where(positive_value, "> 0");
    truth.specimen.width = s.at("width_mm").number_where(positive_value, "> 0");
    truth.specimen.thickness = s.at("thickness_mm").number_where(positive_value, "> 0");
    truth.specimen.density_kg_m3 = optional_number(s, "density_kg_m3", 65.0, positive_value, "> 0");
  }
  if (const auto n = top.find("noise")) {
    n->expect_object({"seed", "force_relative", "force_floor_N"});
    truth.noise.seed = static_cast<unsigned long long>(optional_integer(*n, "seed", 1, 0, 2147483647));
    truth.noise.force_relative = optional_number(*n, "force_relative", 0.0, non_negative_value, ">= 0");
    truth.noise.force_floor = optional_number(*n, "force_floor_N", 0.0, non_negative_value, ">= 0");
  }
  const std::vector<std::string> uses{"calibration", "validation"};
  if (const auto list = top.find("quasi_static")) {
    const std::size_t count = list->expect_array(1, 100);
    for (std::size_t i = 0; i < count; ++i) {
      const io::JsonNode q = (*list)[i];
      q.expect_object({"name", "rate_mm_min", "max_strain", "hold_s", "sample_hz", "preload_cycle", "rest_s",
                       "lateral", "use", "preflex_cycles", "preflex_strain", "rest_between_tests_s", "lift_off"});
      QuasiStaticProtocol p;
      p.name = q.at("name").string();
      p.rate_mm_min = q.at("rate_mm_min").number_where(positive_value, "> 0");
      p.max_strain = optional_number(q, "max_strain", 0.75, [](double x) { return x > 0.0 && x < 0.95; },
                                     "in (0, 0.95) (nominal compression)");
      p.hold_s = optional_number(q, "hold_s", 2.0, non_negative_value, ">= 0");
      p.sample_hz = optional_number(q, "sample_hz", 10.0, positive_value, "> 0");
      p.prior = read_legacy_preflex(q, p.max_strain);
      if (const auto l = q.find("lift_off")) p.lift_off = l->boolean();
      p.lateral = optional_choice(q, "lateral", {"free", "constrained"}, "free") == "free"
                      ? material::LoadMode::uniaxial_free
                      : material::LoadMode::uniaxial_constrained;
      p.use = optional_choice(q, "use", uses, "");
      truth.quasi_static.push_back(p);
    }
  }
  if (const auto list = top.find("dynamic")) {
    const std::size_t count = list->expect_array(1, 100);
    for (std::size_t i = 0; i < count; ++i) {
      const io::JsonNode d = (*list)[i];
      d.expect_object({"name", "preload_strain", "preload_rate_mm_min", "acceleration_amplitude_m_s2", "amplitude_is",
                       "amplitude_convention", "frequencies_Hz", "cycles", "fit_cycles", "steps_per_cycle", "use",
                       "dwell_before_sweep_s", "preflex_cycles", "preflex_strain", "rest_between_tests_s", "lift_off"});
      DynamicProtocol p;
      p.name = d.at("name").string();
      p.preload_strain = d.at("preload_strain").number_where([](double x) { return x > 0.0 && x < 0.9; }, "in (0, 0.9)");
      p.preload_rate_mm_min = optional_number(d, "preload_rate_mm_min", 30.0, positive_value, "> 0");
      p.acceleration_amplitude = d.at("acceleration_amplitude_m_s2").number_where(positive_value, "> 0");
      p.amplitude_peak_to_peak = read_peak_to_peak(d);
      p.dwell_s = optional_number(d, "dwell_before_sweep_s", 0.0, non_negative_value, ">= 0");
      p.prior = read_prior_loading(d);
      if (const auto l = d.find("lift_off")) p.lift_off = l->boolean();
      const io::JsonNode freqs = d.at("frequencies_Hz");
      const std::size_t nf = freqs.expect_array(3, 1000);
      for (std::size_t k = 0; k < nf; ++k) p.frequencies_Hz.push_back(freqs[k].number_where(positive_value, "> 0"));
      p.cycles = optional_integer(d, "cycles", 20, 2, 100000);
      p.fit_cycles = optional_integer(d, "fit_cycles", 10, 1, p.cycles);
      p.steps_per_cycle = optional_integer(d, "steps_per_cycle", 64, 16, 100000);
      p.use = optional_choice(d, "use", uses, "");
      truth.dynamic.push_back(p);
    }
  }
  if (truth.quasi_static.empty() && truth.dynamic.empty())
    throw InputError(src + ": the truth defines no test (quasi_static or dynamic)");
  return truth;
}

QuasiStaticRecord run_quasi_static(const material::Material& model, const LabSpecimen& specimen,
                                   const QuasiStaticProtocol& p) {
  const double H = specimen.thickness;
  const double speed = p.rate_mm_min / 60.0;  // mm/s
  const double ramp_s = p.max_strain * H / speed;
  const int ramp_steps = static_cast<int>(std::ceil(ramp_s * p.sample_hz));
  std::vector<Segment> segments;
  const double test_start = append_prior_loading(segments, p.prior, H, speed, p.sample_hz);
  segments.push_back(ramp(-p.max_strain, ramp_s, ramp_steps));
  if (p.hold_s > 0.0) segments.push_back(hold(p.hold_s, static_cast<int>(std::ceil(p.hold_s * p.sample_hz))));
  segments.push_back(ramp(0.0, ramp_s, ramp_steps));
  const material::History history = material::build_history(segments, axis_control(p.lift_off));
  const material::PointResult r = material::run_point(model, p.lateral, history);

  QuasiStaticRecord rec;
  for (std::size_t k = 0; k < r.time.size(); ++k) {
    if (r.time[k] < test_start - 1e-9) continue;
    rec.time_s.push_back(r.time[k] - test_start);
    rec.displacement_mm.push_back(-history.control[k] * H);      // crosshead (platen) travel
    rec.force_N.push_back(-r.P[k](0, 0) * specimen.area());       // compression positive [N]
  }
  return rec;
}

void add_force_noise(QuasiStaticRecord& record, const LabNoise& noise, unsigned long long stream) {
  if (noise.force_relative <= 0.0 && noise.force_floor <= 0.0) return;
  Gaussian g(noise.seed, stream);
  for (double& f : record.force_N) {
    const double sd = std::hypot(noise.force_relative * f, noise.force_floor);
    f += sd * g.next();
  }
}

DynamicRecord run_dynamic(const material::Material& model, const LabSpecimen& specimen, const DynamicProtocol& p,
                          const LabNoise& noise, unsigned long long stream) {
  const double H = specimen.thickness;
  const double speed = p.preload_rate_mm_min / 60.0;  // mm/s
  const double preload_s = p.preload_strain * H / speed;
  std::vector<Segment> segments;
  double t = append_prior_loading(segments, p.prior, H, speed, 5.0);
  segments.push_back(ramp(-p.preload_strain, preload_s, static_cast<int>(std::ceil(preload_s * 5.0))));
  t += preload_s;
  if (p.dwell_s > 0.0) {
    segments.push_back(hold(p.dwell_s, static_cast<int>(std::ceil(p.dwell_s * 20.0))));
    t += p.dwell_s;
  }
  std::vector<double> start;  // start time of each frequency's sine
  for (double f : p.frequencies_Hz) {
    Segment s;
    s.kind = Segment::Kind::sine;
    s.amplitude = p.displacement_amplitude_mm(f) / H;
    s.frequency = f;
    // The transient cycles, then the fitted ones: two sines of whole cycles, so the second starts where the first
    // began (build_history: a sine about the control value where it starts) and the path is the one sine.
    const int transient = p.cycles - p.fit_cycles;
    if (transient > 0) {
      s.cycles = transient;
      s.steps = transient * (p.transient_steps_per_cycle > 0 ? p.transient_steps_per_cycle : p.steps_per_cycle);
      segments.push_back(s);
    }
    s.cycles = p.fit_cycles;
    s.steps = p.fit_cycles * p.steps_per_cycle;
    segments.push_back(s);
    start.push_back(t);
    t += p.cycles / f;
  }
  const material::History history = material::build_history(segments, axis_control(p.lift_off));
  const material::PointResult r = material::run_point(model, material::LoadMode::uniaxial_free, history);

  const bool noisy = noise.force_relative > 0.0 || noise.force_floor > 0.0;
  Gaussian g(noise.seed, stream);
  DynamicRecord rec;
  for (std::size_t i = 0; i < p.frequencies_Hz.size(); ++i) {
    const double f = p.frequencies_Hz[i];
    const double t_end = start[i] + p.cycles / f;
    const double t_begin = t_end - p.fit_cycles / f;
    std::vector<double> ts, strain, force;
    for (std::size_t k = 0; k < r.time.size(); ++k) {
      if (r.time[k] < t_begin - 1e-9 || r.time[k] > t_end + 1e-9) continue;
      ts.push_back(r.time[k] - start[i]);
      strain.push_back(-history.control[k]);
      force.push_back(-r.P[k](0, 0) * specimen.area());
    }
    if (noisy) {
      // Noise relative to the oscillating force (the load cell's dynamic reading), not to the static preload.
      const double amplitude = std::abs(fit_sine(ts, force, f).phasor);
      const double sd = std::hypot(noise.force_relative * amplitude, noise.force_floor);
      for (double& x : force) x += sd * g.next();
    }
    std::vector<double> stress(force.size());
    for (std::size_t k = 0; k < force.size(); ++k) stress[k] = force[k] / specimen.area();
    const std::complex<double> E = fit_sine(ts, stress, f).phasor / fit_sine(ts, strain, f).phasor;  // MPa
    rec.frequency_Hz.push_back(f);
    rec.dynamic_modulus_kPa.push_back(std::abs(E) * 1000.0);
    rec.phase_deg.push_back(std::arg(E) * 180.0 / std::numbers::pi);
  }
  return rec;
}

io::OutputFolder lab_output_folder(const std::filesystem::path& dir, bool overwrite, const LabTruth& truth) {
  io::OutputFolder f;
  f.dir = dir;
  f.overwrite = overwrite;
  f.command = "cushion lab";
  f.markers = {"campaign.json"};
  f.inputs = {truth.file, truth.material_file};
  f.staged_next_to_it = true;
  return f;
}

void run_lab(const LabTruth& truth, const std::filesystem::path& out_dir, std::ostream& log) {
  namespace fs = std::filesystem;
  const material::MaterialDefinition def = material::read_material_file(truth.material_file);
  io::check_output_folder(lab_output_folder(out_dir, true, truth));
  const fs::path tmp = out_dir.string() + ".partial";
  fs::remove_all(tmp);
  io::create_folder(tmp);

  nlohmann::json manifest;
  manifest["description"] = "SYNTHETIC campaign generated by `cushion lab` from " + truth.material_file.filename().string() +
                            (truth.description.empty() ? "" : ": " + truth.description);
  manifest["specimen"] = {{"length_mm", truth.specimen.length},
                          {"width_mm", truth.specimen.width},
                          {"thickness_mm", truth.specimen.thickness},
                          {"density_kg_m3", truth.specimen.density_kg_m3}};
  manifest["tests"] = nlohmann::json::array();
  unsigned long long stream = 0;
  for (const auto& p : truth.quasi_static) {
    QuasiStaticRecord rec = run_quasi_static(*def.model, truth.specimen, p);
    add_force_noise(rec, truth.noise, stream++);
    const std::string file = p.name + ".csv";
    write_csv(tmp / file, {"time_s", "displacement_mm", "force_N"}, {rec.time_s, rec.displacement_mm, rec.force_N},
              {"synthetic quasi-static test from cushion lab: " + p.name, "compression positive"});
    nlohmann::json t{{"kind", "quasi_static"}, {"name", p.name}, {"file", file}, {"rate_mm_min", p.rate_mm_min},
                     {"lateral", p.lateral == material::LoadMode::uniaxial_free ? "free" : "constrained"},
                     {"lift_off", p.lift_off}};
    write_prior_loading(p.prior, t);
    if (!p.use.empty()) t["use"] = p.use;
    manifest["tests"].push_back(t);
    double fmax = 0.0;
    for (double f : rec.force_N) fmax = std::max(fmax, f);
    log << "lab: " << p.name << ": quasi-static " << p.rate_mm_min << " mm/min to " << p.max_strain * 100.0
        << "%, " << rec.time_s.size() << " samples, peak force " << fmax << " N\n";
  }
  for (const auto& p : truth.dynamic) {
    const DynamicRecord rec = run_dynamic(*def.model, truth.specimen, p, truth.noise, stream++);
    const std::string file = p.name + ".csv";
    write_csv(tmp / file, {"frequency_Hz", "dynamic_modulus_kPa", "phase_deg"},
              {rec.frequency_Hz, rec.dynamic_modulus_kPa, rec.phase_deg},
              {"synthetic dynamic test from cushion lab: " + p.name,
               "nominal stress amplitude over nominal strain amplitude; phase of stress relative to strain"});
    nlohmann::json t{{"kind", "dynamic"}, {"name", p.name}, {"file", file}, {"preload_strain", p.preload_strain},
                     {"acceleration_amplitude_m_s2", p.acceleration_amplitude},
                     {"amplitude_convention", p.amplitude_peak_to_peak ? "peak_to_peak" : "peak"},
                     {"preload_rate_mm_min", p.preload_rate_mm_min}, {"dwell_before_sweep_s", p.dwell_s},
                     {"cycles", p.cycles}, {"fit_cycles", p.fit_cycles}, {"lift_off", p.lift_off}};
    write_prior_loading(p.prior, t);
    if (!p.use.empty()) t["use"] = p.use;
    manifest["tests"].push_back(t);
    log << "lab: " << p.name << ": dynamic about " << p.preload_strain * 100.0 << "% preload, "
        << rec.frequency_Hz.size() << " frequencies, |E*| " << rec.dynamic_modulus_kPa.front() << " .. "
        << rec.dynamic_modulus_kPa.back() << " kPa\n";
  }
  {
    std::ofstream out(tmp / "campaign.json");
    out << manifest.dump(2) << "\n";
    if (!out) throw std::runtime_error((tmp / "campaign.json").string() + ": cannot write");
  }
  io::replace_folder(tmp, out_dir);
}

}  // namespace cushion::calibration
