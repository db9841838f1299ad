// Materials and sections of a deck (deck_parts.hpp): *MATERIAL, *HYPERFOAM, *HYPERELASTIC (NEO HOOKE,
// OGDEN), *ELASTIC (as its small-strain neo-Hooke), *VISCOELASTIC (TIME=PRONY), *DENSITY, *SOLID SECTION. Moduli are converted with the deck's
// stress unit, density with its density unit.
#include <algorithm>
#include <cmath>

#include "io/input_error.hpp"
#include "io/text_support.hpp"
#include "solver/deck/deck_parts.hpp"

namespace cushion::solver::deck {

namespace {

/// The open material for an option keyword (InputError if none).
DeckMaterial& current(State& s, const Block& b) {
  if (s.current_material.empty()) fail(b, b.keyword, "must follow a *MATERIAL (or another option of it)");
  return s.materials.at(s.current_material);
}

/// Number of terms N= (1..6, default 1).
int terms_parameter(const Block& b) {
  const auto n = parameter(b, "N");
  if (!n) return 1;
  const int value = integer(b, b.keyword, *n);
  if (value < 1 || value > 6) fail(b, b.keyword, "N must be 1..6, found " + *n);
  return value;
}

/// MODULI=LONG TERM | INSTANTANEOUS of *HYPERFOAM / *HYPERELASTIC.
void read_moduli(DeckMaterial& m, const Block& b) {
  const auto moduli = parameter(b, "MODULI");
  if (!moduli) return;
  const std::string v = io::upper_case(*moduli);
  if (v != "LONG TERM" && v != "INSTANTANEOUS") fail(b, b.keyword, "MODULI must be LONG TERM or INSTANTANEOUS");
  m.spec.moduli = v == "LONG TERM" ? material::ModuliConvention::long_term : material::ModuliConvention::instantaneous;
  m.moduli = b.keyword;
}

/// Marks the elastic base of `m` as given (InputError on a second one).
void set_base(DeckMaterial& m, const Block& b) {
  if (m.has_base) fail(b, b.keyword, "material " + m.name + " already has an elastic base");
  m.has_base = true;
}

/// CalculiX's rule for D1 = 0 (it has no hybrid elements): an initial Poisson ratio of "0.475" (manual),
/// in fact K0 = 20 mu0 (nu = 58/122 = 0.4754), i.e. D1 = 2 / K0 = 1 / (10 mu0) [1/MPa]. Measured on the
/// CalculiX test beamog (tests/peer/calculix): K0 = 20 mu0 reproduces its displacements to 1e-6, the
/// literal nu = 0.475 (K0 = 19.67 mu0) only to 3.4e-4.
double default_D1(double mu0) { return 1.0 / (10.0 * mu0); }

/// Ogden terms (mu_i, alpha_i) and D_i into the material; D1 = 0 replaced as CalculiX does, with a warning.
void set_ogden(State& s, DeckMaterial& m, const Block& b, std::vector<material::OgdenTerm> terms, std::vector<double> D) {
  for (auto& t : terms) t.mu *= s.units.stress();
  for (double& d : D) d /= s.units.stress();
  double mu0 = 0.0;
  for (const auto& t : terms) mu0 += t.mu;
  if (!(mu0 > 0.0)) fail(b, b.keyword, "the initial shear modulus (sum of mu_i) must be > 0");
  if (D.front() == 0.0) {
    D.front() = default_D1(mu0);
    s.out.warnings.push_back(where(b.keyword) + ": *" + b.name + ": D1 = 0 (incompressible) replaced by D1 = " +
                             io::format_double(D.front() / s.units.stress()) +
                             " (bulk modulus 20 x the initial shear modulus, as CalculiX; cushion has no hybrid elements)");
  }
  m.spec.base = material::MaterialSpec::Base::ogden;
  m.spec.ogden = std::move(terms);
  m.spec.ogden_D = std::move(D);
}

}  // namespace

void material(State& s, const Block& b) {
  check_parameters(b, {"NAME"});
  if (s.step) fail(b, b.keyword, "must come before the first *STEP");
  const std::string name = required_parameter(b, "NAME");
  if (s.materials.count(io::upper_case(name))) fail(b, b.keyword, "material " + name + " is defined twice");
  DeckMaterial m;
  m.name = name;
  m.defined = b.keyword;
  m.spec.name = name;
  s.materials[io::upper_case(name)] = m;
  s.current_material = io::upper_case(name);
}

void hyperfoam(State& s, const Block& b) {
  check_parameters(b, {"N", "MODULI"});
  DeckMaterial& m = current(s, b);
  set_base(m, b);
  read_moduli(m, b);
  const int n = terms_parameter(b);
  // mu_1, alpha_1, ..., mu_N, alpha_N, nu_1, ..., nu_N (CalculiX manual *HYPERFOAM, ABAQUS alike).
  const std::vector<double> v = packed_numbers(b, 3 * static_cast<std::size_t>(n));
  m.spec.base = material::MaterialSpec::Base::hyperfoam;
  for (int i = 0; i < n; ++i) {
    const double nu = v[2 * n + i];
    if (v[2 * i + 1] == 0.0) fail(b, b.data.front(), "alpha_" + std::to_string(i + 1) + " must be non-zero");
    if (!(nu >= 0.0 && nu < 0.5)) fail(b, b.data.front(), "nu_" + std::to_string(i + 1) + " must lie in [0, 0.5)");
    m.spec.hyperfoam.push_back({v[2 * i] * s.units.stress(), v[2 * i + 1], nu});
  }
}

void hyperelastic(State& s, const Block& b) {
  check_parameters(b, {"NEO HOOKE", "OGDEN", "N", "MODULI"});
  DeckMaterial& m = current(s, b);
  set_base(m, b);
  read_moduli(m, b);
  const bool neo = parameter(b, "NEO HOOKE").has_value(), ogden = parameter(b, "OGDEN").has_value();
  if (neo == ogden)
    fail(b, b.keyword, "give NEO HOOKE or OGDEN (the other forms, and the default POLYNOMIAL, are not supported by "
                       "cushion run)");
  if (neo) {
    if (parameter(b, "N")) fail(b, b.keyword, "N is not a parameter of NEO HOOKE");
    const std::vector<double> v = packed_numbers(b, 2);  // C10, D1: W = C10 (I1bar - 3) + (J - 1)^2 / D1
    if (v[1] < 0.0) fail(b, b.data.front(), "D1 must be >= 0");
    return set_ogden(s, m, b, {{2.0 * v[0], 2.0}}, {v[1]});
  }
  const int n = terms_parameter(b);
  // mu_1, alpha_1, ..., mu_N, alpha_N, D_1, ..., D_N (CalculiX manual *HYPERELASTIC, OGDEN).
  const std::vector<double> v = packed_numbers(b, 3 * static_cast<std::size_t>(n));
  std::vector<material::OgdenTerm> terms;
  for (int i = 0; i < n; ++i) {
    if (v[2 * i + 1] == 0.0) fail(b, b.data.front(), "alpha_" + std::to_string(i + 1) + " must be non-zero");
    terms.push_back({v[2 * i], v[2 * i + 1]});
  }
  std::vector<double> D(v.begin() + 2 * n, v.end());
  if (std::any_of(D.begin(), D.end(), [](double d) { return d < 0.0; })) fail(b, b.data.front(), "D_i must be >= 0");
  set_ogden(s, m, b, std::move(terms), std::move(D));
}

void elastic(State& s, const Block& b) {
  check_parameters(b, {"TYPE"});
  if (io::upper_case(parameter(b, "TYPE").value_or("ISO")) != "ISO")
    fail(b, b.keyword, "only TYPE=ISO (isotropic) is supported by cushion run");
  DeckMaterial& m = current(s, b);
  set_base(m, b);
  const std::vector<double> v = packed_numbers(b, 2);  // E, nu
  const double E = v[0], nu = v[1];
  if (!(E > 0.0)) fail(b, b.data.front(), "Young's modulus must be > 0");
  if (!(nu > -1.0 && nu < 0.5)) fail(b, b.data.front(), "Poisson's ratio must lie in (-1, 0.5)");
  // Neo-Hooke with the same initial shear and bulk moduli: mu = 2 C10 = E / (2 (1 + nu)),
  // K = 2 / D1 = E / (3 (1 - 2 nu)) (docs/physics.md, linear elasticity as the small-strain limit).
  set_ogden(s, m, b, {{E / (2.0 * (1.0 + nu)), 2.0}}, {6.0 * (1.0 - 2.0 * nu) / E});
  m.elastic = b.keyword;
}

void damping(State& s, const Block& b) {
  check_parameters(b, {"ALPHA", "BETA", "STRUCTURAL"});
  DeckMaterial& m = current(s, b);
  if (m.damping) fail(b, b.keyword, "material " + m.name + " already has a *DAMPING");
  auto value = [&](const char* key) {
    const auto v = parameter(b, key);
    if (!v) return 0.0;
    const double x = number(b, b.keyword, *v);
    if (!(x >= 0.0)) fail(b, b.keyword, std::string(key) + " must be >= 0");
    return x;
  };
  m.damping_values = {value("ALPHA"), value("BETA"), value("STRUCTURAL")};  // [1/s], [s], [-]
  m.damping = b.keyword;
}

void viscoelastic(State& s, const Block& b) {
  check_parameters(b, {"TIME"});
  DeckMaterial& m = current(s, b);
  if (io::upper_case(required_parameter(b, "TIME")) != "PRONY") fail(b, b.keyword, "only TIME=PRONY is supported by cushion run");
  if (m.has_prony) fail(b, b.keyword, "material " + m.name + " already has a *VISCOELASTIC");
  m.has_prony = true;
  if (b.data.empty()) fail(b, b.keyword, "no Prony terms (lines 'g_i, k_i, tau_i')");
  for (const Line& line : b.data) {
    const std::vector<std::string> f = mesh::inp_fields(line.text);
    if (f.size() != 3) fail(b, line, "expected 'g_i, k_i, tau_i', got " + std::to_string(f.size()) + " fields");
    const double g = number(b, line, f[0]), k = number(b, line, f[1]), tau = number(b, line, f[2]);
    if (std::abs(k - g) > 1e-12 * std::max(1.0, std::abs(g)))
      fail(b, line, "k_i = " + f[1] + " differs from g_i = " + f[0] +
                        ": cushion's Prony series relaxes shear and bulk alike (give k_i = g_i)");
    if (!(g >= 0.0) || !(tau > 0.0)) fail(b, line, "need g_i >= 0 and tau_i > 0");
    m.spec.prony.push_back({g, tau});
  }
}

void density(State& s, const Block& b) {
  check_parameters(b, {});
  DeckMaterial& m = current(s, b);
  const double rho = packed_numbers(b, 1).front();
  if (!(rho > 0.0)) fail(b, b.data.front(), "density must be > 0");
  m.spec.density = rho * s.units.density();
}

void solid_section(State& s, const Block& b) {
  check_parameters(b, {"ELSET", "MATERIAL"});
  if (s.step) fail(b, b.keyword, "must come before the first *STEP");
  const std::string elset = element_set(s, b, b.keyword, required_parameter(b, "ELSET"));
  s.sections.push_back({b.keyword, elset, io::upper_case(required_parameter(b, "MATERIAL"))});
}

void finish_material(State& s) {
  if (s.sections.empty()) throw InputError(s.file.string() + ": no *SOLID SECTION: the elements have no material");
  const State::Section& first = s.sections.front();
  std::vector<char> covered(s.out.mesh.num_elements(), 0);
  for (const State::Section& section : s.sections) {
    auto fail_here = [&](const std::string& problem) {
      throw InputError(where(section.defined) + ": *SOLID SECTION: " + problem);
    };
    if (!s.materials.count(section.material)) fail_here("unknown material " + section.material);
    if (section.material != first.material)
      fail_here("a second material (" + section.material + " after " + first.material +
                "): cushion run takes one material per deck");
    for (int e : s.out.mesh.element_sets.at(section.elset)) covered[e] = 1;
  }
  const auto missing = std::find(covered.begin(), covered.end(), 0);
  if (missing != covered.end())
    throw InputError(s.file.string() + ": element " +
                     std::to_string(s.out.mesh.elements[missing - covered.begin()].label) +
                     " is in no *SOLID SECTION (every element needs the material)");
  const DeckMaterial& m = s.materials.at(first.material);
  if (m.elastic)
    s.out.warnings.push_back(where(*m.elastic) + ": *ELASTIC read as the compressible neo-Hooke solid with the same "
                             "initial shear and bulk moduli: identical at small strain (linear perturbation steps, "
                             "small loads), a hyperelastic solid at large strain");
  if (!m.has_base) throw InputError(where(m.defined) + ": *MATERIAL: " + m.name + " has no *HYPERFOAM, *HYPERELASTIC or *ELASTIC");
  // *DAMPING of the material: the damping of its steady-state steps (Rayleigh alpha M + beta K, structural i s K).
  for (StepSpec& step : s.out.spec.steps)
    if (step.type == StepSpec::Type::steady_state) step.steady_state.damping = m.damping_values;
    else if (step.type == StepSpec::Type::dynamic)
      step.dynamic.damping = {m.damping_values.rayleigh_alpha, m.damping_values.rayleigh_beta, 0.0};
  s.out.material = material::build_material(m.spec, where(m.defined) + ": *MATERIAL " + m.name);
}

}  // namespace cushion::solver::deck
