#pragma once
/// Rigid indenter surfaces as signed gap functions of a point in the indenter's own frame.
///
/// Every surface describes a rigid BODY by a smooth signed gap g(x) [mm]: g > 0 outside the body
/// (the foam side), g < 0 inside (penetration), g = 0 on its surface. For the analytic shapes g is
/// the exact signed distance (|grad g| = 1); the SIT-BAR blends distances with a soft minimum, so
/// |grad g| <= 1 in the blend zone. Contact uses g, grad g and the Hessian of g, which gives the
/// exact (consistent) linearisation of the contact force for curved surfaces. The indenter moves
/// by a rigid translation c(t): the gap of a current point x is g(x - c(t)).
#include <memory>
#include <string>
#include <vector>

#include "material/tensor.hpp"
#include "mesh/stl.hpp"
#include "solver/case/contact_spec.hpp"

namespace cushion::solver {

/// Signed gap and its first and second derivatives at one point (indenter frame, current config).
struct GapPoint {
  double g = 0.0;             ///< signed gap [mm] (> 0 open, < 0 penetration)
  Vec3 grad = Vec3::UnitZ();  ///< d g / d x [-], the outward normal for a signed distance
  Mat3 hess = Mat3::Zero();   ///< d^2 g / dx dx [1/mm] (symmetric)
};

/// A rigid body bounded by a smooth surface (const, thread-safe).
class RigidSurface {
 public:
  virtual ~RigidSurface() = default;
  /// Gap at point x [mm] in the indenter's frame.
  virtual GapPoint gap(const Vec3& x) const = 0;
  /// One line, e.g. "sphere R = 50 mm at (0, 0, 130) mm".
  virtual std::string describe() const = 0;
};

/// Half-space behind a plane: the body is {x : n.(x - p) < 0}; n = outward unit normal.
std::shared_ptr<const RigidSurface> make_plane(const Vec3& point, const Vec3& normal);

/// Solid sphere, centre [mm], radius R [mm].
std::shared_ptr<const RigidSurface> make_sphere(const Vec3& centre, double radius);

/// Solid infinite circular cylinder: axis through `point` along `axis`, radius R [mm].
std::shared_ptr<const RigidSurface> make_cylinder(const Vec3& point, const Vec3& axis, double radius);

/// Flat circular punch (ISO 2439 indenter foot): a solid vertical cylinder of radius R [mm] whose
/// flat bottom face is at z = bottom [mm], centre (cx, cy), the bottom edge rounded with radius
/// r_edge [mm] (0 < r_edge <= R), extending to z = +infinity.
std::shared_ptr<const RigidSurface> make_flat_punch(double cx, double cy, double bottom, double radius,
                                                    double r_edge);

/// SIT-BAR surrogate (SitBarShape, solver/case/contact_spec.hpp): two ellipsoidal lobes centred at
/// (centre_x -+ it_spacing/2, centre_y, lowest_z + c) merged with a flat rectangular plate whose
/// underside is at z = lowest_z + c (the lobes' equator), footprint plate_x x plate_y, all merged by
/// a smooth (C1) soft minimum of width `blend`.
std::shared_ptr<const RigidSurface> make_sitbar(const SitBarShape& shape);

/// Rigid body bounded by a closed, consistently oriented triangle surface (outward normals).
/// Signed distance to the nearest triangle (uniform bucket grid), sign from the angle-weighted
/// pseudonormal of the nearest feature. Throws cushion::InputError (via mesh::check_closed) if the
/// surface is not closed; `where` names it in messages.
std::shared_ptr<const RigidSurface> make_stl_surface(const mesh::TriangleSurface& surface, const std::string& where);

/// Rigid surface of an open triangle set whose normals (right-hand rule) point towards the foam: the
/// element faces of a deck's rigid-body master surface. Signed distance as make_stl_surface, without
/// the closed check (the sign comes from the pseudonormals of the nearest feature, so points near the
/// surface, on either side, get the right sign). Throws InputError if the set is empty.
std::shared_ptr<const RigidSurface> make_facet_surface(const mesh::TriangleSurface& surface, const std::string& where);

/// An axis-aligned plane x[axis] = offset [mm] (axis 0, 1, 2: x, y, z).
struct AxisPlane {
  int axis = 0;
  double offset = 0.0;  ///< [mm]
};
/// "x = 0 mm".
std::string to_string(const AxisPlane& plane);

/// Indices of the triangles whose three vertices lie within `tolerance` [mm] of `plane`.
std::vector<int> facets_in_plane(const mesh::TriangleSurface& surface, const AxisPlane& plane, double tolerance);

/// make_stl_surface for a model cut by symmetry planes: after the closed check, the triangles lying in
/// one of `symmetry_planes` (within `tolerance` [mm]) are removed and their number is returned in
/// `dropped`. Such triangles close the cut body on a symmetry plane, where the mirrored body continues
/// it; kept, they are a wall that the foam nodes on the plane touch with gap 0 however deep they are
/// pressed. The signed distance to the remaining (open) surface keeps its sign from the pseudonormals
/// of the nearest feature. Throws InputError if no triangle is left.
std::shared_ptr<const RigidSurface> make_stl_surface(const mesh::TriangleSurface& surface, const std::string& where,
                                                     const std::vector<AxisPlane>& symmetry_planes, double tolerance,
                                                     int& dropped);

/// Soft minimum of two gap functions of width k [mm] (quadratic, C1): equal to min(a, b) where
/// |a.g - b.g| >= k, smooth in between; derivatives by the chain rule.
GapPoint soft_min(const GapPoint& a, const GapPoint& b, double k);

}  // namespace cushion::solver
