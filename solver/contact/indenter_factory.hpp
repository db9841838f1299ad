#pragma once
/// The rigid surface of a case file's indenter description (IndenterSpec, solver/case/contact_spec.hpp).
#include <memory>
#include <string>

#include "solver/case/contact_spec.hpp"
#include "solver/contact/rigid_surface.hpp"

namespace cushion::solver {

/// The rigid surface of an indenter [mm] (reads and checks the STL file); `where` prefixes messages.
/// Throws InputError for an unreadable or open STL surface.
std::shared_ptr<const RigidSurface> make_indenter(const IndenterSpec& spec, const std::string& where);

}  // namespace cushion::solver
