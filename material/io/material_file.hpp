#pragma once
/// Material files: JSON with units in every key. Format (README "Material file"):
/// {
///   "name": "foam65",                                                              (optional, default "material")
///   "description": "where the numbers come from",                                  (optional)
///   "density_kg_m3": 65,                                                           (optional, > 0)
///   "hyperfoam": {"terms": [{"mu_kPa": 12.0, "alpha": 9.0, "nu": 0.0}, ...]},      (1..6 terms)
///     or "neo_hookean": {"mu_kPa": 10, "lambda_kPa": 5},                           (exactly one base)
///   "viscoelastic": {"moduli": "long_term" | "instantaneous",                      (optional)
///                    "prony": [{"g": 0.31, "tau_s": 0.01}, ...]}                     (relative, ABAQUS)
///     or           {"moduli": ..., "absolute": {"E_inf_kPa": 3.05,
///                    "terms": [{"E_kPa": 23.9, "tau_s": 0.01}, ...]}}                (paper Table 3)
/// }
/// Every key shown is required inside its object. Ranges: alpha != 0, 0 <= nu < 0.5, sum mu > 0;
/// neo-Hookean mu > 0, lambda > -2 mu / 3; 1..20 Prony terms, g >= 0, sum g < 1, tau_s > 0, E_kPa >= 0,
/// E_inf_kPa > 0. Physical bounds, so that no value overflows the model (issue 16: mu_kPa 1e308
/// gave -inf stresses): hyperfoam |mu_kPa| <= 1e9 (fitted terms of opposite sign can be large),
/// neo-Hookean mu_kPa <= 1e6, 0 < |alpha| <= 100, |lambda_kPa| <= 1e9, E_kPa and E_inf_kPa <= 1e6,
/// tau_s <= 1e9 s, density_kg_m3 <= 1e7 (mass scaling allowed).
/// Unknown keys, missing keys, wrong types, out-of-range or non-finite values raise
/// InputError naming the file and the key path (e.g. "foam.json: hyperfoam.terms[1].alpha: must be non-zero").
/// The writer always writes the relative "prony" form.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "material/effect_catalog.hpp"
#include "material/hyperfoam.hpp"
#include "material/ogden.hpp"
#include "material/viscoelastic.hpp"

namespace cushion::material {

/// Plain data read from / written to a material file, in internal units (MPa, t/mm^3, s).
struct MaterialSpec {
  std::string name = "material";
  std::string description;  ///< free text (provenance of the numbers); empty: not written
  double density = 0.0;  ///< [t/mm^3] (65 kg/m^3 = 6.5e-11 t/mm^3); 0 means "not given"
  /// ogden: ABAQUS *HYPERELASTIC, OGDEN / NEO HOOKE (from a deck only; material files have no "ogden" key)
  enum class Base { hyperfoam, neo_hookean, ogden } base = Base::hyperfoam;
  std::vector<HyperfoamTerm> hyperfoam;  ///< base == hyperfoam
  double neo_mu = 0.0, neo_lambda = 0.0; ///< base == neo_hookean [MPa]
  std::vector<OgdenTerm> ogden;          ///< base == ogden
  std::vector<double> ogden_D;           ///< base == ogden: D_1..D_N [1/MPa]
  std::vector<PronyTerm> prony;          ///< empty: purely elastic
  ModuliConvention moduli = ModuliConvention::long_term;
  std::vector<EffectSpec> effects;       ///< optional physical effects, file units (material/effect_catalog.hpp)
};

/// The built model plus what the solver needs besides the constitutive law.
struct MaterialDefinition {
  MaterialSpec spec;
  std::shared_ptr<const Hyperelastic> elastic;  ///< the base as given in the file
  std::shared_ptr<const Material> model;        ///< elastic, or Viscoelastic wrapping it, then the effects
  std::string source;                           ///< file name for messages
};

/// Builds the model from a spec (throws InputError naming `source` on invalid parameters).
MaterialDefinition build_material(const MaterialSpec& spec, const std::string& source = "material");

/// Reads and validates a material file; throws InputError("<file>: <key>: <problem>").
MaterialDefinition read_material_file(const std::filesystem::path& file);

/// Parses material JSON text (for files and for materials embedded in other files).
MaterialDefinition parse_material_json(const std::string& text, const std::string& source);

/// Writes a spec as a material file (kPa, kg/m^3, s), atomically (temporary file then rename).
/// An Ogden base has no material-file form: std::invalid_argument.
void write_material_file(const MaterialSpec& spec, const std::filesystem::path& file);

}  // namespace cushion::material
