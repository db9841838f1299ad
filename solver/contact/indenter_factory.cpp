#include "solver/contact/indenter_factory.hpp"

#include "io/input_error.hpp"
#include "mesh/stl.hpp"

namespace cushion::solver {

namespace {

std::string plane_list(const std::vector<AxisPlane>& planes) {
  std::string out;
  for (const AxisPlane& p : planes) out += (out.empty() ? "" : ", ") + to_string(p);
  return out;
}

// The STL indenter with its triangles on symmetry planes dropped; warnings about them and about
// triangles on other held planes go to `notes`.
std::shared_ptr<const RigidSurface> stl_indenter(const IndenterSpec& s, const std::string& where,
                                                 const HeldPlanes& planes, std::vector<std::string>* notes) {
  const std::string name = s.stl_file.string();
  const mesh::TriangleSurface surface = mesh::read_stl(name);
  int dropped = 0;
  auto out = make_stl_surface(surface, name + " (" + where + ")", planes.symmetry, planes.tolerance, dropped);
  if (!notes) return out;
  if (dropped > 0)
    notes->push_back(where + ": " + std::to_string(dropped) + " of " + std::to_string(surface.triangles.size()) +
                     " triangles of " + name + " lie in the symmetry planes " + plane_list(planes.symmetry) +
                     " and were dropped: they close the cut indenter where its mirror image continues it, so "
                     "they are no contact surface (foam nodes on the plane would touch them)");
  for (const AxisPlane& plane : planes.held) {
    const std::size_t n = facets_in_plane(surface, plane, planes.tolerance).size();
    if (n > 0)
      notes->push_back(where + ": " + std::to_string(n) + " triangles of " + name + " lie in the plane " +
                       to_string(plane) + " where nodes are held; foam nodes on that plane can touch them (if it is "
                       "a symmetry plane, hold it with a symmetry condition: its triangles are then dropped)");
  }
  return out;
}

}  // namespace

std::shared_ptr<const RigidSurface> make_indenter(const IndenterSpec& s, const std::string& where,
                                                  const HeldPlanes& planes, std::vector<std::string>* notes) {
  switch (s.type) {
    case IndenterSpec::Type::plane: return make_plane(s.point, s.direction);
    case IndenterSpec::Type::sphere: return make_sphere(s.point, s.radius);
    case IndenterSpec::Type::cylinder: return make_cylinder(s.point, s.direction, s.radius);
    case IndenterSpec::Type::flat_punch:
      return make_flat_punch(s.point.x(), s.point.y(), s.point.z(), s.radius, s.edge_radius);
    case IndenterSpec::Type::sitbar: return make_sitbar(s.sitbar);
    case IndenterSpec::Type::stl: return stl_indenter(s, where, planes, notes);
    case IndenterSpec::Type::facets:
      if (!s.facets) throw InputError(where + ": rigid surface without facets");
      return make_facet_surface(*s.facets, s.facets_name + " (" + where + ")");
  }
  throw InputError(where + ": unknown indenter type");
}

}  // namespace cushion::solver
