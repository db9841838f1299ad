// Time domain vs frequency domain: the Newmark step driven by a small base sinusoid about a relaxed
// 20 % preload (hyperfoam + Prony, Rayleigh alpha and beta on) reaches a steady state whose reaction
// amplitude and phase match the steady-state step within 1 % and 0.5 deg at 1, 5 and 20 Hz.
#include <gtest/gtest.h>

#include "solver/dynamics/newmark.hpp"
#include "solver_fixtures.hpp"
#include "test_dynamics_support.hpp"

namespace cushion::solver::test {
namespace {

using namespace cushion::solver::dynamics;

/// Phasor Y of y(t) ~ c0 + c1 t + Re(Y e^{i w t}) by least squares over the samples.
cplx fit_phasor(const std::vector<double>& t, const std::vector<double>& y, double w) {
  Eigen::MatrixXd A(static_cast<Eigen::Index>(t.size()), 4);
  Eigen::VectorXd b(static_cast<Eigen::Index>(t.size()));
  for (std::size_t i = 0; i < t.size(); ++i) {
    A.row(static_cast<Eigen::Index>(i)) << 1.0, t[i], std::cos(w * t[i]), std::sin(w * t[i]);
    b(static_cast<Eigen::Index>(i)) = y[i];
  }
  const Eigen::Vector4d c = A.colPivHouseholderQr().solve(b);
  return {c(2), -c(3)};
}

TEST(DynamicsTimeVsFrequency, NewmarkSteadyStateMatchesSteadyStateStep) {
  const mesh::Mesh mesh = column(10.0, 10.0, 3);
  auto mat = std::make_shared<material::Viscoelastic>(hyperfoam(),
                                                      std::vector<material::PronyTerm>{{0.3, 0.02}, {0.2, 0.2}});
  std::vector<Section> sections{{"foam", {0, 1, 2}, mat, Formulation::full, 1.5e-7}};  // first mode ~60 Hz
  const auto base = set_dofs(mesh, "zmin", 2), top = set_dofs(mesh, "zmax", 2), lateral = lateral_dofs(mesh);
  Assembler A(mesh, sections, DofMap(mesh.num_nodes(), constrained_mask(mesh, {base, top, lateral})), AssemblyOptions{1});
  StateStore st0 = A.make_state_store();
  Eigen::VectorXd u_pre = Eigen::VectorXd::Zero(3 * mesh.num_nodes());
  ramp(A, st0, u_pre, top, -2.0, 8, 1e6);  // relaxed 20 % preload

  const auto points = base_point_states(A, st0, u_pre, BaseStress::relaxed);
  LinearisedSystem sys(mesh, sections, points, u_pre);
  const Damping damp{180.0, 1e-4, 0.0};
  HarmonicModel model;
  model.system = &sys;
  Excitation x{base, lateral};
  x.held.insert(x.held.end(), top.begin(), top.end());
  SteadyStateSolver ssd(model, damp, x, {{"top", top}, {"base", base}});
  const SparseMatrix C = damping_matrix(damp, sys.mass(), sys.long_term_stiffness());

  const double U = 0.005;  // [mm]
  for (double f : {1.0, 5.0, 20.0}) {
    const double w = 2 * M_PI * f;
    const cplx K_ssd = ssd.solve(f, U).reaction[0] / U;

    StateStore st = st0;
    NewmarkIntegrator nm(A, sys.mass(), C);
    auto lin = make_linear_solver(LinearSolverKind::lu);
    Kinematics k{u_pre, Eigen::VectorXd::Zero(u_pre.size()), Eigen::VectorXd::Zero(u_pre.size())};
    const int per_cycle = 100;
    const int cycles = static_cast<int>(std::ceil(std::max(5.0, 1.6 * f)));  // >= 8 tau_2 of transient decay
    const double dt = 1.0 / (f * per_cycle);
    std::vector<double> t_fit, r_fit;
    NewtonOptions o;
    o.residual_tolerance = 1e-10;
    o.correction_tolerance = 1e-10;
    o.force_floor = 1e-12;
    for (int i = 1; i <= cycles * per_cycle; ++i) {
      const double t = i * dt;
      Kinematics p = k;
      for (int d : base) p.u(d) = U * std::sin(w * t), p.v(d) = U * w * std::cos(w * t), p.a(d) = -U * w * w * std::sin(w * t);
      const NewtonResult r = nm.step(st, *lin, k, dt, p, Eigen::VectorXd::Zero(u_pre.size()), o);
      ASSERT_TRUE(r.converged()) << f << " Hz, step " << i << ": " << r.message;
      st.commit();
      if (i > (cycles - 2) * per_cycle) {
        double R = 0.0;
        for (int d : top) R += nm.support_force()(d);
        t_fit.push_back(t);
        r_fit.push_back(R);
      }
    }
    // The drive U sin(w t) has the phasor -i U.
    const cplx K_time = fit_phasor(t_fit, r_fit, w) / cplx(0.0, -U);
    EXPECT_LT(amplitude_error(K_time, K_ssd), 1e-2) << f << " Hz";
    EXPECT_LT(phase_error_deg(K_time, K_ssd), 0.5) << f << " Hz";
    std::printf("%5.1f Hz: |K| ssd %.6g time %.6g N/mm, phase ssd %.4f time %.4f deg\n", f, std::abs(K_ssd),
                std::abs(K_time), std::arg(-K_ssd) * 180 / M_PI, std::arg(-K_time) * 180 / M_PI);
  }
}

}  // namespace
}  // namespace cushion::solver::test
