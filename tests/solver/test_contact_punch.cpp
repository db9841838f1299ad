// Requirement: contact with a frictionless flat cylindrical punch on a thin layer bonded to a rigid
// base converges to the thin-layer (oedometric) solution.
// Reference: for a compressible layer of thickness h << a (punch radius a) bonded to a rigid base,
// the leading-order thin-layer solution is uniaxial strain under the punch (Winkler foundation with
// the oedometric modulus M = E (1 - nu) / ((1 + nu)(1 - 2 nu)); Barber, Contact Mechanics, 2018,
// thin-layer limit; Argatov & Mishuris, Contact Mechanics of Articular Cartilage Layers, 2015,
// ch. 2): F0 = pi a^2 M d / h. The material around the punch edge adds a force of relative size
// O(h / a) (the edge singularity is integrable: the total force converges, the edge pressure does
// not), so F / F0 - 1 = c h / a + O((h / a)^2).
// Checks (linear limit: d / h = 0.2 %, hyperfoam mu = 0.1 MPa, nu = 0.3): at h / a = 0.1, 0.05 and
// 0.025 the deviation F / F0 - 1 is positive (the edge adds force), below 0.25 h / a, falls at
// least by a factor 1.8 each time h / a halves, and is below 0.5 % at h / a = 0.025: the computed
// force converges to the thin-layer limit. Measured: +2.19 %, +0.92 %, +0.30 %. Mesh: cylindrical (r, theta, z) grid, quarter model, rings
// graded towards the punch edge r = a (a node ring lies exactly on it). The axis is a small hole
// r0 = 0.02 a whose surface is held u_x = u_y = 0, which is the exact lateral condition of the
// uniaxial-strain interior; the hole's area is taken out of F0.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <numbers>
#include <sstream>

#include "mesh/inp_reader.hpp"
#include "mesh/structured_hex.hpp"
#include "tests/solver/test_run_support.hpp"

namespace cushion::solver {
namespace {

constexpr double kMu = 0.1;  // [MPa]
constexpr double kNu = 0.3;
constexpr double kA = 20.0;  // punch radius [mm]

/// Quarter annulus r0 <= r <= outer, 0 <= theta <= 90 deg, 0 <= z <= h (C3D8), written as .inp.
void write_layer_mesh(const std::filesystem::path& file, double r0, double outer, double h, int nr, int ntheta,
                      int nz) {
  mesh::BlockSpec spec;
  spec.low = {r0, 0.0, 0.0};
  spec.high = {outer, 90.0, h};
  spec.n = {nr, ntheta, nz};
  spec.grading[0] = {mesh::AxisGrading::Kind::focus, 30.0, kA};
  mesh::Mesh m = mesh::structured_block(spec);
  for (auto& x : m.nodes) {
    const double r = x.x(), theta = x.y() * std::numbers::pi / 180.0;
    const bool on_y_axis = std::abs(x.y() - 90.0) < 1e-9, on_x_axis = std::abs(x.y()) < 1e-9;
    x.x() = on_y_axis ? 0.0 : r * std::cos(theta);
    x.y() = on_x_axis ? 0.0 : r * std::sin(theta);
  }
  m.node_sets.clear();  // the (r, theta) box's sets mean nothing after the mapping
  m.surfaces.clear();
  mesh::write_inp(m, file.string());
}

/// Force on the punch [N] (full model) pressed d = 0.002 h into a layer of thickness h.
double punch_force(double h, double r0, const std::string& tag) {
  const auto dir = test::scratch_dir(tag + "_" + std::to_string(::getpid()));  // other builds run this suite too
  std::ostringstream foam;
  foam << R"({"name": "linear_limit", "density_kg_m3": 65, "hyperfoam": {"terms": [{"mu_kPa": )" << 1e3 * kMu
       << R"(, "alpha": 2, "nu": )" << kNu << "}]}}";
  test::write_text(dir / "foam.json", foam.str());
  write_layer_mesh(dir / "layer.inp", r0, kA + 12.0 * h, h, 40, 24, 4);
  const double d = 0.002 * h;
  std::ostringstream c;
  c.precision(17);
  c << R"J({"mesh": {"inp": "layer.inp"}, "material": {"file": "foam.json"},
    "sets": {"sym_x": "x == 0", "sym_y": "y == 0", "base": "z == 0", "top": "z == )J"
    << h << R"J(", "hole": "cylinder(0, 0, 0, 0, 0, 1, )J" << r0 << R"J()"},
    "steps": [{"name": "press", "type": "static", "time_period_s": 1, "increment": {"initial_s": 1, "max_s": 1},
      "boundary": [{"set": "base", "type": "fixed"}, {"set": "hole", "dof": "xy", "value_mm": 0},
                   {"set": "sym_x", "type": "symmetry_x"}, {"set": "sym_y", "type": "symmetry_y"}],
      "contact": [{"name": "punch", "set": "top",
                   "indenter": {"type": "flat_punch", "centre_mm": [0, 0], "bottom_z_mm": )J"
    << h << R"J(, "radius_mm": )J" << kA << R"J(, "edge_radius_mm": )J" << 0.05 * d << R"J(},
                   "motion_mm": [0, 0, )J"
    << -d << R"J(], "penalty_MPa_per_mm": 100, "tolerance_mm": )J" << 1e-3 * d << R"J(, "force_factor": 4}],
      "output": {"frame_every_increments": 100}}],
    "solver": {"residual_tolerance": 1e-7, "correction_tolerance": 1e-7}})J";
  const auto file = test::write_text(dir / "case.json", c.str());
  test::run_case(file, dir / "out");
  const CsvTable contact = read_csv(dir / "out" / "contact_punch.csv");
  EXPECT_NEAR(contact.col("punch.U3_mm").back(), -d, 1e-12);
  return -contact.col("punch.F3_N").back();
}

TEST(PunchOnBondedLayer, ForceConvergesToThinLayerLimit) {
  const double E = 2.0 * kMu * (1.0 + kNu);
  const double M = E * (1.0 - kNu) / ((1.0 + kNu) * (1.0 - 2.0 * kNu));
  const double r0 = 0.02 * kA;
  std::vector<double> deviation;
  for (const double h_over_a : {0.1, 0.05, 0.025}) {
    const double h = h_over_a * kA, d = 0.002 * h;
    const double F0 = std::numbers::pi * (kA * kA - r0 * r0) * M * d / h;
    const double F = punch_force(h, r0, "_h" + std::to_string(static_cast<int>(1000 * h_over_a)));
    deviation.push_back(F / F0 - 1.0);
    std::cout << "punch h/a = " << h_over_a << ": F = " << F << " N, thin-layer F0 = " << F0
              << " N, F/F0 - 1 = " << deviation.back() << "\n";
    EXPECT_GT(deviation.back(), 0.0) << "h/a = " << h_over_a;
    EXPECT_LT(deviation.back(), 0.25 * h_over_a) << "h/a = " << h_over_a;
  }
  // At least first-order convergence to the thin-layer limit (measured ratios 2.37 and 3.03).
  EXPECT_GT(deviation[0] / deviation[1], 1.8);
  EXPECT_GT(deviation[1] / deviation[2], 1.8);
  EXPECT_LT(deviation[2], 0.005);  // measured +0.30 % at h / a = 0.025
}

}  // namespace
}  // namespace cushion::solver
