#pragma once
/// The rigid surface of a case file's indenter description (IndenterSpec, solver/case/contact_spec.hpp).
#include <memory>
#include <string>
#include <vector>

#include "solver/case/contact_spec.hpp"
#include "solver/contact/rigid_surface.hpp"

namespace cushion::solver {

/// Axis-aligned planes of the model on which boundary conditions hold the normal displacement.
struct HeldPlanes {
  std::vector<AxisPlane> symmetry;  ///< planes of symmetry_x|y|z conditions (the model is cut there)
  std::vector<AxisPlane> held;      ///< other planes whose nodes are held normal to them (fixed, zero displacement)
  double tolerance = 0.0;           ///< a triangle lies in a plane if its vertices are this close [mm]
};

/// The rigid surface of an indenter [mm] (reads and checks the STL file); `where` prefixes messages.
/// Throws InputError for an unreadable or open STL surface. For an STL indenter, the triangles lying
/// in `planes.symmetry` are dropped (make_stl_surface) and those lying in `planes.held` counted; one
/// warning line each (how many triangles, which plane, why) goes to `notes`.
std::shared_ptr<const RigidSurface> make_indenter(const IndenterSpec& spec, const std::string& where,
                                                  const HeldPlanes& planes = {},
                                                  std::vector<std::string>* notes = nullptr);

}  // namespace cushion::solver
