#include "solver/analysis/analysis_output.hpp"

#include "io/text_support.hpp"

#include <algorithm>
#include <cctype>
#include <span>

namespace cushion::solver {

namespace {

/// Frobenius norm of the viscous part of the Cauchy stress at one point [MPa] (Material::viscous_stress
/// of the point's trial state).
double viscous_norm(const material::Material& m, const PointOutput& p, std::span<const double> state) {
  return cauchy_from_pk2(p.F, from_voigt_stress(m.viscous_stress(p.F, state))).norm();
}

}  // namespace

FrameData make_frame(double time, const Assembler& assembler, const std::vector<PointOutput>& points,
                     const StateStore& state, const Eigen::VectorXd& u, const Eigen::VectorXd& f_int) {
  const mesh::Mesh& mesh = assembler.mesh();
  const DofMap& dofs = assembler.dofs();
  FrameData frame;
  frame.time = time;
  frame.displacement.resize(mesh.num_nodes());
  frame.reaction_force.assign(mesh.num_nodes(), Vec3::Zero());
  for (std::size_t a = 0; a < mesh.num_nodes(); ++a)
    for (int c = 0; c < 3; ++c) {
      const int d = DofMap::dof(static_cast<int>(a), c);
      frame.displacement[a](c) = u(d);
      if (dofs.is_constrained(d)) frame.reaction_force[a](c) = f_int(d);
    }
  const std::size_t ne = mesh.num_elements();
  frame.cauchy_stress.assign(ne, Mat3::Zero());
  frame.deformation_gradient.assign(ne, Mat3::Identity());
  frame.viscous_stress_norm.assign(ne, 0.0);
  for (std::size_t e = 0; e < ne; ++e) {
    const int section = assembler.section_of(static_cast<int>(e));
    if (section < 0) continue;  // element without material: zero stress, F = I
    const material::Material& m = *assembler.sections()[section].material;
    const std::size_t first = assembler.point_offset(static_cast<int>(e));
    const int n = num_points(mesh.elements[e].type);
    const std::span<const double> element_state = state.new_state(static_cast<int>(e));
    const std::size_t state_size = m.state_size();
    Mat3 sigma = Mat3::Zero(), F = Mat3::Zero();
    double visc = 0.0, V = 0.0;
    for (int q = 0; q < n; ++q) {
      const PointOutput& p = points[first + q];
      sigma += p.dV0 * from_voigt_stress(p.sigma);
      F += p.dV0 * p.F;
      visc += p.dV0 * viscous_norm(m, p, element_state.subspan(static_cast<std::size_t>(q) * state_size, state_size));
      V += p.dV0;
    }
    frame.cauchy_stress[e] = sigma / V;
    frame.deformation_gradient[e] = F / V;
    frame.viscous_stress_norm[e] = visc / V;
  }
  return frame;
}

HistoryColumns::HistoryColumns(const CaseSpec& spec, const mesh::Mesh& mesh) {
  for (const StepSpec& step : spec.steps)
    for (const HistoryRequest& request : step.output.history)
      for (HistoryQuantity q : request.quantities) {
        const std::string name = history_column(request.set, q);
        if (std::find(names_.begin(), names_.end(), name) != names_.end()) continue;
        const int k = static_cast<int>(q);
        names_.push_back(name);
        columns_.push_back({&mesh.node_sets.at(request.set), k % 3, k >= 3});
      }
}

std::vector<double> HistoryColumns::values(const Eigen::VectorXd& u, const Eigen::VectorXd& f_int,
                                           const DofMap& dofs) const {
  std::vector<double> out;
  for (const Column& c : columns_) {
    double sum = 0.0;
    for (int node : *c.nodes) {
      const int d = DofMap::dof(node, c.component);
      sum += c.reaction ? (dofs.is_constrained(d) ? f_int(d) : 0.0) : u(d);
    }
    out.push_back(c.reaction ? sum : sum / static_cast<double>(c.nodes->size()));
  }
  return out;
}

namespace {

/// Column names of a print request after "time_s".
std::vector<std::string> print_columns(const PrintRequest& r) {
  const bool node = r.kind == PrintRequest::Kind::node;
  std::vector<std::string> columns{node ? "node" : "element"};
  auto has = [&r](const char* q) { return std::find(r.quantities.begin(), r.quantities.end(), q) != r.quantities.end(); };
  if (node && has("U")) columns.insert(columns.end(), {"U1_mm", "U2_mm", "U3_mm"});
  if (node && has("RF")) columns.insert(columns.end(), {"RF1_N", "RF2_N", "RF3_N"});
  if (!node && has("S")) columns.insert(columns.end(), {"S11_kPa", "S22_kPa", "S33_kPa", "S12_kPa", "S13_kPa", "S23_kPa"});
  return columns;
}


}  // namespace

PrintTables::PrintTables(const CaseSpec& spec, const mesh::Mesh& mesh, const std::filesystem::path& dir) : mesh_(mesh) {
  for (const PrintRequest& r : spec.prints) {
    const bool node = r.kind == PrintRequest::Kind::node;
    const std::string file = (node ? "node_print_" : "el_print_") + io::file_safe_name(r.set) + ".csv";
    tables_.push_back({&r, node ? &mesh.node_sets.at(r.set) : &mesh.element_sets.at(r.set),
                       std::make_unique<HistoryWriter>(
                           dir / file, print_columns(r),
                           std::vector<std::string>{"cushion run " + spec.file.string() + ": " +
                                                    (node ? "*NODE PRINT" : "*EL PRINT") + " of set " + r.set +
                                                    " at every frame (total time)",
                                                    node ? "U displacement [mm], RF reaction force [N]"
                                                         : "S Cauchy stress averaged over the element [kPa]"})});
  }
}

void PrintTables::write(const FrameData& frame) const {
  for (const Table& t : tables_) {
    const std::vector<std::string>& columns = t.writer->columns();
    for (int m : *t.members) {
      std::vector<double> row;
      if (t.request->kind == PrintRequest::Kind::node) {
        row.push_back(mesh_.node_labels.empty() ? m + 1 : mesh_.node_labels[m]);
        for (std::size_t c = 1; c < columns.size(); ++c) {
          const bool reaction = columns[c].rfind("RF", 0) == 0;
          const int k = columns[c][reaction ? 2 : 1] - '1';
          row.push_back(reaction ? frame.reaction_force[m](k) : frame.displacement[m](k));
        }
      } else {
        row.push_back(mesh_.elements[m].label);
        const Mat3& s = frame.cauchy_stress[m];
        if (columns.size() > 1)
          for (double v : {s(0, 0), s(1, 1), s(2, 2), s(0, 1), s(0, 2), s(1, 2)}) row.push_back(1e3 * v);  // MPa -> kPa
      }
      t.writer->write_row(frame.time, row);
    }
  }
}

struct AnalysisOutput::Files {
  ResultSeries series;
  HistoryWriter history;
  PrintTables prints;
};

AnalysisOutput::AnalysisOutput(const CaseSpec& spec, const mesh::Mesh& mesh, const std::filesystem::path& dir,
                               bool writes)
    : mesh_(mesh), dir_(dir), columns_(spec, mesh) {
  if (!writes) return;
  files_.reset(new Files{ResultSeries(dir, "results"),
                         HistoryWriter(dir / "history.csv", columns_.names(),
                                       {"cushion run " + spec.file.string() + ": history per converged increment",
                                        "U = mean displacement of the set [mm], RF = sum of reaction forces over "
                                        "the set [N]"}),
                         PrintTables(spec, mesh, dir)});
}

AnalysisOutput::~AnalysisOutput() = default;

void AnalysisOutput::write_frame(FrameData frame) {
  if (files_) {
    files_->series.write_frame(mesh_, frame);
    files_->prints.write(frame);
  }
  ++frames_;
  last_frame_time_ = frame.time;
}

void AnalysisOutput::write_history(double time, const Eigen::VectorXd& u, const Eigen::VectorXd& f_int,
                                   const DofMap& dofs) {
  if (files_) files_->history.write_row(time, columns_.values(u, f_int, dofs));
}

}  // namespace cushion::solver
