#include "material/material.hpp"

#include <algorithm>

namespace cushion::material {

void Material::initial_state(std::span<double> state) const { std::fill(state.begin(), state.end(), 0.0); }

Vec6 Material::viscous_stress(const Mat3& /*F*/, std::span<const double> /*state*/) const { return Vec6::Zero(); }

}  // namespace cushion::material
