#include "material/hyperelastic.hpp"

namespace cushion::material {

// A hyperelastic model has no history: the increment is the evaluation at F_new.
PointResponse Hyperelastic::integrate(const Mat3& /*F_old*/, const Mat3& F_new, double /*dt*/,
                                      std::span<const double> /*state_old*/,
                                      std::span<double> /*state_new*/) const {
  ElasticEval e = evaluate(F_new);
  PointResponse r;
  r.S = e.S;
  r.dS_dE = e.dS_dE;
  r.status = e.status;
  r.message = std::move(e.message);
  if (r.status == Status::failed) r.dt_factor = 0.5;
  return r;
}

// No rate dependence: the complex tangent is the real material tangent at the base state.
Mat6c Hyperelastic::complex_tangent(const Mat3& F_base, double /*omega*/) const {
  return evaluate(F_base).dS_dE.cast<std::complex<double>>();
}

}  // namespace cushion::material
