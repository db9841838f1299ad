#include "mesh/tetgen_mesher.hpp"

#include <tetgen.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "io/input_error.hpp"
#include "mesh/quadratic.hpp"
#include "mesh/selectors.hpp"

namespace cushion::mesh {
namespace {

// Fills a TetGen piecewise linear complex from points and polygonal facets (owned by `in`).
void set_plc(tetgenio& in, const std::vector<Vec3>& points,
             const std::vector<std::vector<int>>& facets) {
  in.firstnumber = 0;
  in.numberofpoints = static_cast<int>(points.size());
  in.pointlist = new REAL[3 * points.size()];
  for (std::size_t i = 0; i < points.size(); ++i)
    for (int d = 0; d < 3; ++d) in.pointlist[3 * i + d] = points[i][d];
  in.numberoffacets = static_cast<int>(facets.size());
  in.facetlist = new tetgenio::facet[facets.size()];
  for (std::size_t f = 0; f < facets.size(); ++f) {
    tetgenio::facet& facet = in.facetlist[f];
    tetgenio::init(&facet);
    facet.numberofpolygons = 1;
    facet.polygonlist = new tetgenio::polygon[1];
    tetgenio::polygon& polygon = facet.polygonlist[0];
    tetgenio::init(&polygon);
    polygon.numberofvertices = static_cast<int>(facets[f].size());
    polygon.vertexlist = new int[facets[f].size()];
    for (std::size_t k = 0; k < facets[f].size(); ++k) polygon.vertexlist[k] = facets[f][k];
  }
}

// Runs TetGen and converts its output to a C3D4 (or C3D10) mesh with positive orientation.
Mesh run_tetgen(tetgenio& in, const TetgenOptions& options) {
  std::string switches = tetgen_switches(options);
  tetgenio out;
  try {
    tetrahedralize(switches.data(), &in, &out);
  } catch (int code) {
    throw std::runtime_error("TetGen failed (error code " + std::to_string(code) +
                             ") with switches '" + switches + "'");
  }
  if (out.numberoftetrahedra == 0) throw std::runtime_error("TetGen produced no tetrahedra");
  Mesh mesh;
  for (int i = 0; i < out.numberofpoints; ++i) {
    mesh.nodes.emplace_back(out.pointlist[3 * i], out.pointlist[3 * i + 1], out.pointlist[3 * i + 2]);
    mesh.node_labels.push_back(i + 1);
  }
  for (int t = 0; t < out.numberoftetrahedra; ++t) {
    Element tet{ElementType::tet4, {}, t + 1};
    for (int k = 0; k < 4; ++k) tet.nodes[k] = out.tetrahedronlist[out.numberofcorners * t + k] - out.firstnumber;
    const Vec3& x0 = mesh.nodes[tet.nodes[0]];
    const double six_v = (mesh.nodes[tet.nodes[1]] - x0)
                             .cross(mesh.nodes[tet.nodes[2]] - x0)
                             .dot(mesh.nodes[tet.nodes[3]] - x0);
    if (six_v < 0) std::swap(tet.nodes[1], tet.nodes[2]);
    mesh.elements.push_back(tet);
    mesh.element_sets["all"].push_back(t);
  }
  return mesh;
}

void check_options(const TetgenOptions& options) {
  if (!std::isfinite(options.max_radius_edge) || !std::isfinite(options.min_dihedral) ||
      !std::isfinite(options.max_volume))
    throw InputError("tetgen: options must be finite");
  if (options.max_radius_edge > 0 && options.max_radius_edge < 1.0)
    throw InputError("tetgen: max_radius_edge must be >= 1 (TetGen does not terminate below ~1.1)");
  if (options.min_dihedral < 0 || options.min_dihedral > 30)
    throw InputError("tetgen: min_dihedral must lie in [0, 30] deg");
}

}  // namespace

std::string tetgen_switches(const TetgenOptions& options) {
  std::ostringstream s;
  s.precision(10);
  s << "p";
  if (options.max_radius_edge > 0) s << "q" << options.max_radius_edge << "/" << options.min_dihedral;
  if (options.max_volume > 0) s << "a" << options.max_volume;
  if (!options.optimise) s << "O0";
  if (!options.verbose) s << "Q";
  return s.str();
}

Mesh tetgen_box(const Vec3& low, const Vec3& high, const TetgenOptions& options) {
  check_options(options);
  if (!(high.array() > low.array()).all()) throw InputError("tetgen box: high must exceed low");
  std::vector<Vec3> corners;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i)
        corners.emplace_back(i ? high.x() : low.x(), j ? high.y() : low.y(), k ? high.z() : low.z());
  // Corner index i + 2 j + 4 k; the six sides as quadrilateral facets.
  const std::vector<std::vector<int>> sides = {{0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                               {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 5, 7, 6}};
  tetgenio in;
  set_plc(in, corners, sides);
  Mesh mesh = run_tetgen(in, options);
  if (options.quadratic) mesh = to_tet10(mesh);
  const double tol = 1e-9 * (high - low).norm();
  const char* names[3][2] = {{"xmin", "xmax"}, {"ymin", "ymax"}, {"zmin", "zmax"}};
  for (int d = 0; d < 3; ++d)
    for (int side = 0; side < 2; ++side) {
      const PlaneSelector plane{d, Comparison::equal, side == 0 ? low[d] : high[d], tol};
      const std::vector<int> nodes = select_nodes(mesh, Selector{plane});
      mesh.node_sets[names[d][side]] = nodes;
      mesh.surfaces[names[d][side]] = surface_from_node_set(mesh, nodes);
    }
  return mesh;
}

Mesh tetgen_surface(const TriangleSurface& surface, const TetgenOptions& options,
                    const std::string& where) {
  check_options(options);
  check_closed(surface, where);
  std::vector<std::vector<int>> facets;
  for (const auto& t : surface.triangles) facets.push_back({t[0], t[1], t[2]});
  tetgenio in;
  set_plc(in, surface.vertices, facets);
  Mesh mesh = run_tetgen(in, options);
  if (options.quadratic) mesh = to_tet10(mesh);
  std::vector<Face> exterior = boundary_faces(mesh);
  std::vector<int> nodes;
  for (const Face& face : exterior) {
    const Element& element = mesh.elements[face.element];
    for (int local : face_nodes(element.type, face.face)) nodes.push_back(element.nodes[local]);
  }
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  mesh.node_sets["boundary"] = nodes;
  mesh.surfaces["boundary"] = exterior;
  return mesh;
}

double max_radius_edge_ratio(const Mesh& mesh) {
  double worst = 0.0;
  for (const Element& element : mesh.elements) {
    if (is_hexahedron(element.type)) continue;
    const Vec3& x0 = mesh.nodes[element.nodes[0]];
    const Vec3 a = mesh.nodes[element.nodes[1]] - x0, b = mesh.nodes[element.nodes[2]] - x0,
               c = mesh.nodes[element.nodes[3]] - x0;
    // Circumcentre relative to x0: (|a|^2 b x c + |b|^2 c x a + |c|^2 a x b) / (2 a . (b x c)).
    const Vec3 centre =
        (a.squaredNorm() * b.cross(c) + b.squaredNorm() * c.cross(a) + c.squaredNorm() * a.cross(b)) /
        (2.0 * a.dot(b.cross(c)));
    const double shortest = std::min({a.norm(), b.norm(), c.norm(), (b - a).norm(), (c - a).norm(),
                                      (c - b).norm()});
    worst = std::max(worst, centre.norm() / shortest);
  }
  return worst;
}

}  // namespace cushion::mesh
