#pragma once
/// Displacement boundary conditions of one step on the full DOF vector (3 per node, reference
/// frame axes, mm). A step lists all its conditions (case_spec.hpp); how the driver treats DOFs
/// whose constraint changes between steps is described in analysis.hpp.
#include <map>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "mesh/mesh.hpp"
#include "solver/case/case_spec.hpp"

namespace cushion::solver {

/// Constrained DOFs of a step: true for every component a condition of the step prescribes
/// (size 3 x nodes). Sets must exist in the mesh (std::out_of_range otherwise; load_case checks).
std::vector<bool> constrained_mask(const mesh::Mesh& mesh, const StepSpec& step);

/// Prescribed displacements of one step as functions of the step time.
class StepBoundary {
 public:
  /// `u_start`: full displacement vector at the start of the step [mm] (start values of the default
  /// linear ramps); `t_start`: total time at the start of the step [s].
  /// `f_start`: concentrated loads at the end of the previous step [N] (full vector; empty: none).
  StepBoundary(const mesh::Mesh& mesh, const StepSpec& step, const std::map<std::string, Amplitude>& amplitudes,
               double t_start, const Eigen::VectorXd& u_start, Eigen::VectorXd f_start = Eigen::VectorXd());

  /// Writes the prescribed values at step time t [s] into the constrained entries of `u` (full
  /// vector [mm]). Conditions are applied in the order listed: on a DOF named by two conditions the
  /// later one wins.
  void apply(double t_step, Eigen::VectorXd& u) const;
  /// The same with the time derivatives (prescribed_motion, case_spec.hpp): prescribed displacement
  /// [mm], velocity [mm/s] and acceleration [mm/s^2] at step time t [s] into the constrained entries
  /// of the full vectors u, v, a (dynamic steps).
  void apply_motion(double t_step, Eigen::VectorXd& u, Eigen::VectorXd& v, Eigen::VectorXd& a) const;

  /// Concentrated loads of the step (StepSpec::loads) at step time t [s] [N], full vector: each ramps
  /// from its start value (or follows its amplitude); a start load the step does not list ramps to 0.
  Eigen::VectorXd loads(double t_step) const;

  /// Corner times of the step's amplitudes as step times in (0, period) [s]: increments end there
  /// exactly, so piecewise-linear histories are followed without cutting corners.
  std::vector<double> corner_times() const;

 private:
  struct Entry {
    const BoundarySpec* bc;
    std::vector<int> dofs;  ///< global DOFs the condition prescribes
  };
  const StepSpec& step_;
  const std::map<std::string, Amplitude>& amplitudes_;
  double t_start_;
  Eigen::VectorXd u_start_;
  std::vector<Entry> entries_;
  struct LoadEntry {
    const LoadSpec* load;
    std::vector<int> dofs;
  };
  Eigen::VectorXd f_start_;
  std::vector<LoadEntry> loads_;
};

}  // namespace cushion::solver
