// Hyperfoam fit to an elastic uniaxial curve: closed forms against the material model, recovery of a
// known 3-term curve, Drucker stability of the result.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "calibration/hyperfoam_fit.hpp"
#include "material/stability.hpp"

namespace cal = cushion::calibration;
namespace mat = cushion::material;

namespace {
const std::vector<mat::HyperfoamTerm> kTerms{{0.004, 2.0, 0.0}, {0.001, 8.0, 0.0}, {1e-5, -6.0, 0.0}};
cal::ElasticCurve curve_of(const std::vector<mat::HyperfoamTerm>& terms, double nu, cal::Lateral lateral) {
  cal::ElasticCurve c;
  for (int k = 0; k <= 60; ++k) c.strain.push_back(0.75 * k / 60.0);
  c.stress = cal::hyperfoam_uniaxial_stress(terms, nu, lateral, c.strain);
  return c;
}
}  // namespace

TEST(HyperfoamFit, ClosedFormsMatchTheMaterialModel) {
  // Independent check through Hyperfoam::principal_kirchhoff: free faces (l2 = l3 = l^-nu) have zero
  // lateral stress and nominal stress tau1/l; constrained faces (l2 = l3 = 1) likewise. 1e-12 MPa.
  for (double nu : {0.0, 0.2}) {
    std::vector<mat::HyperfoamTerm> t = kTerms;
    for (auto& term : t) term.nu = nu;
    const mat::Hyperfoam foam(t);
    for (double e : {0.1, 0.4, 0.7}) {
      const double l = 1.0 - e;
      const cushion::Vec3 tf = foam.principal_kirchhoff({l, std::pow(l, -nu), std::pow(l, -nu)});
      EXPECT_NEAR(tf(1), 0.0, 1e-12);
      EXPECT_NEAR(cal::hyperfoam_uniaxial_stress(t, nu, cal::Lateral::free, {e})[0], -tf(0) / l, 1e-12);
      const cushion::Vec3 tc = foam.principal_kirchhoff({l, 1.0, 1.0});
      EXPECT_NEAR(cal::hyperfoam_uniaxial_stress(t, nu, cal::Lateral::constrained, {e})[0], -tc(0) / l, 1e-12);
    }
  }
}

TEST(HyperfoamFit, RecoversKnownThreeTermCurve) {
  const auto c = curve_of(kTerms, 0.0, cal::Lateral::free);
  const auto fit = cal::fit_hyperfoam(c);
  // Within 0.5 % of the peak stress over 0..75 % strain, and Drucker stable.
  EXPECT_LT(fit.max_error, 5e-3);
  EXPECT_TRUE(fit.stable) << fit.stability;
  ASSERT_EQ(fit.terms.size(), 3u);
  const mat::Hyperfoam model(fit.terms);
  EXPECT_TRUE(mat::check_stability(model, -0.75, 0.5).stable());
  // The curve re-evaluated independently through the material model agrees with the data.
  const double peak = *std::max_element(c.stress.begin(), c.stress.end());
  for (std::size_t k = 0; k < c.strain.size(); k += 10) {
    const double l = 1.0 - c.strain[k];
    const double s = -model.principal_kirchhoff({l, 1.0, 1.0})(0) / l;  // nu = 0: lateral stretch 1
    EXPECT_NEAR(s, c.stress[k], 5e-3 * peak);
  }
}

TEST(HyperfoamFit, FitsConstrainedCurveWithGivenNu) {
  std::vector<mat::HyperfoamTerm> t = kTerms;
  for (auto& term : t) term.nu = 0.1;
  const auto c = curve_of(t, 0.1, cal::Lateral::constrained);
  cal::HyperfoamFitOptions o;
  o.nu = 0.1;
  o.lateral = cal::Lateral::constrained;
  const auto fit = cal::fit_hyperfoam(c, o);
  EXPECT_LT(fit.max_error, 5e-3);
  EXPECT_DOUBLE_EQ(fit.nu, 0.1);
}

TEST(HyperfoamFit, RejectsBadOptions) {
  const auto c = curve_of(kTerms, 0.0, cal::Lateral::free);
  cal::HyperfoamFitOptions o;
  o.terms = 7;
  EXPECT_THROW(cal::fit_hyperfoam(c, o), std::invalid_argument);
}
