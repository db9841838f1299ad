#include "material/material.hpp"

#include <algorithm>

namespace cushion::material {

void Material::initial_state(std::span<double> state) const { std::fill(state.begin(), state.end(), 0.0); }

}  // namespace cushion::material
