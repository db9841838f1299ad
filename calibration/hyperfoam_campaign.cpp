#include "calibration/hyperfoam_campaign.hpp"

#include <algorithm>
#include <cmath>

#include "calibration/campaign.hpp"
#include "io/csv.hpp"
#include "io/input_error.hpp"
#include "io/json_reader.hpp"

namespace cushion::calibration {
namespace {

bool positive(double x) { return x > 0.0; }
bool non_negative(double x) { return x >= 0.0; }

/// MPa per unit of a stress column named "..._MPa", "..._kPa" or "..._Pa"; 0 when the name carries no unit.
double stress_unit(const std::string& column) {
  auto ends = [&](const std::string& suffix) {
    return column.size() > suffix.size() && column.compare(column.size() - suffix.size(), suffix.size(), suffix) == 0;
  };
  if (ends("_MPa")) return 1.0;
  if (ends("_kPa")) return 1e-3;
  if (ends("_Pa")) return 1e-6;
  return 0.0;
}

HyperfoamMode parse_mode(const io::JsonNode& node) {
  const std::string m = node.choice({"uniaxial", "equibiaxial", "planar", "simple_shear", "volumetric"});
  if (m == "uniaxial") return HyperfoamMode::uniaxial;
  if (m == "equibiaxial") return HyperfoamMode::equibiaxial;
  if (m == "planar") return HyperfoamMode::planar;
  if (m == "simple_shear") return HyperfoamMode::simple_shear;
  return HyperfoamMode::volumetric;
}

/// The column `name` of the table (InputError naming the manifest key when absent).
const std::vector<double>& column(const CsvTable& table, const io::JsonNode& key, const std::string& name) {
  if (!table.has(name)) key.fail("column '" + name + "' is not in " + table.source);
  return table.col(name);
}

/// Checks the values of one test: stretches > 0, stress of the sign of the deformation (tension positive).
void check_rows(const HyperfoamTest& t, const std::vector<int>& lines) {
  const std::string source = t.file.string();
  if (t.control.size() < 2) throw InputError(source + ": " + std::to_string(t.control.size()) + " data rows: need at least 2");
  double peak = 0.0;
  for (double s : t.stress) peak = std::max(peak, std::abs(s));
  const bool shear = t.mode == HyperfoamMode::simple_shear;
  for (std::size_t j = 0; j < t.control.size(); ++j) {
    const double x = t.control[j];
    if (!shear && !(x > 0.0)) throw InputError(at_line(source, lines, j, t.control_column) + "stretch must be > 0");
    if (!t.lateral.empty() && !(t.lateral[j] > 0.0))
      throw InputError(at_line(source, lines, j, t.lateral_column) + "stretch must be > 0");
    const double deformation = shear ? x : x - 1.0;
    if (std::abs(t.stress[j]) > 0.01 * peak && deformation * t.stress[j] < 0.0)
      throw InputError(at_line(source, lines, j, t.stress_column) +
                       "stress has the opposite sign of the deformation: give it tension positive (compression negative)");
  }
}

HyperfoamTest read_test(const io::JsonNode& t, const std::filesystem::path& folder) {
  t.expect_object({"name", "mode", "file", "stretch_column", "shear_strain_column", "stress_column",
                   "lateral_stretch_column", "description"});
  HyperfoamTest test;
  test.mode = parse_mode(t.at("mode"));
  test.file = folder / t.at("file").string();
  test.name = t.find("name") ? t.at("name").string() : test.file.stem().string();
  const bool shear = test.mode == HyperfoamMode::simple_shear;
  const char* control_key = shear ? "shear_strain_column" : "stretch_column";
  if (t.has(shear ? "stretch_column" : "shear_strain_column"))
    t.at(shear ? "stretch_column" : "shear_strain_column").fail(std::string("not used in mode ") + to_string(test.mode) +
                                                                 ": give \"" + control_key + "\"");
  if (t.has("lateral_stretch_column") && !has_free_direction(test.mode))
    t.at("lateral_stretch_column").fail("mode " + to_string(test.mode) + " has no stress-free direction");
  test.control_column = t.at(control_key).string();
  test.stress_column = t.at("stress_column").string();
  const double unit = stress_unit(test.stress_column);
  if (unit == 0.0) t.at("stress_column").fail("the column name must end in its unit: _MPa, _kPa or _Pa");
  const CsvTable table = read_csv(test.file);
  test.control = column(table, t.at(control_key), test.control_column);
  for (double s : column(table, t.at("stress_column"), test.stress_column)) test.stress.push_back(s * unit);
  if (auto l = t.find("lateral_stretch_column")) {
    test.lateral_column = l->string();
    test.lateral = column(table, *l, test.lateral_column);
  }
  check_rows(test, data_row_lines(test.file));
  return test;
}

HyperfoamFitSettings read_settings(const io::JsonNode& f) {
  f.expect_object({"terms", "poisson", "lateral_weight", "stable_stretch"});
  HyperfoamFitSettings s;
  if (auto n = f.find("terms")) s.terms = int(n->integer(1, 6));
  if (auto p = f.find("poisson")) s.per_term_nu = p->choice({"per_term", "common"}) == "per_term";
  if (auto w = f.find("lateral_weight")) s.lateral_weight = w->number_where(non_negative, ">= 0");
  if (auto r = f.find("stable_stretch")) {
    r->expect_array(2, 2);
    const double lo = (*r)[0].number_where(positive, "> 0"), hi = (*r)[1].number();
    if (!(lo < 1.0 && hi > 1.0)) r->fail("must be [min, max] with 0 < min < 1 < max");
    s.stable_stretch = std::make_pair(lo, hi);
  }
  return s;
}

}  // namespace

std::string to_string(HyperfoamMode mode) {
  switch (mode) {
    case HyperfoamMode::uniaxial: return "uniaxial";
    case HyperfoamMode::equibiaxial: return "equibiaxial";
    case HyperfoamMode::planar: return "planar";
    case HyperfoamMode::simple_shear: return "simple_shear";
    case HyperfoamMode::volumetric: return "volumetric";
  }
  return "?";
}

bool has_free_direction(HyperfoamMode mode) {
  return mode == HyperfoamMode::uniaxial || mode == HyperfoamMode::equibiaxial || mode == HyperfoamMode::planar;
}

bool is_hyperfoam_campaign(const std::filesystem::path& manifest) {
  const std::string source = manifest.string();
  const nlohmann::json document = io::parse_json(io::read_text_file(source), source);
  return document.is_object() && document.contains("hyperfoam_tests");
}

HyperfoamCampaign read_hyperfoam_campaign(const std::filesystem::path& manifest) {
  const std::string source = manifest.string();
  const nlohmann::json document = io::parse_json(io::read_text_file(source), source);
  const io::JsonNode root(document, source);
  root.expect_object({"description", "density_kg_m3", "hyperfoam_tests", "hyperfoam_fit"});
  HyperfoamCampaign c;
  c.manifest = manifest;
  if (auto d = root.find("description")) c.description = d->string();
  if (auto d = root.find("density_kg_m3")) c.density = d->number_where(positive, "> 0") * 1e-12;  // kg/m^3 -> t/mm^3
  if (auto f = root.find("hyperfoam_fit")) c.settings = read_settings(*f);
  const io::JsonNode tests = root.at("hyperfoam_tests");
  const std::size_t n = tests.expect_array(1, 100);
  std::size_t points = 0;
  for (std::size_t i = 0; i < n; ++i) {
    c.tests.push_back(read_test(tests[i], manifest.parent_path()));
    points += c.tests.back().control.size() * (c.tests.back().lateral.empty() ? 1 : 2);
  }
  const std::size_t parameters = std::size_t(c.settings.terms) * (c.settings.per_term_nu ? 3 : 2) + 1;
  if (points < parameters)
    root.at("hyperfoam_tests").fail(std::to_string(points) + " data values for " + std::to_string(parameters) +
                                    " parameters: give more points or fewer terms");
  return c;
}

}  // namespace cushion::calibration
