#pragma once
/// Test-data generation for the diagnose benchmark (issue 15), INDEPENDENT of cushion's material/ and
/// calibration/: the physical effects are written here in their own functional forms (several per
/// family), with their own parameters. Family names are cushion's catalogue names so that a verdict can
/// be scored; nothing else is shared.
///
/// 1D, compression positive: e nominal strain, l = 1 - e, e' = de/dt, s stresses in kPa.
/// An effect acts in one of three places of the step (foreign_machine.hpp):
///   soften   the elastic stress s_e before the Prony decorator sees it (mullins forms);
///   factor   a multiplier on each Prony weight a_j (foreign_foam.hpp), at the increment's (midpoint) strain
///            (strain_dependent_prony forms);
///   extra    a stress added to the total (pneumatic, friction, stiffness_damping forms).
/// Forms (equation in one line each; the parameter named "magnitude" in effect_forms() is the one
/// rescaled so that the effect is 10-50 x the noise in at least one test):
///   pneumatic/stretch_maxwell        Maxwell branch, h' = E(l) e' - h/tau(l), E = E0 l^-p, tau = tau0 l^-m
///   pneumatic/darcy                  s = C e'/l^(n+1), C = eta R^2/(8 K0) (Darcy flow, K = K0 l^n, pressure/J)
///   pneumatic/power_law_dashpot      s = c0 l^-m |e'|^q sign(e'), q in 0.5..0.8
///   friction/jenkins                 spring k in series with a slider: z += k de, |z| <= s_y, s = z
///   friction/bouc_wen                dz/de = (s_y/e_y) [1 - (b sign(z de) + 1 - b) |z/s_y|^n], s = z
///   friction/dahl                    dz/de = (s_y/e_y) max(0, 1 - z sign(de)/s_y)^a, s = z
///   mullins/ogden_roxburgh           s = eta s_e, eta = 1 - erf((W_max - W)/(m + beta W_max))/r
///   mullins/exponential_damage       s = (1 - d_inf (1 - exp(-e_max/e_d))) s_e
///   mullins/qi_boyce_like            s = s_e [1 - a_inf tanh(e_max/e_s) (1 - (e/e_max)^p)]
///   stiffness_damping/stiffness_proportional  s = beta E_t(e) e'
///   stiffness_damping/fractional     s = c D^q e, q in 0.3..0.7, as a Maxwell bank of the spring-pot's
///                                    relaxation spectrum H(tau) = c sin(q pi)/pi tau^-q, tau 1e-5..1e4 s
///   stiffness_damping/secant_proportional     s = beta (s_e(e)/e) e'
///   strain_dependent_prony/power_law a_j -> a_j l^-c
///   strain_dependent_prony/exponential a_j -> a_j exp(k e)
///   strain_dependent_prony/linear_per_term a_j -> a_j (1 + K w_j e), w_j in 0.2..1 per term
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "foreign_foam.hpp"
#include "foreign_random.hpp"

namespace foreign_bench {

/// One effect of a truth: family (cushion's catalogue name), form, parameters (units in the names).
struct EffectSpec {
  std::string family, form;
  std::map<std::string, double> parameters;
};

/// One time increment of the test machine (strain compression positive).
struct Increment {
  double dt_s = 0.0;
  double strain_old = 0.0, strain_new = 0.0;
  double strain_rate_per_s() const { return (strain_new - strain_old) / dt_s; }
  double strain_mid() const { return 0.5 * (strain_old + strain_new); }
};

class Effect {
 public:
  virtual ~Effect() = default;
  /// Elastic stress after softening, at the increment's end (may advance the effect's memory).
  virtual double soften_kPa(const Increment& inc, double elastic_kPa) { return elastic_kPa; }
  /// Multiplier of Prony weight j over the increment.
  virtual double prony_factor(std::size_t term, const Increment& inc) const { return 1.0; }
  /// Stress added to the total at the increment's end (advances the effect's internal variables).
  virtual double extra_stress_kPa(const Increment& inc) { return 0.0; }
};

/// A fresh (virgin, relaxed) effect for a test.
std::unique_ptr<Effect> make_effect(const EffectSpec& spec, const BaseFoam& foam);

struct EffectForm {
  std::string family, form;
  std::string magnitude;                ///< the parameter the scaling rescales
  double magnitude_lo, magnitude_hi;    ///< its search range
  std::string equation;                 ///< one line, for truth.json and the report
};

const std::vector<EffectForm>& effect_forms();
/// The five families, in catalogue order: pneumatic, friction, mullins, stiffness_damping, strain_dependent_prony.
const std::vector<std::string>& effect_families();
std::vector<const EffectForm*> forms_of_family(const std::string& family);
const EffectForm& find_form(const std::string& family, const std::string& form);

/// Random shape parameters of a form (the magnitude at the geometric middle of its range).
EffectSpec draw_effect_shape(const EffectForm& form, const BaseFoam& foam, Random& random);

/// Derived values written to truth.json for reading (e.g. the Darcy permeability from C).
void add_derived_parameters(EffectSpec& spec);

}  // namespace foreign_bench
