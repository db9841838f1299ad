// Bad input of the steady-state solver: missing density, non-positive frequency, bad DOF sets.
#include <gtest/gtest.h>

#include "material/neo_hookean.hpp"
#include "test_dynamics_support.hpp"

namespace cushion::solver::test {
namespace {

using namespace cushion::solver::dynamics;

struct Small {
  mesh::Mesh mesh = column(10.0, 10.0, 1);
  std::vector<Section> sections;
  std::unique_ptr<LinearisedSystem> sys;
  explicit Small(double density) {
    sections = {{"seat_foam", {0}, std::make_shared<material::NeoHookean>(0.02, 0.01), Formulation::full, density}};
    Assembler A(mesh, sections, DofMap(mesh.num_nodes(), {}), AssemblyOptions{1});
    StateStore st = A.make_state_store();
    const Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * mesh.num_nodes());
    sys = std::make_unique<LinearisedSystem>(mesh, sections, base_point_states(A, st, u, BaseStress::relaxed), u);
  }
  HarmonicModel model() const {
    HarmonicModel m;
    m.system = sys.get();
    return m;
  }
};

TEST(DynamicsErrors, MissingDensityNamesTheSection) {
  Small s(0.0);
  try {
    SteadyStateSolver(s.model(), {}, {set_dofs(s.mesh, "zmin", 2), {}}, {});
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("seat_foam"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("density"), std::string::npos) << e.what();
  }
}

TEST(DynamicsErrors, NonPositiveFrequencyAndBadSets) {
  Small s(6.5e-11);
  Excitation x{set_dofs(s.mesh, "zmin", 2), lateral_dofs(s.mesh)};
  SteadyStateSolver solver(s.model(), {}, x, {});
  EXPECT_THROW(solver.solve(0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(solver.solve(-5.0, 1.0), std::invalid_argument);
  EXPECT_NO_THROW(solver.solve(5.0, 1.0));
  EXPECT_THROW(SteadyStateSolver(s.model(), {}, {{}, lateral_dofs(s.mesh)}, {}), std::invalid_argument);  // nothing driven
  EXPECT_THROW(SteadyStateSolver(s.model(), {}, {x.driven, x.driven}, {}), std::invalid_argument);       // overlap
  EXPECT_THROW(SteadyStateSolver(s.model(), {}, {{100000}, {}}, {}), std::invalid_argument);             // out of range
  EXPECT_THROW(SteadyStateSolver(s.model(), {-1.0, 0.0, 0.0}, x, {}), std::invalid_argument);           // damping < 0
}

}  // namespace
}  // namespace cushion::solver::test
