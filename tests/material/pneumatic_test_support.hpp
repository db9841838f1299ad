#pragma once
/// Shared helpers of the pneumatic-effect tests (test_effect_pneumatic.cpp, test_effect_pneumatic_drag.cpp): air
/// parameter sets, the virgin state, and the extra nominal stress of one confined increment.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "material/effect_pneumatic.hpp"
#include "tests/material/test_effect_support.hpp"

namespace cushion::material::pneumatic_test {

inline PneumaticParameters strong_air(double R = 40.0) {
  PneumaticParameters p;
  p.drainage_length = R;
  p.permeability = 1e-4;  // mm^2: coefficient eta R^2/(8 K0) = 3.6e-5 MPa s at R = 40 mm
  p.permeability_exponent = 2.0;
  return p;
}

inline PneumaticParameters power_law_air(double q, double air_modulus_MPa = std::numeric_limits<double>::infinity()) {
  PneumaticParameters p = strong_air();
  p.rate_exponent = q;
  p.air_modulus = air_modulus_MPa;
  return p;
}

inline PneumaticParameters trapped_air(double air_modulus_MPa, double air_modulus_exponent = 0.0) {
  PneumaticParameters p = strong_air();
  p.air_modulus = air_modulus_MPa;
  p.air_modulus_exponent = air_modulus_exponent;
  return p;
}

inline Mat3 confined(double J) { return Vec3(J, 1.0, 1.0).asDiagonal(); }

/// The virgin state of m (the air pressure 0).
inline std::vector<double> virgin(const Material& m) {
  std::vector<double> s(m.state_size());
  m.initial_state(s);
  return s;
}

/// Extra first Piola-Kirchhoff stress P11 of the effect over its base for one increment from the state (virgin when
/// empty); the state after it in `next` when given.
inline double extra_P11(const PneumaticEffect& m, double J_old, double J_new, double dt, std::vector<double> state = {},
                 std::vector<double>* next = nullptr) {
  if (state.empty()) state = virgin(m);
  std::vector<double> out(m.state_size()), none;
  const PointResponse r = m.integrate(confined(J_old), confined(J_new), dt, state, out);
  EXPECT_EQ(r.status, Status::ok) << r.message;
  if (next) *next = out;
  return J_new * (r.S(0) - m.inner().integrate(confined(J_old), confined(J_new), dt, none, none).S(0));
}

/// The extra P11 of a and b along a confined compression ramp J 1 -> 0.8 in 50 increments of 0.01 s agree to `relative`.
inline void expect_same_along_a_ramp(const PneumaticEffect& a, const PneumaticEffect& b, double relative) {
  std::vector<double> state_a = virgin(a), state_b = virgin(b);
  for (int k = 0; k < 50; ++k) {
    const double J_old = 1.0 - 0.004 * k, J_new = J_old - 0.004;
    std::vector<double> next_a, next_b;
    const double sa = extra_P11(a, J_old, J_new, 0.01, state_a, &next_a);
    const double sb = extra_P11(b, J_old, J_new, 0.01, state_b, &next_b);
    EXPECT_NEAR(sb, sa, relative * std::abs(sa)) << k;
    state_a = next_a, state_b = next_b;
  }
}

/// The increment tangent of m from F_old to F_new (dt 0.01 s) against finite differences to 1e-6 relative, from a
/// non-zero air pressure (an increment I -> F_old of 0.02 s first).
inline void expect_exact_tangent_from_air_pressure(const PneumaticEffect& m, const Mat3& F_old, const Mat3& F_new) {
  std::vector<double> air(m.state_size());
  m.integrate(Mat3::Identity(), F_old, 0.02, virgin(m), air);
  EXPECT_NE(air.back(), 0.0);
  EXPECT_LT(test::increment_tangent_error(m, F_old, F_new, 0.01, air), 1e-6);
}

}  // namespace cushion::material::pneumatic_test
