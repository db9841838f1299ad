#include "solver/analysis/analysis_context.hpp"

#include "solver/analysis/contact_contributor.hpp"

namespace cushion::solver {

void TimedLinearSolver::factorize(const Eigen::SparseMatrix<double>& A) {
  ++stats_.factorizations;
  timed(stats_.factorization_time, [&] { inner_->factorize(A); });
}

Eigen::VectorXd TimedLinearSolver::solve(const Eigen::VectorXd& b) {
  // The report is written even when the solve throws (a Krylov method that did not converge).
  struct Report {
    const LinearSolver& s;
    std::ostream& log;
    ~Report() {
      if (const std::string r = s.last_solve_report(); !r.empty()) log << "      " << r << "\n";
    }
  } report{*inner_, log_};
  return timed(stats_.solve_time, [&] { return inner_->solve(b); });
}

AnalysisContext::AnalysisContext(const mesh::Mesh& mesh, const CaseSpec& spec, std::vector<Section> sections,
                                 LinearSolverFactory make_linear, unsigned threads, AnalysisOutput& output,
                                 std::ostream& log, std::ostream* progress,
                                 std::shared_ptr<const Distribution> distribution,
                                 LinearSolverFactory make_sweep_preconditioner)
    : mesh_(mesh), spec_(spec), output_(output), log_(log), progress_(progress), sections_(std::move(sections)),
      make_linear_(std::move(make_linear)), make_sweep_preconditioner_(std::move(make_sweep_preconditioner)),
      threads_(threads), distribution_(std::move(distribution)),
      start_(std::chrono::steady_clock::now()) {
  model_.u = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(mesh.num_nodes()));
  model_.f_int = model_.u;
  model_.constrained.assign(model_.u.size(), false);
}

void AnalysisContext::report_progress(const std::string& line) {
  if (progress_) *progress_ << line << std::endl;
}

System& AnalysisContext::system(const std::vector<bool>& mask) {
  for (auto& s : systems_)
    if (s->constrained == mask) return *s;
  auto s = std::make_unique<System>();
  s->constrained = mask;
  s->assembler =
      std::make_unique<Assembler>(mesh_, sections_, DofMap(mesh_.num_nodes(), mask), AssemblyOptions{threads_, distribution_});
  s->linear = std::make_unique<TimedLinearSolver>(make_linear_(), stats_, log_);
  s->linear->set_geometry(s->assembler->dofs(), mesh_.nodes);
  if (systems_.empty()) model_.material = s->assembler->make_state_store();  // same layout for every system
  systems_.push_back(std::move(s));
  return *systems_.back();
}

std::shared_ptr<ContactContributor> AnalysisContext::contact(const ContactSpec& spec) {
  auto& slot = contacts_[spec.name];
  if (!slot) slot = std::make_shared<ContactContributor>(spec, *this);
  return slot;
}

const ContactContributor* AnalysisContext::find_contact(const std::string& name) const {
  const auto it = contacts_.find(name);
  return it == contacts_.end() ? nullptr : it->second.get();
}

double AnalysisContext::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

}  // namespace cushion::solver
