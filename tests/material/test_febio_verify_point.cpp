// Requirement (issue 13, peer suites): FEBio verification problems that are one homogeneous material point
// reproduce the suite's gold value (febiosoftware/TestSuite, code/linuxGoldStandards.py, last field; MIT
// licence) through cushion's material-point driver. Without a <logfile> the gold value is FEBio's
// "solution_norm": the Euclidean norm of the displacement components that are neither fixed nor
// prescribed, at the last time step. Inputs and the table: tests/peer/febio/README.md.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "material/io/material_file.hpp"
#include "material/point_driver.hpp"

namespace cm = cushion::material;

namespace {

/// P11 [MPa] at the last sample of a uniaxial (free lateral) history.
double last_p11(const cm::Material& material, const cm::History& history) {
  return cm::run_point(material, cm::LoadMode::uniaxial_free, history).P.back()(0, 0);
}

/// Creep under a constant nominal stress: appends samples at `times` and finds each sample's strain by the
/// secant method so that P11 = p11 there (the driver imposes strain; the load is imposed by iteration).
cm::PointResult creep(const cm::Material& material, double p11, const std::vector<double>& times) {
  cm::History history{{0.0}, {0.0}};
  for (double t : times) {
    history.time.push_back(t);
    history.control.push_back(history.control.back());
    double a = history.control.back(), b = a + 1e-3;
    history.control.back() = a;
    double fa = last_p11(material, history) - p11;
    for (int it = 0; it < 50 && std::abs(fa) > 1e-15; ++it) {
      history.control.back() = b;
      const double fb = last_p11(material, history) - p11;
      const double next = b - fb * (b - a) / (fb - fa);
      a = b, fa = fb, b = next;
    }
    history.control.back() = a;
  }
  return cm::run_point(material, cm::LoadMode::uniaxial_free, history);
}

// ma05: one unit hex8 (held on x = -0.5, y = -0.5, z = 0), nodal forces 4 x 0.0005 in x on the x = 0.5 face
// from t = 0 (a creep test: nominal stress 0.002), neo-Hookean E = 1, v = 0 with one Prony term g1 = 0.95,
// t1 = 0.01 (tests/peer/febio/ma05/material.json); the point is homogeneous, so the element formulation does
// not enter. At t = 1 (100 relaxation times) the creep has ended: the gold value tests the long-term limit of
// cushion's Prony form, the 100 increments of the creep path the form itself (it must not drift).
TEST(FebioVerify, Ma05ViscoelasticCreep) {
  const auto file = std::filesystem::path(CUSHION_SOURCE_DIR) / "tests/peer/febio/ma05/material.json";
  const cm::MaterialDefinition definition = cm::read_material_file(file);
  std::vector<double> times;
  for (int i = 1; i <= 100; ++i) times.push_back(0.01 * i);
  const double force_per_area_MPa = 4 * 0.0005 * 1e-3;  // FEBio's stress unit read as kPa
  const cm::PointResult r = creep(*definition.model, force_per_area_MPa, times);
  // free components at t = 1: u_x of the 4 nodes at x = 0.5, u_y of the 4 at y = 0.5, u_z of the 4 at z = 1
  double sum = 0.0;
  for (int d = 0; d < 3; ++d) sum += 4.0 * std::pow(r.F.back()(d, d) - 1.0, 2);
  const double gold = 0.004003999996, value = std::sqrt(sum);
  std::printf("FebioVerify ma05: gold %.12g, cushion %.12g, difference %+.3e (tolerance 1e-9)\n", gold, value,
              (value - gold) / gold);
  EXPECT_NEAR(value / gold, 1.0, 1e-9);
  // the creep is monotone: the strain at t = 0.01 (one relaxation time) lies below the final one
  EXPECT_LT(r.F[1](0, 0), r.F.back()(0, 0));
}

}  // namespace
