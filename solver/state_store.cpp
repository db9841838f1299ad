#include "solver/state_store.hpp"

namespace cushion::solver {

StateStore::StateStore(const std::vector<ElementLayout>& layout) : offset_(layout.size() + 1, 0) {
  for (std::size_t e = 0; e < layout.size(); ++e)
    offset_[e + 1] = offset_[e] + layout[e].num_points * (layout[e].material ? layout[e].material->state_size() : 0);
  old_.assign(offset_.back(), 0.0);
  for (std::size_t e = 0; e < layout.size(); ++e) {
    if (!layout[e].material) continue;
    const std::size_t ns = layout[e].material->state_size();
    for (int q = 0; q < layout[e].num_points; ++q)
      layout[e].material->initial_state(std::span<double>(old_.data() + offset_[e] + q * ns, ns));
  }
  new_ = old_;
}

}  // namespace cushion::solver
