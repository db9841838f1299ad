// Sweep output: CSV columns and values, and one VTK frame per frequency collected in a .pvd.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "material/neo_hookean.hpp"
#include "solver/dynamics/sweep.hpp"
#include "test_dynamics_support.hpp"

namespace cushion::solver::test {
namespace {

using namespace cushion::solver::dynamics;

TEST(DynamicsOutput, CsvRowsAndPvdOverFrequency) {
  const mesh::Mesh mesh = column(10.0, 20.0, 2);
  std::vector<Section> sections{{"foam", {0, 1}, std::make_shared<material::NeoHookean>(0.02, 0.01), Formulation::full, 6.5e-11}};
  Assembler A(mesh, sections, DofMap(mesh.num_nodes(), {}), AssemblyOptions{1});
  StateStore st = A.make_state_store();
  const Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * mesh.num_nodes());
  LinearisedSystem sys(mesh, sections, base_point_states(A, st, u, BaseStress::relaxed), u);
  HarmonicModel model;
  model.system = &sys;
  Excitation x{set_dofs(mesh, "zmin", 2), lateral_dofs(mesh)};
  for (int d : set_dofs(mesh, "zmax", 2)) x.held.push_back(d);
  SteadyStateSolver s(model, {180.0, 1e-4, 0.0}, x, {{"indenter", set_dofs(mesh, "zmax", 2)}, {"base", set_dofs(mesh, "zmin", 2)}});
  const auto dir = std::filesystem::temp_directory_path() / "cushion_test_dynamics_output";
  std::filesystem::remove_all(dir);
  ResultSeries series(dir, "sweep");
  std::vector<SweepRow> rows;
  const NominalGeometry g{100.0, 20.0};
  for (double f : {1.0, 2.0}) {
    const auto r = s.solve(f, displacement_amplitude(250.0, AccelerationReading::peak_to_peak, f));
    rows.push_back(make_row(r, Measure::indenter_held, g));
    write_frequency_frame(series, mesh, sys, sys.element_base(), r, 2);
  }
  // Quasi-static limit: K = M_c A / L = 0.05 * 100 / 20 N/mm, E = K L / A = 0.05 MPa = 50 kPa.
  EXPECT_NEAR(std::abs(rows[0].stiffness), 0.25, 0.25 * 1e-3);
  EXPECT_NEAR(1e3 * std::abs(rows[0].modulus), 50.0, 50.0 * 1e-3);
  write_sweep_csv(dir / "sweep.csv", rows, {"test"});
  std::ifstream in(dir / "sweep.csv");
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "# test");
  std::getline(in, line);
  EXPECT_EQ(line.rfind("frequency_Hz,", 0), 0u);
  EXPECT_NE(line.find("dynamic_modulus_kPa"), std::string::npos);
  int n = 0;
  while (std::getline(in, line)) ++n;
  EXPECT_EQ(n, 2);
  std::ifstream pvd(series.pvd_file());
  std::stringstream text;
  text << pvd.rdbuf();
  EXPECT_NE(text.str().find("timestep=\"2\""), std::string::npos) << text.str();
  EXPECT_EQ(series.frame_count(), 2u);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace cushion::solver::test
