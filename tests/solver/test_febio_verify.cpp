// Requirement (issue 13, peer suites): problems of FEBio's verification suite (febiosoftware/TestSuite,
// Verify/*.feb, MIT licence), translated into cushion case files under tests/peer/febio/, reproduce the
// suite's gold value (code/linuxGoldStandards.py, last field) within the tolerance stated per problem.
// The gold value of a problem without a <logfile> is FEBio's "solution_norm" at the last time step: the
// Euclidean norm of the total displacement over FEBio's equations, i.e. every nodal displacement
// component that is neither fixed nor prescribed (rigid bodies here are fully prescribed: no equations).
// This test computes the same quantity from the last frame of the cushion run. Tolerances and the
// reasons for them: tests/peer/febio/README.md.
#include <cmath>
#include <vector>

#include "solver/output/vtu_reader.hpp"
#include "test_run_support.hpp"

namespace cushion::solver {
namespace {

/// FEBio's solution norm from a finished run: sqrt of the sum of u_i^2 over the displacement components
/// the last step neither holds nor prescribes.
double febio_solution_norm(const LoadedCase& loaded, const VtuContents& last_frame) {
  const std::size_t nodes = loaded.mesh.nodes.size();
  std::vector<bool> constrained(3 * nodes, false);
  for (const BoundarySpec& bc : loaded.spec.steps.back().boundary)
    for (int node : loaded.mesh.node_sets.at(bc.set))
      for (int d = 0; d < 3; ++d)
        if (bc.dofs[d]) constrained[3 * node + d] = true;
  const std::vector<double>& u = last_frame.point_data.at("displacement_mm").values;
  double sum = 0.0;
  for (std::size_t i = 0; i < 3 * nodes; ++i)
    if (!constrained[i]) sum += u[i] * u[i];
  return std::sqrt(sum);
}

/// Runs tests/peer/febio/<problem>/case.json and returns the solution norm at its end.
double run_problem(const std::string& problem) {
  const auto file = test::fs::path(CUSHION_SOURCE_DIR) / "tests" / "peer" / "febio" / problem / "case.json";
  const LoadedCase loaded = load_case(file);
  const auto out = test::scratch_dir();
  RunOptions options;
  options.output_dir = out;
  options.threads = 1;
  run_analysis(loaded, options);
  const auto frames = read_pvd(out / "results.pvd");
  return febio_solution_norm(loaded, read_vtu(out / frames.back().file));
}

/// |cushion - gold| / gold within `relative_tolerance`; prints the measured difference for the README table.
void expect_gold(const std::string& problem, double gold, double relative_tolerance) {
  const double value = run_problem(problem);
  const double difference = (value - gold) / gold;
  std::printf("FebioVerify %s: gold %.12g, cushion %.12g, difference %+.3e (tolerance %.0e)\n", problem.c_str(),
              gold, value, difference, relative_tolerance);
  EXPECT_LE(std::abs(difference), relative_tolerance) << problem << ": cushion " << value << ", gold " << gold;
}

// ma02: 'Ogden unconstrained' block pulled to stretch 1.5, hex8 with 2x2x2 Gauss points in both codes, same
// mesh: the same discrete problem, so only the two Newton tolerances separate the values.
TEST(FebioVerify, Ma02OgdenUnconstrainedTension) { expect_gold("ma02", 7.50244860312, 1e-6); }

// mi24: neo-Hookean (v = 0.49) quarter billet pressed by prescribed displacements; same mesh and element.
TEST(FebioVerify, Mi24NeoHookeanBilletPrescribed) { expect_gold("mi24", 10.5596276733, 1e-8); }

// mi25: homogeneous uniaxial stretch 2 of a neo-Hookean cube (2x2x2 hex8). cushion equals the closed form
// (1.92028031384) to 1e-11; FEBio's gold lies 8.8e-7 below it (its Newton tolerances), hence 2e-6.
TEST(FebioVerify, Mi25NeoHookeanUniaxialStretch) { expect_gold("mi25", 1.92028200836, 2e-6); }

// Contact with rigid bodies: cushion's node-to-rigid-plane penalty (augmented to 1e-6 mm unless stated) vs
// FEBio's contact formulations; the same meshes. The differences (README in tests/peer/febio) come from the
// contact discretisation and FEBio's residual penetration, so the tolerances are wider.
// co22: neo-Hookean billet between two rigid plates (FEBio node-on-facet, augmented Lagrangian).
TEST(FebioVerify, Co22NeoHookeanBilletBetweenRigidPlates) { expect_gold("co22", 23.8300033387, 2e-3); }

// co38: the same billet in 'Ogden unconstrained' (FEBio sliding-elastic, augmented to 20 %: FEBio penetrates).
TEST(FebioVerify, Co38OgdenBilletBetweenRigidPlates) { expect_gold("co38", 18.2542286352, 6e-3); }

// co39: quarter billet in 'Ogden unconstrained' under a rigid bar (FEBio facet-on-facet PENALTY with the
// auto penalty; the same penalty here, without augmentation).
TEST(FebioVerify, Co39OgdenQuarterBilletRigidBar) { expect_gold("co39", 4.67824825162, 2e-3); }

// co09: neo-Hookean block pushed up a fixed inclined rigid plane (FEBio node-on-facet PENALTY, 200 at t = 1;
// the same penalty here, without augmentation).
TEST(FebioVerify, Co09NeoHookeanBlockSlidesOnIncline) { expect_gold("co09", 63.1607955173, 5e-4); }

}  // namespace
}  // namespace cushion::solver
