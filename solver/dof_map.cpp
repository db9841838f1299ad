#include "solver/dof_map.hpp"

#include <stdexcept>

namespace cushion::solver {

DofMap::DofMap(std::size_t num_nodes, const std::vector<bool>& constrained) : equation_(3 * num_nodes, 0) {
  if (!constrained.empty() && constrained.size() != 3 * num_nodes)
    throw std::invalid_argument("DofMap: constrained mask must have 3 entries per node");
  for (std::size_t d = 0; d < equation_.size(); ++d) {
    if (!constrained.empty() && constrained[d]) {
      equation_[d] = -static_cast<int>(constrained_dofs_.size()) - 1;
      constrained_dofs_.push_back(static_cast<int>(d));
    } else {
      equation_[d] = static_cast<int>(free_dofs_.size());
      free_dofs_.push_back(static_cast<int>(d));
    }
  }
}

Eigen::VectorXd DofMap::gather_free(const Eigen::VectorXd& full) const {
  Eigen::VectorXd free(free_dofs_.size());
  for (std::size_t e = 0; e < free_dofs_.size(); ++e) free(e) = full(free_dofs_[e]);
  return free;
}

void DofMap::scatter_free(const Eigen::VectorXd& free, Eigen::VectorXd& full) const {
  for (std::size_t e = 0; e < free_dofs_.size(); ++e) full(free_dofs_[e]) = free(e);
}

}  // namespace cushion::solver
