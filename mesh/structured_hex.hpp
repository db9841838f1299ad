#pragma once
/// Structured block generator: a box [x0,x1] x [y0,y1] x [z0,z1] mm cut into nx x ny x nz hexahedra
/// (C3D8) or 6 tetrahedra (C3D4) per hexahedron, with optional grading along each axis.
#include <array>

#include "mesh/mesh.hpp"

namespace cushion::mesh {

/// Element-size distribution along one axis. All ratios are size ratios of elements [-].
struct AxisGrading {
  enum class Kind {
    uniform,    ///< equal element sizes
    geometric,  ///< sizes grow geometrically from the low end: h_last / h_first = ratio
    focus       ///< finest at coordinate `focus` [mm], growing geometrically away from it on each
                ///< side: h_coarsest / h_finest = ratio within each side (focus may be an end)
  };
  Kind kind = Kind::uniform;
  double ratio = 1.0;  ///< > 0; for `geometric` < 1 means finer at the high end
  double focus = 0.0;  ///< [mm], only for Kind::focus; must lie in [low, high] of the axis
};

/// A box block. Node sets and surfaces "xmin", "xmax", "ymin", "ymax", "zmin", "zmax" and the
/// element set "all" are created; node labels and element labels start at 1.
struct BlockSpec {
  Vec3 low = Vec3::Zero();    ///< (x0, y0, z0) [mm]
  Vec3 high = Vec3::Ones();   ///< (x1, y1, z1) [mm]
  std::array<int, 3> n{1, 1, 1};  ///< elements per axis (nx, ny, nz) >= 1
  std::array<AxisGrading, 3> grading{};
  ElementType type = ElementType::hex8;  ///< hex8 or tet4 (tet10: call to_tet10 on the result)
};

/// Node coordinates along one axis (n + 1 values from low to high) [mm]; throws
/// cushion::InputError for invalid grading (non-positive ratio, focus outside the axis).
std::vector<double> graded_coordinates(double low, double high, int n, const AxisGrading& grading);

/// Builds the block mesh; throws cushion::InputError for an empty box or n < 1.
Mesh structured_block(const BlockSpec& spec);

}  // namespace cushion::mesh
