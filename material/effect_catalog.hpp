#pragma once
/// The catalogue of optional physical effects (all off unless listed) and the one function that
/// stacks them on a material. Generic by design: the `diagnose` command enumerates effect_catalog(),
/// builds candidate lists of EffectSpec from the defaults and bounds, and refits the parameters
/// marked `fit` without knowing any effect by name. Material files list them as
///   "effects": [{"kind": "pneumatic", "drainage_length_mm": 40, "permeability_mm2": 1e-3}, ...]
/// (parameter keys carry their units; omitted parameters take their defaults).
///
/// Effects (material/effect_*.hpp for the equations):
///   pneumatic               air-flow (Darcy) damping, lumped, size-dependent through R
///   friction                rate-independent frictional hysteresis (elasto-plastic parallel branch)
///   mullins                 Ogden-Roxburgh softening below the largest energy reached
///   strain_dependent_prony  Prony moduli scaled by J^{-c} (needs a viscoelastic material; first in the list)
///   stiffness_damping       Rayleigh-beta damping beta_s C_d dE/dt at material level (C_d: initial or current tangent),
///                           or a fractional derivative D^q E in place of dE/dt (derivative_order q < 1)
/// The "reference elastic base" of mullins (energy W) and stiffness_damping (C0 at F = I) is the
/// LONG-TERM base when the base model is Viscoelastic, else the elastic base.
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "material/hyperelastic.hpp"

namespace cushion::material {

/// One effect as written in a material file: its kind and named parameters in FILE units (the
/// unit is part of the name: "_mm", "_mm2", "_kPa", "_Pa_s", "_s"; no suffix: dimensionless).
struct EffectSpec {
  std::string kind;
  std::map<std::string, double> parameters;  ///< omitted parameters take the catalogue default
};

/// One parameter of an effect, in file units.
struct EffectParameterInfo {
  std::string name;          ///< key with its unit, e.g. "permeability_mm2"
  std::string description;   ///< one line
  double default_value = 0;  ///< [file unit]
  double min = 0, max = 0;   ///< admissible range [file unit]
  bool min_exclusive = false;///< true: value > min; false: value >= min (max is always inclusive)
  bool fit = true;           ///< refitted by diagnose by default (false: case or physical constant)
  bool log_scale = false;    ///< positive and spanning decades: fit its logarithm
  /// Where diagnose's fit starts and centres its search range when not the default (0: the default). For a
  /// parameter whose default switches a branch off (air_modulus_kPa 0: no trapped-air spring), so that the
  /// fit starts where the parameter matters.
  double fit_start = 0;
  /// Another parameter of the same effect that diagnose's start search scans together with this one (every
  /// combination of both parameters' trial values) instead of each in turn: for two parameters that set one time scale
  /// or one shape between them, where moving either alone leaves the effect out of its basin (the air flow's trapped-air
  /// modulus with its permeability: the Maxwell time; the dashpot's rate exponent with its permeability exponent: how
  /// the loss grows with frequency and with the preload, docs/physics.md 9.25; empty: scanned in turn).
  std::string scan_with{};
  /// For a parameter diagnose does not fit (fit false): the value it holds there instead of the default, where the
  /// default keeps a form users' files expect and diagnose fits another (pneumatic pressure_share 0: the drag).
  std::optional<double> diagnose_value{};
  /// A second start of diagnose's single fit (none: one start) in a regime of the effect that the start scan from
  /// fit_start does not reach: the single is fitted from both starts and the larger dBIC kept. 0 for a log-scale
  /// parameter whose 0 switches a branch off: held off in that fit (the air flow's trapped-air modulus: a Maxwell
  /// branch from 100 kPa, and 0, a Darcy dashpot with one parameter fewer; docs/physics.md 9.9). > 0 for one whose
  /// start 0 holds a branch off: switched on and fitted from there (mullins strain_scale 0.3: the strain driver,
  /// docs/physics.md 9.10).
  std::optional<double> second_start{};
  /// Another log-scale parameter of the same effect whose 0 switches a branch off: diagnose fits this one only in a fit
  /// where that branch is off, and holds it at its default otherwise (empty: always fitted; the air flow's rate exponent
  /// is fitted for the dashpot, trapped-air modulus 0, and held at 1, Darcy, in the Maxwell branch: free there it took
  /// a foreign Maxwell branch to q 3 and n_K -2; docs/physics.md 9.9).
  std::string fitted_only_without{};
  /// Another log-scale parameter of the same effect whose 0 switches a branch off: diagnose fits this one only in a fit
  /// where that branch is on, and holds it at its default otherwise (empty: always fitted; the air flow's trapped-air
  /// modulus exponent is meaningless in the dashpot, trapped-air modulus 0; docs/physics.md 5.1).
  std::string fitted_only_with{};
  /// Held by diagnose's single and pair fits (at the value given, else the default) and fitted only after the polish of
  /// the best single, from its polished fit (DiagnoseOptions::fit_polished_only, on by default; step 2b of
  /// calibration/diagnose.hpp): a shape parameter that a fit from the start scan takes somewhere wrong when the base
  /// `cushion fit` placed is off, but that a fit from the effect's own polished single moves to where the data want it
  /// (mullins beta, docs/physics.md 9.41-9.42). Only with fit false.
  bool polished_only = false;
  /// A scale that may lie decades from its start but that the stress is linear in (the damping time beta_s): diagnose's
  /// start scan tries it a decade apart over three decades either side of its start, as a log-scale parameter, while
  /// Levenberg-Marquardt fits the value itself (fitted in decades too, it ended lower on the five-test campaigns;
  /// scanned about its start by factors 0-10 only, it could not leave 0 once the scan kept it there; docs/physics.md 9.47).
  /// Only with log_scale false.
  bool scan_decades = false;
  /// For a parameter diagnose holds (fit false): another value at which the NAMED single is fitted once more after the
  /// ranking, from its own fit, and kept when its BIC is lower (none: not tried). A form that fits its own family
  /// better but would rival other families in the ranking (friction stretch_exponent 1, the nominal Jenkins element,
  /// named friction on four Mullins campaigns when fitted in the ranking; docs/physics.md 9.49): the family stays the
  /// ranking's, the named model and its error after are the better form's.
  std::optional<double> named_value{};
};

/// One effect of the catalogue.
struct EffectInfo {
  std::string kind;
  std::string description;  ///< one line
  std::vector<EffectParameterInfo> parameters;
  bool needs_viscoelastic = false;   ///< only on a Viscoelastic base model, as the first effect
  bool needs_elastic_base = false;   ///< uses the reference elastic base (energy or initial tangent)
  /// A parameter whose value > 0 makes the effect edit the Prony memory beneath it (mullins relaxation_share): then
  /// it must sit directly over the Prony memory (the first effect on a Viscoelastic model, or next over
  /// strain_dependent_prony). Empty: none.
  std::string memory_parameter;
  /// The parameters d_inf and e_d of a damage d = d_inf (1 - exp(-e_max/e_d)) in the largest strain that softens the
  /// first loading too (mullins damage_limit, damage_strain): diagnose fits the single once more from a start with
  /// both estimated from a quasi-static test's loading and unloading and the base's hyperfoam refitted to the first
  /// loadings over 1 - d(e) (calibration/damage_start.hpp). Empty: none.
  std::string damage_limit_parameter{}, damage_strain_parameter{};
  /// A parameter at whose maximum the effect's recoverable softening is off (mullins r: the Ogden-Roxburgh factor
  /// 1 - erf(...)/r within 0.1 % of 1 at r = 1e3): the damage start above holds it there, since its estimate of d_inf
  /// and e_d reads the whole drop of the unloading below the loading as damage (docs/physics.md 9.48). Empty: none.
  std::string recoverable_softening_parameter{};
};

/// Every effect, in a fixed order.
const std::vector<EffectInfo>& effect_catalog();

/// The catalogue entry of `kind`, or nullptr.
const EffectInfo* find_effect(const std::string& kind);

/// Checks kinds, parameter names and ranges, and duplicates. Throws InputError
/// "<source>: effects[i].<parameter>: <problem>" (or "effects[i].kind" for an unknown kind).
void validate_effects(const std::vector<EffectSpec>& effects, const std::string& source = "material");

/// The effects in the order apply_effects needs: needs_viscoelastic ones first, then those whose memory parameter is
/// > 0, then the rest, each group in list order. Both kinds edit the Prony memory beneath them; one of each
/// composes (strain_dependent_prony is a PronyMemory, material/viscoelastic.hpp).
std::vector<EffectSpec> composition_order(std::vector<EffectSpec> effects);

/// Validates, then wraps `base_model` in the effects in list order (the first effect is innermost).
/// elastic_base: the elastic base of the material (may be null when base_model is itself elastic);
/// see "reference elastic base" above. Returns base_model itself for an empty list. Throws
/// InputError as validate_effects, and when strain_dependent_prony (or an effect with its memory parameter > 0) is
/// not first or the model is not viscoelastic, or no elastic base is available for mullins/stiffness_damping.
std::shared_ptr<const Material> apply_effects(std::shared_ptr<const Material> base_model,
                                              std::shared_ptr<const Hyperelastic> elastic_base,
                                              const std::vector<EffectSpec>& effects,
                                              const std::string& source = "material");

}  // namespace cushion::material
