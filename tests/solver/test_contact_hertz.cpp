// Requirement: node-to-rigid-surface contact reproduces the Hertz solution for a rigid sphere on an
// elastic half-space in the small-strain limit.
// Checks: a rigid sphere (R = 10 mm) pressed d = 0.025 and 0.05 mm into a 100 mm hyperfoam block
// (one term, mu = 0.1 MPa, alpha = 2, nu = 0.3 through beta = nu / (1 - 2 nu)); quarter model with
// symmetry planes x = 0, y = 0 and a frictionless base. Linear limit: E = 2 mu (1 + nu),
// E* = E / (1 - nu^2); Hertz: F = 4/3 E* sqrt(R) d^1.5, contact radius a = sqrt(R d) = 0.5 and
// 0.71 mm (a / R <= 0.071, a / block = 0.007). Mesh: uniform 0.09 mm hexahedra over the contact
// zone (11 across 0.99 mm in x, y; 6 in depth), then growing geometrically (13 more) to the 100 mm
// block edge. The full-model contact force (force_factor 4) is within 3 % of Hertz at both depths;
// measured +1.6 % and +2.3 % (a coarser mesh, 0.09 mm x 10 + 12, gives +1.9 % / +2.8 %; a finer
// one, 0.07 mm x 12 + 12, +2.0 % / +2.9 %: the remainder is the finite strain a / R and the finite
// block, not the mesh).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "mesh/inp_reader.hpp"
#include "mesh/structured_hex.hpp"
#include "tests/solver/test_run_support.hpp"

namespace cushion::solver {
namespace {

constexpr double kMu = 0.1;        // [MPa]
constexpr double kNu = 0.3;
constexpr double kRadius = 10.0;   // sphere [mm]
constexpr double kBlock = 100.0;   // block edge [mm]

/// n_fine elements of size h from 0, then n_graded growing geometrically to `length` [mm].
std::vector<double> fine_then_graded(double h, int n_fine, int n_graded, double length) {
  std::vector<double> x;
  for (int i = 0; i <= n_fine; ++i) x.push_back(h * i);
  const double rest = length - x.back();
  double lo = 1.0 + 1e-9, hi = 5.0;  // growth factor q: h q (q^n - 1) / (q - 1) = rest
  for (int it = 0; it < 200; ++it) {
    const double q = 0.5 * (lo + hi);
    (h * q * (std::pow(q, n_graded) - 1.0) / (q - 1.0) > rest ? hi : lo) = q;
  }
  double size = h;
  for (int i = 0; i < n_graded; ++i) x.push_back(x.back() + (size *= lo));
  x.back() = length;
  return x;
}

/// The quarter block [0, L]^3 with the fine zone at x = y = 0, z = L, written as .inp.
void write_block(const std::filesystem::path& file) {
  const std::vector<double> xy = fine_then_graded(0.09, 11, 13, kBlock);
  std::vector<double> z = fine_then_graded(0.09, 6, 13, kBlock);
  for (double& v : z) v = kBlock - v;
  std::reverse(z.begin(), z.end());
  mesh::BlockSpec spec;  // index space: node (i, j, k) at (i, j, k), mapped below
  spec.high = {xy.size() - 1.0, xy.size() - 1.0, z.size() - 1.0};
  spec.n = {static_cast<int>(xy.size()) - 1, static_cast<int>(xy.size()) - 1, static_cast<int>(z.size()) - 1};
  mesh::Mesh m = mesh::structured_block(spec);
  for (auto& p : m.nodes)
    p = {xy[std::lround(p.x())], xy[std::lround(p.y())], z[std::lround(p.z())]};
  m.node_sets.clear();
  m.surfaces.clear();
  mesh::write_inp(m, file.string());
}

std::string hertz_case(double depth) {
  std::ostringstream s;
  s.precision(17);
  s << R"({"mesh": {"inp": "block.inp"}, "material": {"file": "foam.json"},
    "sets": {"sym_x": "x == 0", "sym_y": "y == 0", "base": "z == 0", "top": "z == )" << kBlock << R"("},
    "steps": [{"name": "press", "type": "static", "time_period_s": 1, "increment": {"initial_s": 0.5, "max_s": 0.5},
      "boundary": [{"set": "sym_x", "type": "symmetry_x"}, {"set": "sym_y", "type": "symmetry_y"},
                   {"set": "base", "type": "symmetry_z"}],
      "contact": [{"name": "ball", "set": "top",
                   "indenter": {"type": "sphere", "centre_mm": [0, 0, )" << kBlock + kRadius
    << R"(], "radius_mm": )" << kRadius << R"(},
                   "motion_mm": [0, 0, )" << -depth << R"(], "penalty_MPa_per_mm": 10, "tolerance_mm": )"
    << 2e-3 * depth << R"(, "force_factor": 4}],
      "output": {"frame_every_increments": 100}}],
    "solver": {"residual_tolerance": 1e-5, "correction_tolerance": 1e-5}})";
  return s.str();
}

TEST(HertzCase, RigidSphereOnHyperfoamBlock) {
  const auto dir = test::scratch_dir("_" + std::to_string(::getpid()));  // other builds run this suite too
  std::ostringstream foam;
  foam << R"({"name": "linear_limit", "density_kg_m3": 65, "hyperfoam": {"terms": [{"mu_kPa": )" << 1e3 * kMu
       << R"(, "alpha": 2, "nu": )" << kNu << "}]}}";
  test::write_text(dir / "foam.json", foam.str());
  write_block(dir / "block.inp");
  test::run_case(test::write_text(dir / "case.json", hertz_case(0.05)), dir / "out");
  const CsvTable contact = read_csv(dir / "out" / "contact_ball.csv");
  const auto& U3 = contact.col("ball.U3_mm");
  const auto& F3 = contact.col("ball.F3_N");
  ASSERT_EQ(U3.size(), 3u);
  const double E_star = 2.0 * kMu * (1.0 + kNu) / (1.0 - kNu * kNu);
  for (std::size_t i = 1; i < U3.size(); ++i) {  // d = 0.025, 0.05 mm
    const double d = -U3[i];
    const double F_hertz = 4.0 / 3.0 * E_star * std::sqrt(kRadius) * std::pow(d, 1.5);
    std::cout << "Hertz d = " << d << " mm: F = " << -F3[i] << " N, Hertz " << F_hertz << " N, ratio "
              << -F3[i] / F_hertz << "\n";
    EXPECT_NEAR(-F3[i] / F_hertz, 1.0, 0.03) << "d = " << d << " mm";
  }
}

}  // namespace
}  // namespace cushion::solver
