#pragma once
/// Contact definitions of a case file step (plain structs; parsed and validated by case_file.cpp).
///
///   "contact": [{"name": "sitbar", "set": "top",
///                "indenter": {"type": "sitbar", ...} (see IndenterSpec),
///                "motion_mm": [0, 0, -60], "amplitude"?: "name",
///                "penalty_MPa_per_mm"? = 1, "tangential_penalty_MPa_per_mm"? = 0.1 x penalty,
///                "friction"? = 0, "tolerance_mm"? = 0.1, "smoothing_mm"? = tolerance / 2 (width of
///                the C1-rounded contact law, 0: plain penalty), "max_augmentations"? = 10,
///                "force_factor"? = 1}]
/// motion_mm: translation of the indenter at the end of the step relative to where the case file
/// places it [mm]; without amplitude it ramps linearly from its value at the end of the previous
/// step (0 in the first step), with an amplitude it is motion_mm * a(t). The indenter's shape and
/// contact parameters are those of the first step naming the contact; later steps give its motion
/// (state such as multipliers and stick points carries over). force_factor multiplies the
/// reported forces (4 for a quarter model with two symmetry planes).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "solver/contact/contact_set.hpp"
#include "solver/contact/rigid_surface.hpp"

namespace cushion::solver {

/// Indenter geometry as given in the case file [mm].
///  {"type": "plane", "point_mm": [x,y,z], "normal": [nx,ny,nz]}        normal points to the foam
///  {"type": "sphere", "centre_mm": [x,y,z], "radius_mm": R}
///  {"type": "cylinder", "point_mm": [x,y,z], "axis": [ax,ay,az], "radius_mm": R}
///  {"type": "flat_punch", "centre_mm": [x,y], "bottom_z_mm": z, "radius_mm"? = 100, "edge_radius_mm"? = 1}
///  {"type": "sitbar", "lowest_z_mm"? = 80, "spacing_mm"? = 120, "a_mm"? = 100, "b_mm"? = 130,
///   "c_mm"? = 120, "blend_mm"? = 20, "plate_x_mm"? = 360, "plate_y_mm"? = 300, "plate_edge_mm"? = 10,
///   "centre_mm"? = [0, 0]}
///  {"type": "stl", "file": "indenter.stl"}                              closed, outward normals
struct IndenterSpec {
  enum class Type { plane, sphere, cylinder, flat_punch, sitbar, stl } type = Type::plane;
  Vec3 point = Vec3::Zero();       ///< plane point / sphere centre / cylinder point / punch (cx, cy, bottom) [mm]
  Vec3 direction = Vec3::UnitZ();  ///< plane normal / cylinder axis [-]
  double radius = 0.0;             ///< [mm]
  double edge_radius = 1.0;        ///< flat punch [mm]
  SitBarShape sitbar;
  std::filesystem::path stl_file;  ///< resolved against the case folder
};

struct ContactSpec {
  std::string name;
  std::string set;
  IndenterSpec indenter;
  Vec3 motion = Vec3::Zero();            ///< [mm]
  std::optional<std::string> amplitude;  ///< name in CaseSpec::amplitudes
  ContactParameters parameters;
  double force_factor = 1.0;             ///< [-]
  std::string key;                       ///< "steps[0].contact[0]" for messages
};

}  // namespace cushion::solver
