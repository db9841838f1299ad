#include "calibration/abaqus_cards.hpp"

#include <sstream>

namespace cushion::calibration {

namespace {

/// ABAQUS data lines hold at most 8 values: writes `values` 8 per line.
void data_lines(std::ostringstream& o, const std::vector<double>& values) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    o << values[i];
    o << ((i + 1) % 8 == 0 || i + 1 == values.size() ? "\n" : ", ");
  }
}

}  // namespace

std::string abaqus_cards(const ViscoHyperfoam& m, const std::string& name, double density, const std::string& comment) {
  std::ostringstream o;
  o.precision(10);
  std::istringstream lines(comment);
  for (std::string line; std::getline(lines, line);) o << "** " << line << "\n";
  o << "** Units: mm, N, s, t (tonne); stresses and mu_i in MPa (N/mm^2), density in t/mm^3.\n";
  o << "*MATERIAL, NAME=" << name << "\n";
  if (density > 0.0) o << "*DENSITY\n" << density << "\n";
  o << "*HYPERFOAM, N=" << m.terms.size() << ", MODULI=LONG TERM\n";
  std::vector<double> values;
  for (const auto& t : m.terms) {
    values.push_back(t.mu);
    values.push_back(t.alpha);
  }
  for (const auto& t : m.terms) values.push_back(t.nu);
  data_lines(o, values);
  if (!m.prony.empty()) {
    o << "*VISCOELASTIC, TIME=PRONY\n";
    o << "** g_i, k_i, tau_i [s]: relative moduli, same relaxation in shear and bulk\n";
    for (const auto& t : m.prony) o << t.g << ", " << t.g << ", " << t.tau << "\n";
  }
  return o.str();
}

}  // namespace cushion::calibration
