#include "solver/contact/indenter_factory.hpp"

#include "io/input_error.hpp"
#include "mesh/stl.hpp"

namespace cushion::solver {

std::shared_ptr<const RigidSurface> make_indenter(const IndenterSpec& s, const std::string& where) {
  switch (s.type) {
    case IndenterSpec::Type::plane: return make_plane(s.point, s.direction);
    case IndenterSpec::Type::sphere: return make_sphere(s.point, s.radius);
    case IndenterSpec::Type::cylinder: return make_cylinder(s.point, s.direction, s.radius);
    case IndenterSpec::Type::flat_punch:
      return make_flat_punch(s.point.x(), s.point.y(), s.point.z(), s.radius, s.edge_radius);
    case IndenterSpec::Type::sitbar: return make_sitbar(s.sitbar);
    case IndenterSpec::Type::stl:
      return make_stl_surface(mesh::read_stl(s.stl_file.string()), s.stl_file.string() + " (" + where + ")");
  }
  throw InputError(where + ": unknown indenter type");
}

}  // namespace cushion::solver
