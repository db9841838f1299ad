#include "material/effect_strain_dependent_prony.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace cushion::material {

StrainDependentPronyEffect::StrainDependentPronyEffect(std::shared_ptr<const Viscoelastic> inner, double coefficient_c,
                                                       double history_share, double strain_measure_share)
    : EffectDecorator(inner, 0),
      visco_(std::move(inner)),
      c_(coefficient_c),
      w_(history_share),
      s_(strain_measure_share) {
  if (!std::isfinite(c_)) throw std::invalid_argument("strain_dependent_prony: coefficient c must be finite");
  if (!(w_ >= 0.0 && w_ <= 1.0))
    throw std::invalid_argument("strain_dependent_prony: history_share must lie in [0, 1]");
  if (!(s_ >= 0.0 && s_ <= 1.0))
    throw std::invalid_argument("strain_dependent_prony: strain_measure_share must lie in [0, 1]");
}

double StrainDependentPronyEffect::factor(double J) const {
  return std::exp(c_ * ((1.0 - s_) * -std::log(J) + s_ * (1.0 - J)));
}

Vec6 StrainDependentPronyEffect::dfactor_dE(const Mat3& F) const {
  const double J = F.determinant();
  return -c_ * factor(J) * ((1.0 - s_) / J + s_) * dJ_dE(F);
}

PointResponse StrainDependentPronyEffect::integrate(const Mat3& F_old, const Mat3& F_new, double dt,
                                                    std::span<const double> state_old,
                                                    std::span<double> state_new) const {
  PointResponse r = integrate_inner(F_old, F_new, dt, state_old, state_new);
  if (r.status == Status::failed) return r;
  // The Viscoelastic state starts with S_inf at F_new; its viscous part is r.S - S_inf = sum a_i H_i.
  const Vec6 S_inf = Eigen::Map<const Vec6>(state_new.data());
  const Mat6 C_inf = visco_->long_term_base().evaluate(F_new).dS_dE;
  const double phi = factor(F_new.determinant());
  const Vec6 dphi_dE = dfactor_dE(F_new);
  Vec6 V = r.S - S_inf;              // sum a_i H_i of the inner (unweighted) update
  const Mat6 A_C = r.dS_dE - C_inf;  // A C_inf, the inner viscous tangent
  Mat6 dV_dE = A_C;
  if (w_ > 0.0) {  // weight the increment that entered each H_i by phi^w (the inner added it with weight 1)
    const Vec6 dS_inf = S_inf - Eigen::Map<const Vec6>(state_old.data());
    const double phi_w = std::pow(phi, w_);
    // sum a_i (1 - e^{-x_i})/x_i dS_inf, while each H_i takes its weighted increment
    const Vec6 A_dS = visco_->add_to_memory(state_new, dt, (phi_w - 1.0) * dS_inf) * dS_inf;
    V += (phi_w - 1.0) * A_dS;
    dV_dE = phi_w * A_C + w_ * std::pow(phi, w_ - 1.0) * A_dS * dphi_dE.transpose();
  }
  const double scale = std::pow(phi, 1.0 - w_);
  r.S = S_inf + scale * V;
  r.dS_dE = C_inf + scale * dV_dE + (1.0 - w_) * std::pow(phi, -w_) * V * dphi_dE.transpose();
  return r;
}

Vec6 StrainDependentPronyEffect::viscous_stress(const Mat3& F, std::span<const double> state) const {
  return std::pow(factor(F.determinant()), 1.0 - w_) * EffectDecorator::viscous_stress(F, state);
}

Mat6c StrainDependentPronyEffect::complex_tangent(const Mat3& F_base, double omega) const {
  const Mat6 C_inf = visco_->long_term_base().evaluate(F_base).dS_dE;
  return memory_complex_factor(F_base, omega) * C_inf.cast<std::complex<double>>();
}

std::complex<double> StrainDependentPronyEffect::memory_complex_factor(const Mat3& F_base, double omega) const {
  return 1.0 + factor(F_base.determinant()) * (prony_complex_factor(visco_->terms(), omega) - 1.0);
}

MemoryGain StrainDependentPronyEffect::drive_memory(const Mat3& F_new, std::span<double> state_new, double dt,
                                                    const Vec6& dS) const {
  const double phi = factor(F_new.determinant());
  const double A = visco_->add_to_memory(state_new, dt, std::pow(phi, w_) * dS);  // sum a_i q_i
  return {phi * A, A * dfactor_dE(F_new)};
}

std::string StrainDependentPronyEffect::describe() const {
  std::ostringstream o;
  o << "strain-dependent Prony moduli (f = exp(c g), g = (1 - s)(-ln J) + s (1 - J), c = " << c_ << ", s = " << s_;
  if (w_ > 0.0) o << ", history share " << w_;
  o << ") over " << visco_->describe();
  return o.str();
}

}  // namespace cushion::material
