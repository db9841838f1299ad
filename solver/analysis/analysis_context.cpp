#include "solver/analysis/analysis_context.hpp"

namespace cushion::solver {

void TimedLinearSolver::factorize(const Eigen::SparseMatrix<double>& A) {
  ++stats_.factorizations;
  timed(stats_.factorization_time, [&] { inner_->factorize(A); });
}

Eigen::VectorXd TimedLinearSolver::solve(const Eigen::VectorXd& b) {
  return timed(stats_.solve_time, [&] { return inner_->solve(b); });
}

AnalysisContext::AnalysisContext(const mesh::Mesh& mesh_, const CaseSpec& spec_, std::vector<Section> sections,
                                 LinearSolverKind linear_kind, unsigned threads, AnalysisOutput& output_,
                                 std::ostream& log_, std::ostream* progress_)
    : mesh(mesh_), spec(spec_), output(output_), log(log_), progress(progress_),
      u(Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(mesh_.num_nodes()))), f_int(u),
      constrained(u.size(), false), sections_(std::move(sections)), linear_kind_(linear_kind), threads_(threads),
      start_(std::chrono::steady_clock::now()) {}

System& AnalysisContext::system(const std::vector<bool>& mask) {
  for (auto& s : systems_)
    if (s->constrained == mask) return *s;
  auto s = std::make_unique<System>();
  s->constrained = mask;
  s->assembler = std::make_unique<Assembler>(mesh, sections_, DofMap(mesh.num_nodes(), mask), AssemblyOptions{threads_});
  s->linear = std::make_unique<TimedLinearSolver>(make_linear_solver(linear_kind_), stats);
  if (systems_.empty()) state = s->assembler->make_state_store();  // same layout for every system
  systems_.push_back(std::move(s));
  return *systems_.back();
}

double AnalysisContext::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

}  // namespace cushion::solver
