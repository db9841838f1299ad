#include "calibration/compare_structure_data.hpp"

#include <cmath>
#include <complex>
#include <numbers>

#include "io/input_error.hpp"
#include "io/csv.hpp"

namespace cushion::calibration {

namespace fs = std::filesystem;

namespace {

const char* axis_digit(int axis) { return axis == 0 ? "1" : axis == 1 ? "2" : "3"; }

std::string row_text(const CsvTable& t, std::size_t i, const std::string& column) {
  return t.source + ": data row " + std::to_string(i + 1) + ", column " + column + ": ";
}

void require_file(const fs::path& file, const std::string& what) {
  if (!fs::exists(file)) throw InputError(file.string() + ": no such file (" + what + ")");
}

/// Frequencies strictly increasing and positive.
void check_frequencies(const CsvTable& t) {
  const auto& f = t.col("frequency_Hz");
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (!(f[i] > 0.0)) throw InputError(row_text(t, i, "frequency_Hz") + "frequency must be positive");
    if (i > 0 && !(f[i] > f[i - 1])) throw InputError(row_text(t, i, "frequency_Hz") + "frequencies must be strictly increasing");
  }
}

}  // namespace

IndentationCurve read_indentation_csv(const fs::path& file) {
  const CsvTable t = read_csv(file);
  require_columns(t, {{"indentation_mm", "force_N"}});
  if (t.rows() < 8) throw InputError(t.source + ": only " + std::to_string(t.rows()) + " rows: need at least 8");
  IndentationCurve c{t.col("indentation_mm"), t.col("force_N")};
  double peak = 0.0;
  for (double x : c.indentation) peak = std::max(peak, x);
  if (!(peak > 0.0)) throw InputError(t.source + ": column indentation_mm: no positive indentation (compression positive)");
  return c;
}

StiffnessSpectrum read_stiffness_csv(const fs::path& file) {
  const CsvTable t = read_csv(file);
  const std::size_t set = require_columns(t, {{"frequency_Hz", "dynamic_stiffness_N_per_mm", "phase_deg"},
                                              {"frequency_Hz", "storage_stiffness_N_per_mm", "loss_stiffness_N_per_mm"}});
  if (t.rows() < 3) throw InputError(t.source + ": only " + std::to_string(t.rows()) + " frequencies: need at least 3");
  check_frequencies(t);
  StiffnessSpectrum s;
  s.frequency = t.col("frequency_Hz");
  for (std::size_t i = 0; i < t.rows(); ++i) {
    if (set == 0) {
      const double k = t.col("dynamic_stiffness_N_per_mm")[i], phase = t.col("phase_deg")[i];
      if (!(k > 0.0)) throw InputError(row_text(t, i, "dynamic_stiffness_N_per_mm") + "must be positive");
      if (!(phase > -180.0 && phase <= 180.0)) throw InputError(row_text(t, i, "phase_deg") + "must be in (-180, 180]");
      s.amplitude.push_back(k);
      s.phase.push_back(phase);
    } else {
      const std::complex<double> k(t.col("storage_stiffness_N_per_mm")[i], t.col("loss_stiffness_N_per_mm")[i]);
      if (!(std::abs(k) > 0.0)) throw InputError(row_text(t, i, "storage_stiffness_N_per_mm") + "zero stiffness");
      s.amplitude.push_back(std::abs(k));
      s.phase.push_back(std::arg(k) * 180.0 / std::numbers::pi);
    }
  }
  return s;
}

fs::path model_file(const fs::path& run, const IndentationTest& test) {
  return run / (test.contact.empty() ? std::string("history.csv") : "contact_" + test.contact + ".csv");
}

fs::path model_file(const fs::path& run, const StiffnessTest& test) { return run / (test.sweep_step + "_sweep.csv"); }

IndentationCurve read_model_indentation(const fs::path& run, const IndentationTest& test) {
  const fs::path file = model_file(run, test);
  require_file(file, "model side of test " + test.name);
  const CsvTable t = read_csv(file);
  const std::string prefix = test.contact.empty() ? test.history_set : test.contact;
  const std::string u = prefix + ".U" + axis_digit(test.axis) + "_mm";
  const std::string f = prefix + (test.contact.empty() ? ".RF" : ".F") + axis_digit(test.axis) + "_N";
  require_columns(t, {{u, f}});
  const auto& U = t.col(u);
  const auto& F = t.col(f);
  double largest = 0.0;  // the signed travel of largest magnitude
  for (double x : U)
    if (std::abs(x) > std::abs(largest)) largest = x;
  if (largest == 0.0) throw InputError(t.source + ": column " + u + ": the indenter never moves");
  const double s = largest > 0.0 ? 1.0 : -1.0;
  IndentationCurve c;
  for (std::size_t i = 0; i < U.size(); ++i) {
    c.indentation.push_back(s * U[i]);
    c.force.push_back(s * F[i] * test.model_force_factor);
  }
  return c;
}

StiffnessSpectrum read_model_stiffness(const fs::path& run, const StiffnessTest& test) {
  const fs::path file = model_file(run, test);
  require_file(file, "model side of test " + test.name);
  StiffnessSpectrum s = read_stiffness_csv(file);
  for (double& k : s.amplitude) k *= test.model_force_factor;
  return s;
}

}  // namespace cushion::calibration
