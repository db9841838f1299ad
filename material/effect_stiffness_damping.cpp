#include "material/effect_stiffness_damping.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace cushion::material {

namespace {
std::shared_ptr<const Hyperelastic> checked(std::shared_ptr<const Hyperelastic> base) {
  if (!base) throw std::invalid_argument("stiffness_damping: no elastic base");
  return base;
}

SpringPotBank checked_bank(double order) {
  if (!(order > 0.0 && order <= 1.0))
    throw std::invalid_argument("stiffness_damping: derivative_order must lie in (0, 1]");
  return SpringPotBank(order);
}
}  // namespace

StiffnessDampingEffect::StiffnessDampingEffect(std::shared_ptr<const Material> inner,
                                               std::shared_ptr<const Hyperelastic> elastic_base, double beta_s,
                                               double current_share, double order, double reference_frequency_Hz,
                                               double stretch_exponent, double nominal_share)
    : StiffnessDampingEffect(std::move(inner), std::move(elastic_base), beta_s, current_share, checked_bank(order),
                             reference_frequency_Hz, stretch_exponent, nominal_share) {}

StiffnessDampingEffect::StiffnessDampingEffect(std::shared_ptr<const Material> inner,
                                               std::shared_ptr<const Hyperelastic> elastic_base, double beta_s,
                                               double current_share, SpringPotBank bank, double reference_frequency_Hz,
                                               double stretch_exponent, double nominal_share)
    : EffectDecorator(std::move(inner), bank.memory_size(6)),
      base_(checked(std::move(elastic_base))),
      C0_(base_->evaluate(Mat3::Identity()).dS_dE),
      beta_(beta_s),
      share_(current_share),
      bank_(std::move(bank)),
      coefficient_(beta_s * std::pow(2.0 * std::numbers::pi * reference_frequency_Hz, 1.0 - bank_.order())),
      exponent_(stretch_exponent),
      nominal_(nominal_share) {
  if (!(beta_ >= 0.0) || !std::isfinite(beta_)) throw std::invalid_argument("stiffness_damping: beta_s must be >= 0");
  if (!(share_ >= 0.0 && share_ <= 1.0))
    throw std::invalid_argument("stiffness_damping: current_tangent_share must lie in [0, 1]");
  if (!(reference_frequency_Hz > 0.0) || !std::isfinite(reference_frequency_Hz))
    throw std::invalid_argument("stiffness_damping: order_reference_frequency_Hz must be > 0");
  if (!std::isfinite(exponent_)) throw std::invalid_argument("stiffness_damping: stretch_exponent must be finite");
  if (!(nominal_ >= 0.0 && nominal_ <= 1.0))
    throw std::invalid_argument("stiffness_damping: nominal_tangent_share must lie in [0, 1]");
}

Mat6 StiffnessDampingEffect::damping_tangent(const Mat3& F) const {
  const double stretch_factor = exponent_ == 0.0 ? 1.0 : std::pow(F.determinant(), -exponent_);
  if (share_ == 0.0) return stretch_factor * C0_;
  const ElasticEval elastic = base_->evaluate(F);
  Mat6 current = elastic.dS_dE;
  if (nominal_ > 0.0) {  // + m G, G : X = sym(C^-1 X S_e) = (C^-1 X S_e + S_e X C^-1)/2
    const Mat3 Ci = (F.transpose() * F).inverse(), S_e = from_voigt_stress(elastic.S);
    current += (0.5 * nominal_) * (box_voigt(Ci, S_e) + box_voigt(S_e, Ci));
  }
  return stretch_factor * ((1.0 - share_) * C0_ + share_ * current);
}

PointResponse StiffnessDampingEffect::integrate(const Mat3& F_old, const Mat3& F_new, double dt,
                                                std::span<const double> state_old, std::span<double> state_new) const {
  // C_d at the committed F_old first, then the inner material at F_new: the elastic base's evaluation memo
  // (Hyperfoam::evaluate) still holds the committed point from the increment before (its inner evaluation at its
  // solution), so C_d costs no hyperfoam evaluation on a path; after the inner call it would hold F_new (the same
  // values either way; docs/physics.md 9.46).
  const Mat6 C_d = damping_tangent(F_old);
  PointResponse r = integrate_inner(F_old, F_new, dt, state_old, state_new);
  if (r.status == Status::failed) return r;
  if (bank_.branches() == 0) {  // q = 1: the dashpot, no memory
    if (dt == 0.0) return r;
    const Vec6 E_rate = (to_voigt_strain(green_lagrange(F_new)) - to_voigt_strain(green_lagrange(F_old))) / dt;
    r.S += beta_ * C_d * E_rate;
    r.dS_dE += (beta_ / dt) * C_d;
    return r;
  }
  // q < 1: the bank's memories of C_d-weighted strain increments (stress-like Voigt) in the own state
  const std::span<const double> old_memory = own(state_old);
  const std::span<double> new_memory = own(state_new);
  Vec6 memory_stress;
  if (dt == 0.0) {  // no time passes: the memories carry over and give their stress, no new increment enters
    std::copy(old_memory.begin(), old_memory.end(), new_memory.begin());
    bank_.memory_value(new_memory, {memory_stress.data(), 6});
    r.S += coefficient_ * memory_stress;
    return r;
  }
  const Vec6 dS = C_d * (to_voigt_strain(green_lagrange(F_new)) - to_voigt_strain(green_lagrange(F_old)));
  bank_.advance(dt, {dS.data(), 6}, old_memory, new_memory, {memory_stress.data(), 6});
  r.S += coefficient_ * (memory_stress + (bank_.dashpot() / dt) * dS);
  r.dS_dE += (coefficient_ * bank_.increment_weight(dt)) * C_d;
  return r;
}

Mat6c StiffnessDampingEffect::complex_tangent(const Mat3& F_base, double omega) const {
  return inner_->complex_tangent(F_base, omega) +
         (coefficient_ * bank_.transfer(omega)) * damping_tangent(F_base).cast<std::complex<double>>();
}

std::string StiffnessDampingEffect::describe() const {
  std::ostringstream o;
  o << "stiffness-proportional damping (beta_s = " << beta_ << " s";
  if (share_ > 0.0) o << ", current-tangent share " << share_;
  if (bank_.order() < 1.0) o << ", fractional order " << bank_.order();
  if (exponent_ != 0.0) o << ", stiffness x J^-" << exponent_;
  if (share_ > 0.0 && nominal_ > 0.0) o << ", nominal-tangent share " << nominal_;
  o << ") over " << inner_->describe();
  return o.str();
}

}  // namespace cushion::material
