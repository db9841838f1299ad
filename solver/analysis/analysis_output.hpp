#pragma once
/// Result output of an analysis: frames (.vtu per frame + results.pvd) and the history table
/// (history.csv), built from converged states only. Every file is complete after every write
/// (the writers rename temporary files and flush rows), so an interrupted or failed run leaves
/// readable results up to its last converged frame.
#include <filesystem>
#include <memory>
#include <vector>

#include <Eigen/Dense>

#include "solver/assembler.hpp"
#include "solver/case/case_spec.hpp"
#include "solver/output/frame_data.hpp"
#include "solver/output/history_csv.hpp"
#include "solver/output/vtu_writer.hpp"

namespace cushion::solver {

/// One frame from a converged state: displacements u [mm] (full), reaction forces [N] = f_int at
/// the constrained DOFs of `assembler` (zero elsewhere), and per element the reference-volume
/// average over its quadrature points (`points` and the trial state in `state` from
/// Assembler::assemble at u) of the Cauchy stress [MPa], of F [-] and of the Frobenius norm of the
/// viscous Cauchy stress F S_visc F^T / J [MPa] (S_visc: Material::viscous_stress, e.g. S - S_inf(F)
/// of a Prony material, also under effects; 0 for elastic materials).
FrameData make_frame(double time, const Assembler& assembler, const std::vector<PointOutput>& points,
                     const StateStore& state, const Eigen::VectorXd& u, const Eigen::VectorXd& f_int);

/// History values in the order of history_columns(spec): Ui = mean displacement of the set [mm],
/// RFi = sum over the set of the reactions f_int at constrained DOFs [N] (0 where free).
/// Every column is written at every increment (the sets exist in every step).
class HistoryColumns {
 public:
  HistoryColumns(const CaseSpec& spec, const mesh::Mesh& mesh);
  const std::vector<std::string>& names() const { return names_; }
  std::vector<double> values(const Eigen::VectorXd& u, const Eigen::VectorXd& f_int, const DofMap& dofs) const;

 private:
  struct Column {
    const std::vector<int>* nodes;
    int component;
    bool reaction;
  };
  std::vector<std::string> names_;
  std::vector<Column> columns_;
};

/// The CSV tables of the case's print requests (PrintRequest, case_spec.hpp): node_print_<set>.csv
/// "time_s,node,U1_mm,U2_mm,U3_mm,RF1_N,RF2_N,RF3_N" (the requested groups) and el_print_<set>.csv
/// "time_s,element,S11_kPa,S22_kPa,S33_kPa,S12_kPa,S13_kPa,S23_kPa" (element-mean Cauchy stress), one
/// row per member and frame, labels as in the mesh file.
class PrintTables {
 public:
  PrintTables(const CaseSpec& spec, const mesh::Mesh& mesh, const std::filesystem::path& dir);
  void write(const FrameData& frame) const;

 private:
  struct Table {
    const PrintRequest* request;
    const std::vector<int>* members;
    std::unique_ptr<HistoryWriter> writer;
  };
  const mesh::Mesh& mesh_;
  std::vector<Table> tables_;
};

/// Files of one run: <dir>/results.pvd + results_NNNN.vtu and <dir>/history.csv. In a distributed
/// run only process 0 writes (`writes` false elsewhere: nothing is created, writes are counted only).
class AnalysisOutput {
 public:
  /// Creates the folder and (truncates) the files if `writes`. std::runtime_error if they cannot be written.
  AnalysisOutput(const CaseSpec& spec, const mesh::Mesh& mesh, const std::filesystem::path& dir, bool writes = true);
  ~AnalysisOutput();

  /// Writes a frame (see make_frame) plus extra arrays (e.g. from residual contributors).
  void write_frame(FrameData frame);
  /// Appends one history row at total time `time` [s].
  void write_history(double time, const Eigen::VectorXd& u, const Eigen::VectorXd& f_int, const DofMap& dofs);

  /// A further table <dir>/<file_name> (HistoryWriter), or a writer that writes nothing where writes() is false.
  HistoryWriter table(const std::string& file_name, std::vector<std::string> columns,
                      const std::vector<std::string>& comment) const {
    if (!writes()) return HistoryWriter(std::move(columns));
    return HistoryWriter(dir_ / file_name, std::move(columns), comment);
  }
  /// False on the processes of a distributed run that write nothing (every file writer asks this).
  bool writes() const { return files_ != nullptr; }
  std::filesystem::path pvd_file() const { return dir_ / "results.pvd"; }
  std::filesystem::path history_file() const { return dir_ / "history.csv"; }
  std::size_t frame_count() const { return frames_; }
  double last_frame_time() const { return last_frame_time_; }  ///< total time [s], -1 before any frame

 private:
  struct Files;
  const mesh::Mesh& mesh_;
  std::filesystem::path dir_;
  HistoryColumns columns_;
  std::unique_ptr<Files> files_;
  std::size_t frames_ = 0;
  double last_frame_time_ = -1.0;
};

}  // namespace cushion::solver
