#include "material/neo_hookean.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace cushion::material {

namespace {
// Tensor indices (i, j) of Voigt entry I, order [11, 22, 33, 12, 23, 13].
constexpr int kVoigtI[6] = {0, 1, 2, 0, 1, 0};
constexpr int kVoigtJ[6] = {0, 1, 2, 1, 2, 2};
}  // namespace

NeoHookean::NeoHookean(double mu, double lambda) : mu_(mu), lambda_(lambda) {
  if (!(mu > 0.0) || !(lambda > -2.0 * mu / 3.0))
    throw std::invalid_argument("NeoHookean: need mu > 0 and lambda > -2 mu / 3");
}

ElasticEval NeoHookean::evaluate(const Mat3& F) const {
  ElasticEval out;
  const double J = F.determinant();
  if (!(J > 0.0) || !std::isfinite(J)) {
    out.status = Status::failed;
    out.message = "NeoHookean: J = det F <= 0 or non-finite";
    return out;
  }
  const Mat3 C = F.transpose() * F;
  const Mat3 Cinv = C.inverse();
  const double lnJ = std::log(J);

  // W = mu/2 (I1 - 3 - 2 ln J) + lambda/2 (ln J)^2
  out.W = 0.5 * mu_ * (C.trace() - 3.0 - 2.0 * lnJ) + 0.5 * lambda_ * lnJ * lnJ;
  // S = 2 dW/dC = mu (I - C^-1) + lambda ln J C^-1
  out.S = to_voigt_stress(mu_ * (Mat3::Identity() - Cinv) + lambda_ * lnJ * Cinv);
  // dS/dE = lambda C^-1 (x) C^-1 + 2 (mu - lambda ln J) I_{C^-1},
  // I_{C^-1}_ijkl = (C^-1_ik C^-1_jl + C^-1_il C^-1_jk) / 2. Voigt entry (I, J) is C_ijkl
  // (engineering shear in E, see tensor.hpp).
  const double m = mu_ - lambda_ * lnJ;
  for (int I = 0; I < 6; ++I) {
    const int i = kVoigtI[I], j = kVoigtJ[I];
    for (int K = 0; K < 6; ++K) {
      const int k = kVoigtI[K], l = kVoigtJ[K];
      out.dS_dE(I, K) = lambda_ * Cinv(i, j) * Cinv(k, l) + m * (Cinv(i, k) * Cinv(j, l) + Cinv(i, l) * Cinv(j, k));
    }
  }
  if (!std::isfinite(out.W) || !out.S.allFinite() || !out.dS_dE.allFinite()) {
    out.status = Status::failed;
    out.message = "NeoHookean: non-finite stress or tangent";
  }
  return out;
}

std::shared_ptr<const Hyperelastic> NeoHookean::scaled(double factor) const {
  return std::make_shared<NeoHookean>(factor * mu_, factor * lambda_);
}

std::string NeoHookean::describe() const {
  std::ostringstream s;
  s << "neo-Hookean: mu = " << mu_ * 1e3 << " kPa, lambda = " << lambda_ * 1e3 << " kPa";
  return s.str();
}

}  // namespace cushion::material
