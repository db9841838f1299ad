#pragma once
/// Test support: "foreign" campaigns, generated OUTSIDE cushion's effect library, to check that
/// `diagnose` rests on general signatures and not on the functional forms of material/effect_*.
/// Each campaign is the truth base (hyperfoam + Prony, cushion's Viscoelastic) plus ONE effect written
/// here in a different functional form and with other parameter values than the catalogue's, measured
/// by the lab's protocols (calibration::run_quasi_static / run_dynamic: platen that only pushes, sine fits)
/// with 0.5 % of reading + 0.002 N noise, and written in the campaign format (campaign.hpp).
///
/// The effects act on the axial nominal strain e = 1 - l (compression positive) of the uniaxial tests
/// (nu = 0 base: F = diag(l, 1, 1) throughout) and add a nominal compressive stress s [MPa]:
///   power_law_dashpot   s = eta (1/(1 - e))^m |de/dt|^q sign(de/dt), q = 0.6 (air flow, non-Newtonian)
///   bouc_wen            s = z, dz/de = A - (beta sign(z de) + gamma) |z| (smooth hysteresis, n = 1)
///   exponential_damage  s = -(d (1 - exp(-(e_max - e)/e_c))) s_base (softening below the largest strain)
///   exponential_prony   extra hereditary stress with the base's Prony times and moduli a_i scaled by
///                       exp(k e) - 1 at the strain where the increment happens (preload dependence)
///   fractional_damping  Maxwell bank approximating c D^0.5 e (loss and storage growing like f^0.5)
///   base_off            no effect; the truth hyperfoam has a 4th term (a shape a 3-term fit misses)
///   control             no effect, the base as is
#include <filesystem>
#include <string>

#include "material/io/material_file.hpp"

namespace cushion::foreign {

enum class ForeignCase {
  power_law_dashpot,
  bouc_wen,
  exponential_damage,
  exponential_prony,
  fractional_damping,
  base_off,
  control
};

std::string to_string(ForeignCase c);

struct ForeignCampaign {
  std::filesystem::path manifest;            ///< DIR/campaign.json
  material::MaterialSpec truth_base;          ///< the truth's hyperfoam + Prony (no effect)
  std::string family;  ///< catalogue kind expected first ("": none; base_off, fractional_damping, control)
};

/// Writes the campaign of case `c` into `dir` (created; overwritten). The truth base is
/// cases/hidden_effects/base_material.json (base_off: plus a 4th hyperfoam term).
ForeignCampaign make_foreign_campaign(ForeignCase c, const std::filesystem::path& dir);

}  // namespace cushion::foreign
