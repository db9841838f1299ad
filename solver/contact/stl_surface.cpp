// Rigid body from a closed triangle surface: signed distance to the nearest triangle, found with
// an axis-aligned bounding-box tree; the sign comes from the angle-weighted pseudonormal of the
// nearest feature (face, edge or vertex), which is exact for closed oriented surfaces
// (Baerentzen & Aanaes 2005). Hessian of the distance: 0 on a face, (P_edge - u u^T)/g at an
// edge, (I - u u^T)/g at a vertex.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>

#include "io/input_error.hpp"
#include "solver/contact/rigid_surface.hpp"

namespace cushion::solver {

namespace {

/// Nearest point on triangle (a, b, c) to x, and the feature it lies on: 0 face, 1..3 vertex
/// a, b, c, 4..6 edge ab, bc, ca (Ericson, Real-Time Collision Detection, 5.1.5).
Vec3 closest_on_triangle(const Vec3& x, const Vec3& a, const Vec3& b, const Vec3& c, int& feature) {
  const Vec3 ab = b - a, ac = c - a, ap = x - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return feature = 1, a;
  const Vec3 bp = x - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return feature = 2, b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return feature = 4, Vec3(a + d1 / (d1 - d3) * ab);
  const Vec3 cp = x - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return feature = 3, c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return feature = 6, Vec3(a + d2 / (d2 - d6) * ac);
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return feature = 5, Vec3(b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b));
  const double denom = 1.0 / (va + vb + vc);
  feature = 0;
  return a + ab * (vb * denom) + ac * (vc * denom);
}

struct Box {
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  void add(const Vec3& p) { lo = lo.cwiseMin(p), hi = hi.cwiseMax(p); }
  double distance2(const Vec3& x) const {
    const Vec3 d = (lo - x).cwiseMax(x - hi).cwiseMax(0.0);
    return d.squaredNorm();
  }
};

class StlSurface final : public RigidSurface {
 public:
  /// `dropped`: triangles of the closed surface removed on symmetry planes (for describe()).
  StlSurface(const mesh::TriangleSurface& s, std::string where, int dropped = 0, bool closed = true)
      : s_(s), where_(std::move(where)), dropped_(dropped), closed_(closed) {
    const std::size_t nt = s_.triangles.size();
    face_normal_.resize(nt);
    vertex_normal_.assign(s_.vertices.size(), Vec3::Zero());
    std::map<std::pair<int, int>, Vec3> edge_sum;
    for (std::size_t t = 0; t < nt; ++t) {
      const auto& tri = s_.triangles[t];
      const Vec3 n = (P(tri[1]) - P(tri[0])).cross(P(tri[2]) - P(tri[0])).normalized();
      face_normal_[t] = n;
      for (int k = 0; k < 3; ++k) {
        const Vec3 e1 = (P(tri[(k + 1) % 3]) - P(tri[k])).normalized();
        const Vec3 e2 = (P(tri[(k + 2) % 3]) - P(tri[k])).normalized();
        vertex_normal_[tri[k]] += std::acos(std::clamp(e1.dot(e2), -1.0, 1.0)) * n;  // angle-weighted
        const int i = tri[k], j = tri[(k + 1) % 3];
        const auto [it, fresh] = edge_sum.try_emplace({std::min(i, j), std::max(i, j)}, Vec3::Zero());
        it->second += n;
      }
    }
    edge_normal_.resize(nt);
    for (std::size_t t = 0; t < nt; ++t)
      for (int k = 0; k < 3; ++k) {
        const int i = s_.triangles[t][k], j = s_.triangles[t][(k + 1) % 3];
        edge_normal_[t][k] = edge_sum[{std::min(i, j), std::max(i, j)}];
      }
    order_.resize(nt);
    std::iota(order_.begin(), order_.end(), 0);
    build(0, static_cast<int>(nt));
  }

  GapPoint gap(const Vec3& x) const override {
    double best = INFINITY;
    int best_t = -1, best_f = 0;
    Vec3 best_p;
    nearest(0, x, best, best_t, best_f, best_p);
    const auto& tri = s_.triangles[best_t];
    Vec3 pseudo;  // angle-weighted pseudonormal of the nearest feature
    if (best_f == 0) pseudo = face_normal_[best_t];
    else if (best_f <= 3) pseudo = vertex_normal_[tri[best_f - 1]];
    else pseudo = edge_normal_[best_t][best_f - 4];
    const Vec3 d = x - best_p;
    const double dist = d.norm();
    GapPoint out;
    const double sign = d.dot(pseudo) >= 0.0 ? 1.0 : -1.0;
    if (best_f == 0 || dist < 1e-12) {
      out.g = best_f == 0 ? face_normal_[best_t].dot(d) : 0.0;
      out.grad = pseudo.normalized();
      return out;
    }
    out.g = sign * dist;
    const Vec3 u = sign * d / dist;
    out.grad = u;
    Mat3 P_feature = Mat3::Identity();
    if (best_f >= 4) {
      const int k = best_f - 4;
      const Vec3 e = (P(tri[(k + 1) % 3]) - P(tri[k])).normalized();
      P_feature -= e * e.transpose();
    }
    out.hess = (P_feature - u * u.transpose()) / out.g;
    return out;
  }

  std::string describe() const override {
    return (closed_ ? "closed STL surface " : "rigid facets of ") + where_ + " (" + std::to_string(s_.triangles.size()) + " triangles" +
           (dropped_ ? "; " + std::to_string(dropped_) + " more in symmetry planes dropped" : "") + ")";
  }

 private:
  struct Node {
    Box box;
    int begin = 0, end = 0, left = -1, right = -1;
  };
  const Vec3& P(int v) const { return s_.vertices[v]; }

  int build(int begin, int end) {
    const int id = static_cast<int>(nodes_.size());
    nodes_.push_back({});
    Box box, centres;
    for (int i = begin; i < end; ++i) {
      const auto& tri = s_.triangles[order_[i]];
      Vec3 c = Vec3::Zero();
      for (int v : tri) box.add(P(v)), c += P(v) / 3.0;
      centres.add(c);
    }
    nodes_[id].box = box;
    nodes_[id].begin = begin, nodes_[id].end = end;
    if (end - begin <= 8) return id;
    int axis;
    (centres.hi - centres.lo).maxCoeff(&axis);
    const int mid = (begin + end) / 2;
    auto centre = [&](int t) {
      const auto& tri = s_.triangles[t];
      return P(tri[0])(axis) + P(tri[1])(axis) + P(tri[2])(axis);
    };
    std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                     [&](int a, int b) { return centre(a) < centre(b); });
    const int left = build(begin, mid), right = build(mid, end);
    nodes_[id].left = left, nodes_[id].right = right;
    return id;
  }

  void nearest(int id, const Vec3& x, double& best, int& best_t, int& best_f, Vec3& best_p) const {
    const Node& node = nodes_[id];
    if (node.box.distance2(x) >= best) return;
    if (node.left < 0) {
      for (int i = node.begin; i < node.end; ++i) {
        const auto& tri = s_.triangles[order_[i]];
        int f;
        const Vec3 p = closest_on_triangle(x, P(tri[0]), P(tri[1]), P(tri[2]), f);
        const double d2 = (x - p).squaredNorm();
        if (d2 < best) best = d2, best_t = order_[i], best_f = f, best_p = p;
      }
      return;
    }
    const double dl = nodes_[node.left].box.distance2(x), dr = nodes_[node.right].box.distance2(x);
    if (dl <= dr) {
      nearest(node.left, x, best, best_t, best_f, best_p);
      nearest(node.right, x, best, best_t, best_f, best_p);
    } else {
      nearest(node.right, x, best, best_t, best_f, best_p);
      nearest(node.left, x, best, best_t, best_f, best_p);
    }
  }

  mesh::TriangleSurface s_;
  std::string where_;
  int dropped_ = 0;
  bool closed_ = true;
  std::vector<Vec3> face_normal_, vertex_normal_;
  std::vector<std::array<Vec3, 3>> edge_normal_;  ///< per triangle, edge k = (k, k+1)
  std::vector<int> order_;
  std::vector<Node> nodes_;
};

}  // namespace

std::shared_ptr<const RigidSurface> make_stl_surface(const mesh::TriangleSurface& surface, const std::string& where) {
  mesh::check_closed(surface, where);
  return std::make_shared<StlSurface>(surface, where);
}

std::shared_ptr<const RigidSurface> make_facet_surface(const mesh::TriangleSurface& surface, const std::string& where) {
  if (surface.triangles.empty()) throw InputError(where + ": the surface has no facets");
  return std::make_shared<StlSurface>(surface, where, 0, false);
}

std::string to_string(const AxisPlane& plane) {
  char text[64];
  std::snprintf(text, sizeof text, "%c = %g mm", "xyz"[plane.axis], plane.offset);
  return text;
}

std::vector<int> facets_in_plane(const mesh::TriangleSurface& surface, const AxisPlane& plane, double tolerance) {
  std::vector<int> out;
  for (std::size_t t = 0; t < surface.triangles.size(); ++t) {
    const auto& tri = surface.triangles[t];
    if (std::all_of(tri.begin(), tri.end(), [&](int v) {
          return std::abs(surface.vertices[v][plane.axis] - plane.offset) <= tolerance;
        }))
      out.push_back(static_cast<int>(t));
  }
  return out;
}

std::shared_ptr<const RigidSurface> make_stl_surface(const mesh::TriangleSurface& surface, const std::string& where,
                                                     const std::vector<AxisPlane>& symmetry_planes, double tolerance,
                                                     int& dropped) {
  mesh::check_closed(surface, where);
  std::vector<char> drop(surface.triangles.size(), 0);
  for (const AxisPlane& plane : symmetry_planes)
    for (int t : facets_in_plane(surface, plane, tolerance)) drop[t] = 1;
  mesh::TriangleSurface kept{surface.vertices, {}};
  for (std::size_t t = 0; t < surface.triangles.size(); ++t)
    if (!drop[t]) kept.triangles.push_back(surface.triangles[t]);
  dropped = static_cast<int>(surface.triangles.size() - kept.triangles.size());
  if (kept.triangles.empty())
    throw InputError(where + ": every triangle lies in a symmetry plane of the model; no contact surface is left");
  return std::make_shared<StlSurface>(kept, where, dropped);
}

}  // namespace cushion::solver
