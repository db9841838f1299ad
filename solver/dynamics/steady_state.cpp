#include "solver/dynamics/steady_state.hpp"

#include <chrono>
#include <stdexcept>

#include <Eigen/CholmodSupport>

#include "solver/dof_map.hpp"
#include <unsupported/Eigen/IterativeSolvers>

namespace cushion::solver::dynamics {
namespace {

using cplx = std::complex<double>;

/// A square n x n copy of A (top-left block), zero elsewhere.
SparseMatrix embedded(const SparseMatrix& A, std::size_t n) {
  SparseMatrix B = A;
  B.conservativeResize(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  B.makeCompressed();
  return B;
}

/// Rows `dofs` of the n x n identity.
SparseMatrix selection(const std::vector<int>& dofs, std::size_t n) {
  SparseMatrix P(static_cast<Eigen::Index>(dofs.size()), static_cast<Eigen::Index>(n));
  std::vector<Eigen::Triplet<double>> t;
  for (std::size_t i = 0; i < dofs.size(); ++i) t.emplace_back(static_cast<int>(i), dofs[i], 1.0);
  P.setFromTriplets(t.begin(), t.end());
  return P;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// P^-1 of a real matrix P = Re D_ff(w_ref), applied to the columns of B.
class RealPreconditioner {
 public:
  virtual ~RealPreconditioner() = default;
  /// Prepares P^-1; false if P cannot serve (not positive definite, or the solver failed on it).
  virtual bool set(const SparseMatrix& P) = 0;
  /// P^-1 B; throws LinearSolveError if an iterative solver does not converge.
  virtual Eigen::MatrixXd apply(const Eigen::MatrixXd& B) = 0;
  /// Where P's unknowns sit (LinearSolver::set_geometry); ignored by a factorisation.
  virtual void set_geometry(const DofMap&, const std::vector<Eigen::Vector3d>&) {}
};

/// A CHOLMOD supernodal Cholesky factor of P (lower triangle).
class CholmodPreconditioner final : public RealPreconditioner {
 public:
  CholmodPreconditioner() { factor_.cholmod().print = 0; }
  bool set(const SparseMatrix& P) override {
    factor_.compute(P);
    return factor_.info() == Eigen::Success;
  }
  Eigen::MatrixXd apply(const Eigen::MatrixXd& B) override { return factor_.solve(B); }

 private:
  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> factor_;
};

/// Any LinearSolver (e.g. PETSc CG + algebraic multigrid) solving with P, one column at a time.
class SolverPreconditioner final : public RealPreconditioner {
 public:
  explicit SolverPreconditioner(std::unique_ptr<LinearSolver> solver) : solver_(std::move(solver)) {}
  bool set(const SparseMatrix& P) override {
    try {
      solver_->factorize(P);
      return true;
    } catch (const SingularMatrixError&) {
      return false;
    } catch (const LinearSolveError&) {
      return false;
    }
  }
  Eigen::MatrixXd apply(const Eigen::MatrixXd& B) override {
    Eigen::MatrixXd X(B.rows(), B.cols());
    for (Eigen::Index c = 0; c < B.cols(); ++c) X.col(c) = solver_->solve(B.col(c));
    return X;
  }
  void set_geometry(const DofMap& dofs, const std::vector<Eigen::Vector3d>& nodes) override {
    solver_->set_geometry(dofs, nodes);
  }

 private:
  std::unique_ptr<LinearSolver> solver_;
};

/// Eigen's preconditioner interface over a RealPreconditioner: P^-1 on the real and imaginary parts.
class GmresPreconditioner {
 public:
  template <class M>
  GmresPreconditioner& analyzePattern(const M&) { return *this; }
  template <class M>
  GmresPreconditioner& factorize(const M&) { return *this; }
  template <class M>
  GmresPreconditioner& compute(const M&) { return *this; }
  Eigen::ComputationInfo info() const { return Eigen::Success; }
  void set(RealPreconditioner* p) { p_ = p; }
  template <class V>
  Eigen::VectorXcd solve(const Eigen::MatrixBase<V>& b) const {
    Eigen::MatrixXd B(b.rows(), 2);
    B.col(0) = b.real();
    B.col(1) = b.imag();
    const Eigen::MatrixXd X = p_->apply(B);
    Eigen::VectorXcd x(b.rows());
    x.real() = X.col(0);
    x.imag() = X.col(1);
    return x;
  }

 private:
  RealPreconditioner* p_ = nullptr;
};

}  // namespace

struct SteadyStateSolver::Preconditioner {
  std::unique_ptr<RealPreconditioner> p;
  bool valid = false;
};

SteadyStateSolver::~SteadyStateSolver() = default;

SteadyStateSolver::SteadyStateSolver(HarmonicModel model, Damping damping, Excitation excitation,
                                     std::vector<DofGroup> groups, SolveMethod method)
    : model_(std::move(model)), damping_(damping), groups_(std::move(groups)), method_(method),
      precond_(std::make_unique<Preconditioner>()) {
  precond_->p = std::make_unique<CholmodPreconditioner>();
  if (method_.preconditioner) precond_->p = std::make_unique<SolverPreconditioner>(method_.preconditioner());
  if (!model_.system) throw std::invalid_argument("steady-state: no linearised system");
  const auto missing = model_.system->sections_without_density();
  if (!missing.empty())
    throw std::invalid_argument("steady-state: section \"" + missing.front() +
                                "\" has no mass density (give density_kg_m3 in its material file)");
  if (damping_.rayleigh_alpha < 0.0 || damping_.rayleigh_beta < 0.0 || damping_.structural < 0.0)
    throw std::invalid_argument("steady-state: damping coefficients must be >= 0");
  if (excitation.driven.empty() && excitation.force.empty())
    throw std::invalid_argument("steady-state: no driven DOF and no force");
  n_ = model_.system->num_dofs() + static_cast<std::size_t>(model_.extra_dofs);
  std::vector<int> role(n_, 0);  // 0 free, 1 driven, 2 held
  auto mark = [&](const std::vector<int>& dofs, int r) {
    for (int d : dofs) {
      if (d < 0 || d >= static_cast<int>(n_)) throw std::invalid_argument("steady-state: DOF out of range");
      if (role[d] != 0 && role[d] != r) throw std::invalid_argument("steady-state: a DOF is both driven and held");
      role[d] = r;
    }
  };
  mark(excitation.driven, 1);
  mark(excitation.held, 2);
  for (std::size_t d = 0; d < n_; ++d) (role[d] == 0 ? free_ : constrained_).push_back(static_cast<int>(d));
  unit_c_.setZero(static_cast<Eigen::Index>(constrained_.size()));
  for (std::size_t k = 0; k < constrained_.size(); ++k)
    if (role[constrained_[k]] == 1) unit_c_(static_cast<Eigen::Index>(k)) = 1.0;
  std::vector<int> free_index(n_, -1);
  for (std::size_t k = 0; k < free_.size(); ++k) free_index[free_[k]] = static_cast<int>(k);
  unit_f_.setZero(static_cast<Eigen::Index>(free_.size()));
  for (const auto& [d, f] : excitation.force) {
    if (d < 0 || d >= static_cast<int>(n_)) throw std::invalid_argument("steady-state: force DOF out of range");
    if (free_index[d] >= 0) unit_f_(free_index[d]) += f;
  }
  for (const auto& g : groups_)
    for (int d : g.dofs)
      if (d < 0 || d >= static_cast<int>(n_)) throw std::invalid_argument("steady-state: group " + g.name + " DOF out of range");

  K0_ = embedded(model_.system->long_term_stiffness(), n_);
  M_ = embedded(model_.system->mass(), n_);
  if (!model_.lumped_mass.empty()) {
    SparseMatrix L(static_cast<Eigen::Index>(n_), static_cast<Eigen::Index>(n_));
    std::vector<Eigen::Triplet<double>> t;
    for (const auto& [d, m] : model_.lumped_mass) {
      if (d < 0 || d >= static_cast<int>(n_) || m < 0.0) throw std::invalid_argument("steady-state: bad lumped mass");
      t.emplace_back(d, d, m);
    }
    L.setFromTriplets(t.begin(), t.end());
    M_ = SparseMatrix(M_ + L);
  }
  Kx_ = model_.extra_stiffness.size() == 0 ? SparseMatrix(static_cast<Eigen::Index>(n_), static_cast<Eigen::Index>(n_))
                                           : model_.extra_stiffness;
  if (Kx_.rows() != static_cast<Eigen::Index>(n_) || Kx_.cols() != static_cast<Eigen::Index>(n_))
    throw std::invalid_argument("steady-state: extra stiffness must be n x n");
  Pf_ = selection(free_, n_);
  Pc_ = selection(constrained_, n_);
  // Algebraic multigrid builds its near-null space (rigid-body modes) from the nodes: when the free
  // DOFs are node DOFs only.
  if (method_.geometry && model_.extra_dofs == 0) {
    std::vector<bool> held(n_, true);
    for (int d : free_) held[d] = false;
    precond_->p->set_geometry(DofMap(n_ / 3, held), *method_.geometry);
  }
}

ComplexMatrix SteadyStateSolver::dynamic_matrix(double omega) const {
  const SparseMatrix re = Kx_ - omega * omega * M_;
  const SparseMatrix im = damping_.structural * K0_ + omega * damping_matrix(damping_, M_, K0_);
  ComplexMatrix Ks = model_.system->stiffness(omega);
  Ks.conservativeResize(static_cast<Eigen::Index>(n_), static_cast<Eigen::Index>(n_));
  ComplexMatrix D = Ks + re.cast<cplx>() + cplx(0.0, 1.0) * im.cast<cplx>();
  D.makeCompressed();
  return D;
}

FrequencyResponse SteadyStateSolver::solve(double frequency, cplx amplitude) {
  if (!(frequency > 0.0)) throw std::invalid_argument("steady-state: frequencies must be > 0 Hz");
  const double omega = 2.0 * M_PI * frequency;
  auto t0 = std::chrono::steady_clock::now();
  const ComplexMatrix D = dynamic_matrix(omega);
  const ComplexMatrix Pf = Pf_.cast<cplx>(), Pc = Pc_.cast<cplx>();
  ComplexMatrix Dff = Pf * D * ComplexMatrix(Pf.transpose());
  Dff.makeCompressed();
  const ComplexMatrix Dfc = Pf * D * ComplexMatrix(Pc.transpose());
  const Eigen::VectorXcd uc = amplitude * unit_c_;
  const Eigen::VectorXcd b = amplitude * unit_f_ - Dfc * uc;
  stats_.assembly_time += seconds_since(t0);
  Eigen::VectorXcd uf;
  if (!method_.iterative || !solve_iterative(Dff, b, uf)) {
    t0 = std::chrono::steady_clock::now();
    lu_.factorize(Dff);
    ++stats_.complex_factorisations;
    stats_.factorisation_time += seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    uf = lu_.solve(b);
    stats_.solve_time += seconds_since(t0);
  }

  FrequencyResponse r;
  r.frequency = frequency;
  r.amplitude = amplitude;
  r.u.setZero(static_cast<Eigen::Index>(n_));
  for (std::size_t k = 0; k < free_.size(); ++k) r.u(free_[k]) = uf(static_cast<Eigen::Index>(k));
  for (std::size_t k = 0; k < constrained_.size(); ++k) r.u(constrained_[k]) = uc(static_cast<Eigen::Index>(k));
  const Eigen::VectorXcd f = D * r.u;  // residual: zero at free DOFs, reactions at constrained ones
  std::vector<bool> is_constrained(n_, false);
  for (int d : constrained_) is_constrained[d] = true;
  for (const auto& g : groups_) {
    cplx R = 0.0, U = 0.0;
    for (int d : g.dofs) {
      if (is_constrained[d]) R += f(d);
      U += r.u(d);
    }
    r.reaction.push_back(R);
    r.displacement.push_back(g.dofs.empty() ? cplx(0.0) : U / static_cast<double>(g.dofs.size()));
  }
  return r;
}

bool SteadyStateSolver::solve_iterative(const ComplexMatrix& Dff, const Eigen::VectorXcd& b, Eigen::VectorXcd& x) {
  for (int attempt = 0; attempt < 2; ++attempt) {
    if (!precond_->valid || attempt == 1) {  // P = Re D_ff at this frequency
      const auto t0 = std::chrono::steady_clock::now();
      SparseMatrix P = Dff.real();
      P.makeCompressed();
      precond_->valid = precond_->p->set(P);
      ++stats_.real_factorisations;
      stats_.factorisation_time += seconds_since(t0);
      if (!precond_->valid) return false;  // not positive definite (above a resonance): LU
    }
    const auto t0 = std::chrono::steady_clock::now();
    Eigen::GMRES<ComplexMatrix, GmresPreconditioner> gmres;
    gmres.set_restart(method_.max_iterations);
    gmres.setMaxIterations(method_.max_iterations);
    gmres.preconditioner().set(precond_->p.get());
    gmres.compute(Dff);
    // Eigen's GMRES stops on the preconditioned residual: passes from the last x with the tolerance
    // tightened until the TRUE relative residual |b - D x| / |b| meets method_.tolerance.
    x = Eigen::VectorXcd::Zero(b.size());
    double tol = method_.tolerance;
    bool ok = false;
    for (int pass = 0; pass < 4 && !ok; ++pass) {
      gmres.setTolerance(tol);
      try {
        x = gmres.solveWithGuess(b, x);
      } catch (const LinearSolveError&) {
        break;  // the preconditioner's own Krylov solve did not converge: as GMRES failing
      }
      stats_.iterations += static_cast<int>(gmres.iterations());
      if (gmres.info() != Eigen::Success || !x.allFinite()) break;
      const double residual = (b - Dff * x).norm() / b.norm();
      ok = residual <= method_.tolerance;
      tol = std::max(0.5 * tol * method_.tolerance / residual, 1e-15);
    }
    stats_.solve_time += seconds_since(t0);
    if (ok) return true;
  }
  return false;
}

}  // namespace cushion::solver::dynamics
