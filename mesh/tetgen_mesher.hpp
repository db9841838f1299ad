#pragma once
/// Unstructured tetrahedral meshes by TetGen 1.5 (library API): a box or the inside of a closed
/// triangulated surface (e.g. an STL), with quality and size controls.
#include "mesh/mesh.hpp"
#include "mesh/stl.hpp"

namespace cushion::mesh {

struct TetgenOptions {
  double max_radius_edge = 1.5;  ///< circumradius / shortest edge bound (TetGen -q); <= 0: no
                                 ///< quality refinement [-]
  double min_dihedral = 0.0;     ///< minimum dihedral angle target (TetGen -q.../angle) [deg]
  double max_volume = -1.0;      ///< maximum tetrahedron volume (TetGen -a), <= 0: none [mm^3]
  bool optimise = false;         ///< TetGen's final mesh optimisation (-O, flips and smoothing):
                                 ///< better dihedral angles, but the volume and radius-edge bounds
                                 ///< may then be exceeded (seen: +27 % volume); off = "O0", bounds hold
  bool quadratic = false;        ///< C3D10 (mid-edge nodes added, see to_tet10) instead of C3D4
  bool verbose = false;          ///< let TetGen print to the console (default: "Q", quiet)
};

/// The TetGen switch string used for `options` (e.g. "pq1.5/0a2O0Q").
std::string tetgen_switches(const TetgenOptions& options);

/// Tetrahedral mesh of the box [low, high] [mm]; node sets and surfaces xmin ... zmax as for
/// structured_block, element set "all". Throws cushion::InputError for an empty box or bad options,
/// std::runtime_error if TetGen fails.
Mesh tetgen_box(const Vec3& low, const Vec3& high, const TetgenOptions& options);

/// Tetrahedral mesh of the volume enclosed by a closed surface [mm]; the surface is checked by
/// check_closed (message prefixed by `where`). Node set and surface "boundary" hold the exterior,
/// element set "all".
Mesh tetgen_surface(const TriangleSurface& surface, const TetgenOptions& options,
                    const std::string& where = "surface");

/// Largest circumradius / shortest-edge ratio over the tets of `mesh` [-] (quality measure).
double max_radius_edge_ratio(const Mesh& mesh);

}  // namespace cushion::mesh
