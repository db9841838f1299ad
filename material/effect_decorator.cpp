#include "material/effect_decorator.hpp"

#include <cmath>
#include <stdexcept>

namespace cushion::material {

Vec6 dJ_dE(const Mat3& F) {
  const double J = F.determinant();
  return to_voigt_stress(J * (F.transpose() * F).inverse());
}

Mat6 box_voigt(const Mat3& A, const Mat3& B) {
  // Column K = (kl) is A X B for the X of a unit engineering strain: X_kl = X_lk = 1/2 (X_kk = 1 on the diagonal), so
  // (A X B)_ij = (A_ik B_lj + A_il B_kj)/2. Rows and columns use the same (ij) <-> I pairing as material/tensor.hpp.
  static constexpr int pair[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {0, 2}};
  Mat6 D;
  for (int I = 0; I < 6; ++I)
    for (int K = 0; K < 6; ++K) {
      const int i = pair[I][0], j = pair[I][1], k = pair[K][0], l = pair[K][1];
      D(I, K) = 0.5 * (A(i, k) * B(l, j) + A(i, l) * B(k, j));
    }
  return D;
}

Mat6 dCinv_dE(const Mat3& Ci) {
  // dC^{-1} = -C^{-1} dC C^{-1} with dC = 2 dE.
  return -2.0 * box_voigt(Ci, Ci);
}

Mat6 symmetric_identity_voigt() {
  Vec6 d;
  d << 1.0, 1.0, 1.0, 0.5, 0.5, 0.5;
  return d.asDiagonal();
}

double tensor_norm(const Vec6& v) {
  return std::sqrt(v.head<3>().squaredNorm() + 2.0 * v.tail<3>().squaredNorm());
}

void combine_status(PointResponse& into, Status status, const std::string& message) {
  if (static_cast<int>(status) > static_cast<int>(into.status)) {
    into.status = status;
    into.message = message;
  }
}

EffectDecorator::EffectDecorator(std::shared_ptr<const Material> inner, std::size_t own_size)
    : inner_(std::move(inner)), own_size_(own_size) {
  if (!inner_) throw std::invalid_argument("effect: no inner material");
}

void EffectDecorator::initial_state(std::span<double> state) const {
  inner_->initial_state(state.first(inner_->state_size()));
  own_initial_state(own(state));
}

Vec6 EffectDecorator::viscous_stress(const Mat3& F, std::span<const double> state) const {
  return inner_->viscous_stress(F, state.first(inner_->state_size()));
}

void EffectDecorator::own_initial_state(std::span<double> own_state) const {
  for (double& x : own_state) x = 0.0;
}

PointResponse EffectDecorator::integrate_inner(const Mat3& F_old, const Mat3& F_new, double dt,
                                               std::span<const double> state_old, std::span<double> state_new) const {
  if (!(dt >= 0.0) || state_old.size() != state_size() || state_new.size() != state_size()) {
    PointResponse r;
    r.status = Status::failed;
    r.message = describe() + ": dt < 0 or wrong state size";
    return r;
  }
  const std::size_t n = inner_->state_size();
  PointResponse r = inner_->integrate(F_old, F_new, dt, state_old.first(n), state_new.first(n));
  if (r.status == Status::failed) return r;
  if (!(F_new.determinant() > 0.0)) {  // effects use J and C^{-1}; an inner model could tolerate J <= 0
    r.status = Status::failed;
    r.message = "effect: J <= 0";
    r.dt_factor = 0.5;
  }
  return r;
}

}  // namespace cushion::material
