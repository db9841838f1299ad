#pragma once
/// STL triangulated surfaces (ASCII or binary; coordinates taken as mm) with coincident vertices
/// merged, and a closedness/manifold check for use as a TetGen boundary.
#include <array>
#include <string>
#include <vector>

#include "mesh/mesh.hpp"

namespace cushion::mesh {

struct TriangleSurface {
  std::vector<Vec3> vertices;                ///< [mm]
  std::vector<std::array<int, 3>> triangles;  ///< 0-based vertex indices
};

/// Reads an ASCII or binary STL file (binary detected by its size 84 + 50 n); vertices closer than
/// 1e-9 x the bounding-box diagonal are merged. Throws cushion::InputError naming the file (and
/// line for ASCII) on malformed input.
TriangleSurface read_stl(const std::string& path);

/// Writes an ASCII (binary = false) or binary STL with facet normals from the right-hand rule.
void write_stl(const TriangleSurface& surface, const std::string& path, bool binary = false);

/// Throws cushion::InputError "<where>: surface not closed: N open edge(s) ..." listing up to five
/// edges (vertex coordinates) not shared by exactly two triangles, or edges whose two triangles
/// have inconsistent orientation, or degenerate (zero-area) triangles.
void check_closed(const TriangleSurface& surface, const std::string& where);

/// Signed volume enclosed by a closed surface, positive for outward normals [mm^3].
double enclosed_volume(const TriangleSurface& surface);

}  // namespace cushion::mesh
