#include "material/effect_strain_dependent_prony.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace cushion::material {

StrainDependentPronyEffect::StrainDependentPronyEffect(std::shared_ptr<const Viscoelastic> inner, double coefficient_c)
    : EffectDecorator(inner, 0), visco_(std::move(inner)), c_(coefficient_c) {
  if (!std::isfinite(c_)) throw std::invalid_argument("strain_dependent_prony: coefficient c must be finite");
}

double StrainDependentPronyEffect::factor(double J) const { return std::pow(J, -c_); }

PointResponse StrainDependentPronyEffect::integrate(const Mat3& F_old, const Mat3& F_new, double dt,
                                                    std::span<const double> state_old,
                                                    std::span<double> state_new) const {
  PointResponse r = integrate_inner(F_old, F_new, dt, state_old, state_new);
  if (r.status == Status::failed) return r;
  // The Viscoelastic state starts with S_inf at F_new; its viscous part is r.S - S_inf = sum a_i H_i.
  const Vec6 S_inf = Eigen::Map<const Vec6>(state_new.data());
  const Mat6 C_inf = visco_->long_term_base().evaluate(F_new).dS_dE;
  const Vec6 S_viscous = r.S - S_inf;
  const double J = F_new.determinant(), f = factor(J);
  const Vec6 df_dE = -c_ * f / J * dJ_dE(F_new);
  r.S = S_inf + f * S_viscous;
  r.dS_dE = C_inf + f * (r.dS_dE - C_inf) + S_viscous * df_dE.transpose();
  return r;
}

Vec6 StrainDependentPronyEffect::viscous_stress(const Mat3& F, std::span<const double> state) const {
  return factor(F.determinant()) * EffectDecorator::viscous_stress(F, state);
}

Mat6c StrainDependentPronyEffect::complex_tangent(const Mat3& F_base, double omega) const {
  const std::complex<double> viscous = prony_complex_factor(visco_->terms(), omega) - 1.0;
  const Mat6 C_inf = visco_->long_term_base().evaluate(F_base).dS_dE;
  return (1.0 + factor(F_base.determinant()) * viscous) * C_inf.cast<std::complex<double>>();
}

std::string StrainDependentPronyEffect::describe() const {
  std::ostringstream o;
  o << "strain-dependent Prony moduli (f = J^-c, c = " << c_ << ") over " << visco_->describe();
  return o.str();
}

}  // namespace cushion::material
