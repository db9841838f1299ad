#pragma once
/// Contact definitions of a case file step (plain structs; parsed and validated by parse_contact.cpp).
///
///   "contact": [{"name": "sitbar", "set": "top",
///                "indenter": {"type": "sitbar", ...} (see IndenterSpec),
///                "motion_mm": [0, 0, -60], "amplitude"?: "name",
///                "penalty_MPa_per_mm"? = 1, "tangential_penalty_MPa_per_mm"? = 0.1 x penalty,
///                "friction"? = 0, "tolerance_mm"? = 0.1, "smoothing_mm"? = tolerance / 2 (width of
///                the C1-rounded contact law, 0: plain penalty), "max_augmentations"? = 10,
///                "force_factor"? = 1, "pressure_overclosure"? = "hard" | "linear"}]
/// pressure_overclosure "hard" (default): augmented Lagrangian, the penetration driven below tolerance_mm;
/// "linear": the pressure is penalty_MPa_per_mm x overclosure and stays so (no augmentation: the softened
/// law of ABAQUS/CalculiX *SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR).
/// motion_mm: translation of the indenter at the end of the step relative to where the case file
/// places it [mm]; without amplitude it ramps linearly from its value at the end of the previous
/// step (0 in the first step), with an amplitude it is motion_mm * a(t). The indenter's shape and
/// contact parameters are those of the first step naming the contact; later steps give its motion
/// (state such as multipliers and stick points carries over). force_factor multiplies the
/// reported forces (4 for a quarter model with two symmetry planes).
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "material/tensor.hpp"
#include "mesh/stl.hpp"

namespace cushion::solver {

/// Contact parameters (defaults: the SIT-BAR case); their use: solver/contact/contact_set.hpp.
struct ContactParameters {
  double penalty = 1.0;             ///< normal penalty stiffness per unit area [MPa/mm = N/mm^3]
  double tangential_penalty = 0.0;  ///< tangential penalty per unit area [MPa/mm]; 0: 0.1 x penalty
  double friction = 0.0;            ///< Coulomb coefficient mu [-] (0: frictionless)
  double tolerance = 0.1;           ///< largest penetration accepted after augmentation [mm]
  double smoothing = -1.0;          ///< width delta of the C1 contact law [mm]; < 0: tolerance / 2
  int max_augmentations = 10;       ///< Uzawa updates per increment before giving up
  bool augmented = true;            ///< false: linear pressure-overclosure law (multipliers stay 0)
};

/// Parametric SIT-BAR surrogate (docs/physics.md 1.1; every number assumed unless noted); the surface:
/// make_sitbar in solver/contact/rigid_surface.hpp.
/// Default c = 120 mm (docs/physics.md proposes 60): with c = 60 the lobe flanks turn vertical exactly at
/// 60 mm travel and the plate rim (at the equator) lands on the block, so the paper's 60 mm cannot
/// be pressed smoothly. With c = 120 the plate stays 60 mm above the foam at full travel and the
/// flank slope at 60 mm above the lowest point is bounded (dz/dx = (c/a) r / sqrt(1 - r^2) = 2.1
/// laterally, 1.6 fore-aft, r = sqrt(3)/2).
struct SitBarShape {
  double lowest_z = 80.0;       ///< z of the lobes' lowest points at zero travel [mm]
  double it_spacing = 120.0;    ///< distance between the two lobe centres along x [mm] (RESNA jig, sourced)
  double a = 100.0;             ///< lobe semi-axis along x (lateral) [mm]
  double b = 130.0;             ///< lobe semi-axis along y (fore-aft) [mm]
  double c = 120.0;             ///< lobe semi-axis along z (vertical) [mm]
  double blend = 20.0;          ///< soft-min blend width between lobes and plate [mm]
  double plate_x = 360.0;       ///< plate footprint along x [mm]
  double plate_y = 300.0;       ///< plate footprint along y [mm]
  double plate_edge = 10.0;     ///< edge radius of the plate [mm]
  double centre_x = 0.0;        ///< x of the form's symmetry plane [mm]
  double centre_y = 0.0;        ///< y of the form's symmetry plane [mm]
};

/// Indenter geometry as given in the case file [mm].
///  {"type": "plane", "point_mm": [x,y,z], "normal": [nx,ny,nz]}        normal points to the foam
///  {"type": "sphere", "centre_mm": [x,y,z], "radius_mm": R}
///  {"type": "cylinder", "point_mm": [x,y,z], "axis": [ax,ay,az], "radius_mm": R}
///  {"type": "flat_punch", "centre_mm": [x,y], "bottom_z_mm": z, "radius_mm"? = 100, "edge_radius_mm"? = 1}
///  {"type": "sitbar", "lowest_z_mm"? = 80, "spacing_mm"? = 120, "a_mm"? = 100, "b_mm"? = 130,
///   "c_mm"? = 120, "blend_mm"? = 20, "plate_x_mm"? = 360, "plate_y_mm"? = 300, "plate_edge_mm"? = 10,
///   "centre_mm"? = [0, 0]}
///  {"type": "stl", "file": "indenter.stl"}                              closed, outward normals
/// Type facets (decks only, not a case-file type): the element faces of a *RIGID BODY's master surface,
/// an open triangle set with normals towards the foam (solver/deck/deck_contact.cpp).
struct IndenterSpec {
  enum class Type { plane, sphere, cylinder, flat_punch, sitbar, stl, facets } type = Type::plane;
  Vec3 point = Vec3::Zero();       ///< plane point / sphere centre / cylinder point / punch (cx, cy, bottom) [mm]
  Vec3 direction = Vec3::UnitZ();  ///< plane normal / cylinder axis [-]
  double radius = 0.0;             ///< [mm]
  double edge_radius = 1.0;        ///< flat punch [mm]
  SitBarShape sitbar;              ///< type sitbar only
  std::filesystem::path stl_file;  ///< resolved against the case folder
  std::shared_ptr<const mesh::TriangleSurface> facets;  ///< type facets: triangles [mm], normals to the foam
  std::string facets_name;         ///< type facets: "surface SIND of rigid body INDENTER (deck.inp:517)"
};

/// One "contact" entry of a step.
struct ContactSpec {
  std::string name;                      ///< contact name, unique in its step
  std::string set;                       ///< node set of the foam surface
  IndenterSpec indenter;
  Vec3 motion = Vec3::Zero();            ///< [mm]
  std::optional<std::string> amplitude;  ///< name in CaseSpec::amplitudes
  ContactParameters parameters;
  double force_factor = 1.0;             ///< [-]
  std::string key;                       ///< "steps[0].contact[0]" for messages
};

}  // namespace cushion::solver
