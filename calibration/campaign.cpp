#include "calibration/campaign.hpp"

#include <cmath>
#include <fstream>
#include <numbers>
#include <optional>

#include "io/input_error.hpp"
#include "io/csv.hpp"
#include "io/json_reader.hpp"

namespace cushion::calibration {

std::vector<int> data_row_lines(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::vector<int> lines;
  std::string text;
  int number = 0;
  bool header = false;
  while (std::getline(in, text)) {
    ++number;
    const auto first = text.find_first_not_of(" \t\r");
    if (first == std::string::npos || text[first] == '#') continue;
    if (!header) header = true;
    else lines.push_back(number);
  }
  return lines;
}

std::string at_line(const std::string& source, const std::vector<int>& lines, std::size_t row,
                    const std::string& column) {
  const int line = row < lines.size() ? lines[row] : 0;
  return source + ":" + std::to_string(line) + ", column " + column + ": ";
}

namespace {

bool positive(double x) { return x > 0.0; }
bool unit_interval(double x) { return x >= 0.0 && x < 1.0; }

/// A structure-level test (compare_structure_data.hpp): keys checked, measurement read.
void read_structure_test(const io::JsonNode& t, const std::string& kind, const std::filesystem::path& folder, Campaign& c) {
  const std::filesystem::path file = folder / t.at("file").string();
  const std::string name = t.find("name") ? t.at("name").string() : file.stem().string();
  const double factor = t.find("model_force_factor") ? t.at("model_force_factor").number_where(positive, "> 0") : 1.0;
  if (kind == "indentation") {
    t.expect_object({"kind", "file", "name", "description", "contact", "history_set", "axis", "model_force_factor"});
    IndentationTest q;
    q.name = name;
    q.file = file;
    q.model_force_factor = factor;
    if (t.has("contact") == t.has("history_set"))
      t.fail("give exactly one model source: \"contact\" (contact_<name>.csv of the run) or \"history_set\" (history.csv)");
    if (auto k = t.find("contact")) q.contact = k->string();
    if (auto h = t.find("history_set")) q.history_set = h->string();
    if (auto a = t.find("axis")) {
      const std::string axis = a->choice({"x", "y", "z"});
      q.axis = axis == "x" ? 0 : axis == "y" ? 1 : 2;
    }
    q.record = read_indentation_csv(file);
    c.indentation.push_back(std::move(q));
  } else {
    t.expect_object({"kind", "file", "name", "description", "sweep_step", "model_force_factor"});
    StiffnessTest d;
    d.name = name;
    d.file = file;
    d.model_force_factor = factor;
    d.sweep_step = t.at("sweep_step").string();
    d.record = read_stiffness_csv(file);
    c.stiffness.push_back(std::move(d));
  }
}

}  // namespace

StressStrainRecord read_quasi_static_csv(const std::filesystem::path& file, const Specimen& specimen) {
  const CsvTable t = read_csv(file);
  require_columns(t, {{"time_s", "displacement_mm", "force_N"}});
  const auto lines = data_row_lines(file);
  return to_nominal(t.source, t.col("time_s"), t.col("displacement_mm"), t.col("force_N"), specimen, lines);
}

DynamicModuli read_dynamic_csv(const std::filesystem::path& file, const Specimen& specimen) {
  const CsvTable t = read_csv(file);
  const std::size_t set = require_columns(t, {{"frequency_Hz", "dynamic_modulus_kPa", "phase_deg"},
                                              {"frequency_Hz", "storage_modulus_kPa", "loss_modulus_kPa"},
                                              {"frequency_Hz", "dynamic_stiffness_N_per_mm", "phase_deg"}});
  const auto lines = data_row_lines(file);
  if (t.rows() < 3)
    throw InputError(t.source + ": only " + std::to_string(t.rows()) + " frequencies: need at least 3");
  DynamicModuli d;
  const auto& f = t.col("frequency_Hz");
  for (std::size_t i = 0; i < t.rows(); ++i) {
    if (!(f[i] > 0.0)) throw InputError(at_line(t.source, lines, i, "frequency_Hz") + "frequency must be positive");
    if (i > 0 && !(f[i] > f[i - 1]))
      throw InputError(at_line(t.source, lines, i, "frequency_Hz") + "frequencies must be strictly increasing");
    double Es = 0.0, El = 0.0;
    if (set == 1) {
      Es = t.col("storage_modulus_kPa")[i] * 1e-3;
      El = t.col("loss_modulus_kPa")[i] * 1e-3;
      if (!(Es > 0.0)) throw InputError(at_line(t.source, lines, i, "storage_modulus_kPa") + "must be positive");
      if (!std::isfinite(El)) throw InputError(at_line(t.source, lines, i, "loss_modulus_kPa") + "must be a number");
    } else {
      const std::string mcol = set == 0 ? "dynamic_modulus_kPa" : "dynamic_stiffness_N_per_mm";
      const double m = t.col(mcol)[i];
      const double phase = t.col("phase_deg")[i];
      if (!(m > 0.0)) throw InputError(at_line(t.source, lines, i, mcol) + "must be positive");
      // A phase <= 0 is accepted: the noise of a nearly elastic response at a tiny force amplitude can give one.
      if (!(phase > -90.0 && phase < 90.0))
        throw InputError(at_line(t.source, lines, i, "phase_deg") + "phase must be in (-90, 90) degrees");
      const double E = set == 0 ? m * 1e-3 : m * specimen.thickness / specimen.area();  // MPa
      const double rad = phase * std::numbers::pi / 180.0;
      Es = E * std::cos(rad);
      El = E * std::sin(rad);
    }
    d.frequency.push_back(f[i]);
    d.storage.push_back(Es);
    d.loss.push_back(El);
  }
  return d;
}

const QuasiStaticTest* Campaign::quasi_static_calibration() const {
  for (const auto& t : quasi_static)
    if (t.use == TestUse::calibration) return &t;
  return nullptr;
}

std::vector<const QuasiStaticTest*> Campaign::quasi_static_calibration_tests() const {
  std::vector<const QuasiStaticTest*> out;
  for (const auto& t : quasi_static)
    if (t.use == TestUse::calibration) out.push_back(&t);
  return out;
}

const DynamicTest* Campaign::dynamic_calibration() const {
  for (const auto& t : dynamic)
    if (t.use == TestUse::calibration) return &t;
  return nullptr;
}

namespace {

/// The specimen block: dimensions [mm] and density (kg/m^3 in the file, t/mm^3 here).
Specimen read_specimen(const io::JsonNode& sp) {
  sp.expect_object({"length_mm", "width_mm", "thickness_mm", "density_kg_m3"});
  Specimen s;
  s.length = sp.at("length_mm").number_where(positive, "> 0");
  s.width = sp.at("width_mm").number_where(positive, "> 0");
  s.thickness = sp.at("thickness_mm").number_where(positive, "> 0");
  s.density = sp.at("density_kg_m3").number_where(positive, "> 0") * 1e-12;  // kg/m^3 -> t/mm^3
  return s;
}

/// A material test (quasi-static or dynamic) whose keys are checked and whose use is not yet resolved.
struct PendingTest {
  std::string kind;
  std::optional<TestUse> use;  ///< explicit "use", if any
  io::JsonNode node;
};

/// The material tests of the manifest, keys checked, with their explicit use (at most one dynamic
/// calibration test); structure tests are read into the campaign at once.
std::vector<PendingTest> scan_tests(const io::JsonNode& tests, const std::filesystem::path& folder, Campaign& c,
                                    bool& qs_calibration_given, bool& dyn_calibration_given) {
  const std::size_t n = tests.expect_array(1, 1000);
  std::vector<PendingTest> pending;
  std::optional<std::string> qs_cal, dyn_cal;  // key path of the explicit calibration test
  for (std::size_t i = 0; i < n; ++i) {
    const io::JsonNode t = tests[i];
    const std::string kind = t.at("kind").choice({"quasi_static", "dynamic", "indentation", "dynamic_stiffness"});
    if (kind == "indentation" || kind == "dynamic_stiffness") {
      read_structure_test(t, kind, folder, c);
      continue;
    }
    if (kind == "quasi_static")
      t.expect_object({"kind", "file", "name", "use", "rate_mm_min", "lateral", "preflex_cycles", "preflex_strain",
                       "rest_between_tests_s", "lift_off"});
    else
      t.expect_object({"kind", "file", "name", "use", "preload_strain", "acceleration_amplitude_m_s2", "amplitude_is",
                       "amplitude_convention", "preload_rate_mm_min", "dwell_before_sweep_s", "cycles", "fit_cycles",
                       "preflex_cycles", "preflex_strain", "rest_between_tests_s", "lift_off"});
    std::optional<TestUse> use;
    if (auto u = t.find("use")) {
      use = u->choice({"calibration", "validation"}) == "calibration" ? TestUse::calibration : TestUse::validation;
      if (*use == TestUse::calibration) {
        auto& first = kind == "quasi_static" ? qs_cal : dyn_cal;
        if (first && kind == "dynamic") u->fail("a second " + kind + " calibration test (" + *first + " already is one)");
        if (!first) first = t.path();
      }
    }
    pending.push_back({kind, use, t});
  }
  qs_calibration_given = qs_cal.has_value();
  dyn_calibration_given = dyn_cal.has_value();
  return pending;
}

/// The keys of `keys` a test object does not give.
std::vector<std::string> unrecorded_keys(const io::JsonNode& t, std::initializer_list<const char*> keys) {
  std::vector<std::string> out;
  for (const char* k : keys)
    if (!t.find(k)) out.push_back(k);
  return out;
}

/// A quasi-static test: rate [mm/min in the file, mm/s here], lateral condition, record.
QuasiStaticTest read_quasi_static_test(const io::JsonNode& t, std::string name, const std::filesystem::path& file,
                                       TestUse use, const Specimen& specimen) {
  QuasiStaticTest q;
  q.name = std::move(name);
  q.file = file;
  q.use = use;
  q.rate = t.at("rate_mm_min").number_where(positive, "> 0") / 60.0;
  if (auto l = t.find("lateral")) q.lateral = l->choice({"free", "constrained"}) == "free" ? Lateral::free : Lateral::constrained;
  q.prior = read_prior_loading(t);
  if (auto l = t.find("lift_off")) q.lift_off = l->boolean();
  q.unrecorded = unrecorded_keys(t, {"preflex_cycles", "lift_off"});
  q.record = read_quasi_static_csv(file, specimen);
  return q;
}

/// A dynamic test: preload strain, acceleration amplitude [m/s^2 in the file, mm/s^2 here], moduli.
DynamicTest read_dynamic_test(const io::JsonNode& t, std::string name, const std::filesystem::path& file, TestUse use,
                              const Specimen& specimen) {
  DynamicTest d;
  d.name = std::move(name);
  d.file = file;
  d.use = use;
  d.preload_strain = t.at("preload_strain").number_where(unit_interval, "in [0, 1)");
  d.acceleration_amplitude = t.at("acceleration_amplitude_m_s2").number_where(positive, "> 0") * 1e3;
  d.amplitude_peak_to_peak = read_peak_to_peak(t);
  if (auto r = t.find("preload_rate_mm_min")) d.preload_rate_mm_min = r->number_where(positive, "> 0");
  if (auto w = t.find("dwell_before_sweep_s")) d.dwell_s = w->number_where([](double x) { return x >= 0.0; }, ">= 0");
  if (auto c = t.find("cycles")) d.cycles = static_cast<int>(c->integer(1, 100000));
  if (auto c = t.find("fit_cycles")) d.fit_cycles = static_cast<int>(c->integer(1, d.cycles));
  else if (d.fit_cycles > d.cycles) t.at("cycles").fail("fewer than the default fit_cycles 10: give fit_cycles too");
  d.prior = read_prior_loading(t);
  if (auto l = t.find("lift_off")) d.lift_off = l->boolean();
  d.unrecorded = unrecorded_keys(t, {"amplitude_convention", "preload_rate_mm_min", "dwell_before_sweep_s", "cycles",
                                     "fit_cycles", "preflex_cycles", "lift_off"});
  if (t.find("amplitude_is")) std::erase(d.unrecorded, std::string("amplitude_convention"));  // its older name
  d.moduli = read_dynamic_csv(file, specimen);
  return d;
}

}  // namespace

Campaign read_campaign(const std::filesystem::path& manifest) {
  const std::string source = manifest.string();
  const nlohmann::json document = io::parse_json(io::read_text_file(source), source);
  const io::JsonNode root(document, source);
  root.expect_object({"description", "specimen", "tests"});
  Campaign c;
  c.manifest = manifest;
  if (auto d = root.find("description")) c.description = d->string();
  c.specimen = read_specimen(root.at("specimen"));

  const auto folder = manifest.parent_path();
  // Explicit "use" first, then the default: first test of a kind without an explicit use calibrates
  // if no test of that kind was declared "calibration".
  bool qs_default_taken = false, dyn_default_taken = false;
  const std::vector<PendingTest> pending = scan_tests(root.at("tests"), folder, c, qs_default_taken, dyn_default_taken);
  for (const auto& p : pending) {
    const io::JsonNode& t = p.node;
    const std::filesystem::path file = folder / t.at("file").string();
    std::string name = t.find("name") ? t.at("name").string() : file.stem().string();
    bool& taken = p.kind == "quasi_static" ? qs_default_taken : dyn_default_taken;
    TestUse use = TestUse::validation;
    if (p.use) use = *p.use;
    else if (!taken) {
      use = TestUse::calibration;
      taken = true;
    }
    if (p.kind == "quasi_static")
      c.quasi_static.push_back(read_quasi_static_test(t, std::move(name), file, use, c.specimen));
    else
      c.dynamic.push_back(read_dynamic_test(t, std::move(name), file, use, c.specimen));
  }
  return c;
}

}  // namespace cushion::calibration
