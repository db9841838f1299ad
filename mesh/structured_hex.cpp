#include "mesh/structured_hex.hpp"

#include <algorithm>
#include <cmath>

#include "io/input_error.hpp"
#include "mesh/selectors.hpp"

namespace cushion::mesh {
namespace {

// n + 1 coordinates from a to b (a may exceed b) with sizes h_i = h_0 q^i, h_{n-1} / h_0 = ratio.
std::vector<double> geometric_segment(double a, double b, int n, double ratio) {
  std::vector<double> x(n + 1);
  const double q = n > 1 ? std::pow(ratio, 1.0 / (n - 1)) : 1.0;
  double total = 0.0, h = 1.0;
  for (int i = 0; i < n; ++i, h *= q) total += h;
  x[0] = a;
  h = 1.0;
  double sum = 0.0;
  for (int i = 1; i < n; ++i, h *= q) {
    sum += h;
    x[i] = a + (b - a) * sum / total;
  }
  x[n] = b;
  return x;
}

const char* axis_name(int axis) { return axis == 0 ? "x" : axis == 1 ? "y" : "z"; }

}  // namespace

std::vector<double> graded_coordinates(double low, double high, int n, const AxisGrading& g) {
  if (n < 1) throw InputError("structured block: number of elements must be >= 1");
  if (!(high > low)) throw InputError("structured block: high must exceed low");
  if (!(g.ratio > 0.0) || !std::isfinite(g.ratio))
    throw InputError("structured block: grading ratio must be positive");
  switch (g.kind) {
    case AxisGrading::Kind::uniform:
      return geometric_segment(low, high, n, 1.0);
    case AxisGrading::Kind::geometric:
      return geometric_segment(low, high, n, g.ratio);
    case AxisGrading::Kind::focus: {
      if (g.focus < low || g.focus > high)
        throw InputError("structured block: grading focus " + std::to_string(g.focus) +
                         " mm outside [" + std::to_string(low) + ", " + std::to_string(high) + "]");
      // Elements shared between the two sides in proportion to their lengths (>= 1 on a non-empty side).
      const double tol = 1e-12 * (high - low);
      const bool has_left = g.focus - low > tol, has_right = high - g.focus > tol;
      if (!has_left) return geometric_segment(low, high, n, g.ratio);
      if (!has_right) {
        std::vector<double> x = geometric_segment(high, low, n, g.ratio);
        std::reverse(x.begin(), x.end());
        return x;
      }
      if (n < 2) throw InputError("structured block: an interior focus needs at least 2 elements");
      int n_left = static_cast<int>(std::lround(n * (g.focus - low) / (high - low)));
      n_left = std::clamp(n_left, 1, n - 1);
      std::vector<double> left = geometric_segment(g.focus, low, n_left, g.ratio);
      const std::vector<double> right = geometric_segment(g.focus, high, n - n_left, g.ratio);
      std::reverse(left.begin(), left.end());
      left.insert(left.end(), right.begin() + 1, right.end());
      return left;
    }
  }
  return {};
}

Mesh structured_block(const BlockSpec& spec) {
  if (spec.type == ElementType::tet10)
    throw InputError("structured block: generate tet4 and call to_tet10 for C3D10");
  std::array<std::vector<double>, 3> axis;
  for (int d = 0; d < 3; ++d) {
    try {
      axis[d] = graded_coordinates(spec.low[d], spec.high[d], spec.n[d], spec.grading[d]);
    } catch (const InputError& error) {
      throw InputError(std::string(error.what()) + " (axis " + axis_name(d) + ")");
    }
  }
  const int nx = spec.n[0], ny = spec.n[1], nz = spec.n[2];
  const auto node = [&](int i, int j, int k) { return i + (nx + 1) * (j + (ny + 1) * k); };

  Mesh mesh;
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        mesh.nodes.emplace_back(axis[0][i], axis[1][j], axis[2][k]);
        mesh.node_labels.push_back(static_cast<int>(mesh.nodes.size()));
      }

  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        // C3D8 corner order: bottom (k) counter-clockwise seen from +z, then top (k+1).
        const std::array<int, 8> c = {node(i, j, k),         node(i + 1, j, k),
                                      node(i + 1, j + 1, k), node(i, j + 1, k),
                                      node(i, j, k + 1),     node(i + 1, j, k + 1),
                                      node(i + 1, j + 1, k + 1), node(i, j + 1, k + 1)};
        if (spec.type == ElementType::hex8) {
          Element element{ElementType::hex8, {}, 0};
          std::copy(c.begin(), c.end(), element.nodes.begin());
          mesh.elements.push_back(element);
          continue;
        }
        // Kuhn split: 6 tets along the diagonal corner 1 -> corner 7, one per axis permutation;
        // every cube face is cut along its diagonal through the low corner, so neighbours conform.
        // Corner of the cube at binary offset (bx, by, bz) in C3D8 order:
        const auto corner = [&](int bx, int by, int bz) {
          static constexpr int kIndex[2][2][2] = {{{0, 4}, {3, 7}}, {{1, 5}, {2, 6}}};
          return c[kIndex[bx][by][bz]];
        };
        static constexpr int kPermutations[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2},
                                                    {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
        for (const auto& p : kPermutations) {
          std::array<int, 3> b{0, 0, 0};
          Element tet{ElementType::tet4, {}, 0};
          tet.nodes[0] = corner(0, 0, 0);
          for (int s = 0; s < 3; ++s) {
            b[p[s]] = 1;
            tet.nodes[s + 1] = corner(b[0], b[1], b[2]);
          }
          // Path x,y,z gives positive orientation; odd permutations are mirrored.
          const bool odd = (p[0] == 0 && p[1] == 2) || (p[0] == 1 && p[1] == 0) ||
                           (p[0] == 2 && p[1] == 1);
          if (odd) std::swap(tet.nodes[1], tet.nodes[2]);
          mesh.elements.push_back(tet);
        }
      }
  for (std::size_t e = 0; e < mesh.elements.size(); ++e) {
    mesh.elements[e].label = static_cast<int>(e) + 1;
    mesh.element_sets["all"].push_back(static_cast<int>(e));
  }

  const double tol = 1e-9 * (spec.high - spec.low).norm();
  const char* names[3][2] = {{"xmin", "xmax"}, {"ymin", "ymax"}, {"zmin", "zmax"}};
  for (int d = 0; d < 3; ++d)
    for (int side = 0; side < 2; ++side) {
      const PlaneSelector plane{d, Comparison::equal, side == 0 ? spec.low[d] : spec.high[d], tol};
      const std::vector<int> nodes = select_nodes(mesh, Selector{plane});
      mesh.node_sets[names[d][side]] = nodes;
      mesh.surfaces[names[d][side]] = surface_from_node_set(mesh, nodes);
    }
  return mesh;
}

}  // namespace cushion::mesh
