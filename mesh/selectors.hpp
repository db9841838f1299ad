#pragma once
/// Geometric node selectors (reference coordinates, mm) and node-set -> surface conversion.
/// Selectors are plain structs (filled by a case-file parser) or parsed from compact text:
///   "z == 0", "x <= 1e-6", "y > 5 tol 0.01", "box(x0,y0,z0, x1,y1,z1)",
///   "sphere(cx,cy,cz, r)", "cylinder(px,py,pz, dx,dy,dz, r)", "all".
#include <string>
#include <variant>
#include <vector>

#include "mesh/mesh.hpp"

namespace cushion::mesh {

enum class Comparison { equal, less_equal, greater_equal, less, greater };

/// Tolerances below 0 mean "automatic": 1e-6 x the diagonal of the mesh bounding box [mm].
constexpr double kAutoTolerance = -1.0;

/// Nodes with coordinate[axis] (op) value, within tol [mm]: == means |x - value| <= tol,
/// <= means x <= value + tol, < means x < value - tol (and symmetrically for >=, >).
struct PlaneSelector {
  int axis = 2;  ///< 0 = x, 1 = y, 2 = z
  Comparison op = Comparison::equal;
  double value = 0.0;  ///< [mm]
  double tol = kAutoTolerance;  ///< [mm]
};
/// Nodes inside the axis-aligned box [low, high] enlarged by tol [mm].
struct BoxSelector {
  Vec3 low = Vec3::Zero(), high = Vec3::Zero();
  double tol = kAutoTolerance;
};
/// Nodes with |X - centre| <= radius + tol [mm].
struct SphereSelector {
  Vec3 centre = Vec3::Zero();
  double radius = 0.0;
  double tol = kAutoTolerance;
};
/// Nodes within radius + tol [mm] of the infinite line through `point` along `direction`.
struct CylinderSelector {
  Vec3 point = Vec3::Zero(), direction = Vec3::UnitZ();
  double radius = 0.0;
  double tol = kAutoTolerance;
};
/// Every node.
struct AllSelector {};

using Selector =
    std::variant<PlaneSelector, BoxSelector, SphereSelector, CylinderSelector, AllSelector>;

/// Parses the compact text form; throws cushion::InputError "<where>: selector '<text>': ..."
/// naming the bad token.
Selector parse_selector(const std::string& text, const std::string& where = "selector");

/// Checks a selector built from plain fields (axis range, radius >= 0, low <= high, direction != 0);
/// throws cushion::InputError prefixed by `where`.
void validate(const Selector& selector, const std::string& where = "selector");

/// Sorted indices of the nodes selected (validates first).
std::vector<int> select_nodes(const Mesh& mesh, const Selector& selector);

/// Exterior faces (see boundary_faces) whose corner nodes all belong to `nodes` (any order).
std::vector<Face> surface_from_node_set(const Mesh& mesh, const std::vector<int>& nodes);

}  // namespace cushion::mesh
