#pragma once
/// Degrees of freedom: 3 displacement components per node (dof = 3 node + component). Dirichlet-
/// constrained DOFs are eliminated: the linear systems live on the free DOFs ("equations"), and
/// constrained values are imposed directly in the full displacement vector.
#include <cstddef>
#include <vector>

#include <Eigen/Dense>

namespace cushion::solver {

/// Numbering of the free and constrained DOFs.
class DofMap {
 public:
  /// num_nodes nodes, constrained[dof] true for every Dirichlet DOF (size 3 num_nodes, or empty = none).
  DofMap(std::size_t num_nodes, const std::vector<bool>& constrained);

  /// Global DOF index of component c (0, 1, 2 = x, y, z) of node `node`.
  static int dof(int node, int c) { return 3 * node + c; }

  /// Total DOFs (3 per node).
  std::size_t num_dofs() const { return equation_.size(); }
  /// Free DOFs = size of the reduced system.
  std::size_t num_free() const { return free_dofs_.size(); }
  /// Equation (free-DOF index) of a global DOF, -1 if constrained.
  int equation(int dof) const { return equation_[dof] < 0 ? -1 : equation_[dof]; }
  /// True for a Dirichlet DOF.
  bool is_constrained(int dof) const { return equation_[dof] < 0; }
  /// Position of a constrained global DOF in constrained_dofs(), -1 if free.
  int constrained_index(int dof) const { return equation_[dof] < 0 ? -equation_[dof] - 1 : -1; }
  /// Global DOF of each equation, ascending.
  const std::vector<int>& free_dofs() const { return free_dofs_; }
  /// Constrained global DOFs, ascending.
  const std::vector<int>& constrained_dofs() const { return constrained_dofs_; }

  /// Free part of a full DOF vector (any unit).
  Eigen::VectorXd gather_free(const Eigen::VectorXd& full) const;
  /// Writes a free-DOF vector into the free entries of a full vector (constrained entries untouched).
  void scatter_free(const Eigen::VectorXd& free, Eigen::VectorXd& full) const;

 private:
  std::vector<int> equation_;  ///< free: equation >= 0; constrained: -(constrained index) - 1
  std::vector<int> free_dofs_;
  std::vector<int> constrained_dofs_;
};

}  // namespace cushion::solver
