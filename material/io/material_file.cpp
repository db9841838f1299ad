#include "material/io/material_file.hpp"

#include <cmath>
#include <stdexcept>

#include "io/input_error.hpp"
#include "io/json_reader.hpp"
#include "io/text_support.hpp"
#include "material/neo_hookean.hpp"

namespace cushion::material {

namespace {

constexpr double kPa = 1e-3;             // kPa -> MPa
constexpr double kg_per_m3 = 1e-12;      // kg/m^3 -> t/mm^3
constexpr std::size_t max_prony_terms = 20;

bool non_negative(double x) { return x >= 0.0; }
bool poisson_range(double x) { return x >= 0.0 && x < 0.5; }
// Physical bounds (material_file.hpp): values past them would overflow the model (1e308 kPa gave -inf).
// Hyperfoam terms: fitted terms of opposite sign can be large (a `cushion fit` gave mu_kPa 6.7e6).
bool term_modulus_range(double x) { return std::abs(x) <= 1e9; }               // |mu_kPa| <= 1e9
bool positive_modulus(double x) { return x > 0.0 && x <= 1e6; }
bool non_negative_modulus(double x) { return x >= 0.0 && x <= 1e6; }
bool lambda_range(double x) { return std::abs(x) <= 1e9; }                     // |lambda| <= 1e9 kPa
bool alpha_range(double x) { return x != 0.0 && std::abs(x) <= 100.0; }
bool time_range(double x) { return x > 0.0 && x <= 1e9; }                      // 0 < tau_s <= 1e9 s
bool density_range(double x) { return x > 0.0 && x <= 1e7; }                  // 0 < density <= 1e7 kg/m^3 (mass scaling allowed)

std::vector<HyperfoamTerm> read_hyperfoam(const io::JsonNode& node) {
  node.expect_object({"terms"});
  const io::JsonNode terms = node.at("terms");
  const std::size_t n = terms.expect_array(1, 6);
  std::vector<HyperfoamTerm> result;
  double mu_sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const io::JsonNode term = terms[i];
    term.expect_object({"mu_kPa", "alpha", "nu"});
    HyperfoamTerm t;
    t.mu = term.at("mu_kPa").number_where(term_modulus_range, "in [-1e9, 1e9] kPa") * kPa;
    t.alpha = term.at("alpha").number_where(alpha_range, "non-zero and in [-100, 100]");
    t.nu = term.at("nu").number_where(poisson_range, "in [0, 0.5)");
    mu_sum += t.mu;
    result.push_back(t);
  }
  if (!(mu_sum > 0.0)) terms.fail("the initial shear modulus sum(mu_kPa) must be > 0");
  return result;
}

void read_neo_hookean(const io::JsonNode& node, MaterialSpec& spec) {
  node.expect_object({"mu_kPa", "lambda_kPa"});
  spec.neo_mu = node.at("mu_kPa").number_where(positive_modulus, "> 0 and <= 1e6 kPa") * kPa;
  const io::JsonNode lambda = node.at("lambda_kPa");
  spec.neo_lambda = lambda.number_where(lambda_range, "in [-1e9, 1e9] kPa") * kPa;
  if (!(spec.neo_lambda > -2.0 * spec.neo_mu / 3.0)) lambda.fail("must be > -2 mu_kPa / 3 (positive bulk modulus)");
}

std::vector<PronyTerm> read_relative_prony(const io::JsonNode& prony) {
  const std::size_t n = prony.expect_array(1, max_prony_terms);
  std::vector<PronyTerm> terms;
  double g_sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const io::JsonNode term = prony[i];
    term.expect_object({"g", "tau_s"});
    PronyTerm t;
    t.g = term.at("g").number_where(non_negative, ">= 0");
    t.tau = term.at("tau_s").number_where(time_range, "> 0 and <= 1e9 s");
    g_sum += t.g;
    terms.push_back(t);
  }
  if (!(g_sum < 1.0)) prony.fail("sum of g must be < 1 (a positive long-term modulus), found " + io::format_double(g_sum));
  return terms;
}

std::vector<PronyTerm> read_absolute_prony(const io::JsonNode& absolute) {
  absolute.expect_object({"E_inf_kPa", "terms"});
  const double E_inf = absolute.at("E_inf_kPa").number_where(positive_modulus, "> 0 and <= 1e6 kPa");
  const io::JsonNode terms = absolute.at("terms");
  const std::size_t n = terms.expect_array(1, max_prony_terms);
  std::vector<double> E, tau;
  for (std::size_t i = 0; i < n; ++i) {
    const io::JsonNode term = terms[i];
    term.expect_object({"E_kPa", "tau_s"});
    E.push_back(term.at("E_kPa").number_where(non_negative_modulus, ">= 0 and <= 1e6 kPa"));
    tau.push_back(term.at("tau_s").number_where(time_range, "> 0 and <= 1e9 s"));
  }
  return prony_from_absolute(E_inf, E, tau);
}

void read_viscoelastic(const io::JsonNode& node, MaterialSpec& spec) {
  node.expect_object({"moduli", "prony", "absolute"});
  spec.moduli = node.at("moduli").choice({"long_term", "instantaneous"}) == "long_term"
                    ? ModuliConvention::long_term
                    : ModuliConvention::instantaneous;
  const bool relative = node.has("prony"), absolute = node.has("absolute");
  if (relative == absolute) node.fail("give exactly one of \"prony\" (relative g) or \"absolute\" (E_kPa)");
  spec.prony = relative ? read_relative_prony(node.at("prony")) : read_absolute_prony(node.at("absolute"));
}

/// "effects": [{"kind": "...", "<parameter with unit>": number, ...}, ...]; names checked against the catalogue.
std::vector<EffectSpec> read_effects(const io::JsonNode& node) {
  std::vector<EffectSpec> effects;
  const std::size_t count = node.expect_array(0, 16);
  for (std::size_t i = 0; i < count; ++i) {
    const io::JsonNode item = node[i];
    EffectSpec effect;
    effect.kind = item.at("kind").choice([] {
      std::vector<std::string> kinds;
      for (const auto& info : effect_catalog()) kinds.push_back(info.kind);
      return kinds;
    }());
    std::vector<std::string> allowed{"kind"};
    for (const auto& parameter : find_effect(effect.kind)->parameters) allowed.push_back(parameter.name);
    item.expect_object(allowed);
    for (std::size_t k = 1; k < allowed.size(); ++k)
      if (auto value = item.find(allowed[k])) effect.parameters[allowed[k]] = value->number();
    effects.push_back(std::move(effect));
  }
  return effects;
}

}  // namespace

MaterialDefinition build_material(const MaterialSpec& spec, const std::string& source) {
  MaterialDefinition definition;
  definition.spec = spec;
  definition.source = source;
  try {
    if (spec.base == MaterialSpec::Base::hyperfoam)
      definition.elastic = std::make_shared<Hyperfoam>(spec.hyperfoam);
    else if (spec.base == MaterialSpec::Base::ogden)
      definition.elastic = std::make_shared<Ogden>(spec.ogden, spec.ogden_D);
    else
      definition.elastic = std::make_shared<NeoHookean>(spec.neo_mu, spec.neo_lambda);
    if (spec.prony.empty())
      definition.model = definition.elastic;
    else
      definition.model = std::make_shared<Viscoelastic>(definition.elastic, spec.prony, spec.moduli);
    definition.model = apply_effects(definition.model, definition.elastic, spec.effects, source);
  } catch (const std::invalid_argument& e) {
    throw InputError(source + ": invalid material parameters: " + e.what());
  }
  return definition;
}

MaterialDefinition parse_material_json(const std::string& text, const std::string& source) {
  const nlohmann::json json = io::parse_json(text, source);
  const io::JsonNode root(json, source);
  root.expect_object({"name", "description", "density_kg_m3", "hyperfoam", "neo_hookean", "viscoelastic", "effects"});

  MaterialSpec spec;
  if (auto name = root.find("name")) {
    spec.name = name->string();
    if (spec.name.empty()) name->fail("must not be empty");
  }
  if (auto description = root.find("description")) spec.description = description->string();
  if (auto density = root.find("density_kg_m3"))
    spec.density = density->number_where(density_range, "> 0 and <= 1e7 kg/m^3") * kg_per_m3;

  const bool hyperfoam = root.has("hyperfoam"), neo_hookean = root.has("neo_hookean");
  if (hyperfoam == neo_hookean) root.fail("give exactly one elastic base: \"hyperfoam\" or \"neo_hookean\"");
  if (hyperfoam) {
    spec.base = MaterialSpec::Base::hyperfoam;
    spec.hyperfoam = read_hyperfoam(root.at("hyperfoam"));
  } else {
    spec.base = MaterialSpec::Base::neo_hookean;
    read_neo_hookean(root.at("neo_hookean"), spec);
  }
  if (auto viscoelastic = root.find("viscoelastic")) read_viscoelastic(*viscoelastic, spec);
  if (auto effects = root.find("effects")) spec.effects = read_effects(*effects);
  return build_material(spec, source);
}

MaterialDefinition read_material_file(const std::filesystem::path& file) {
  return parse_material_json(io::read_text_file(file.string()), file.string());
}

void write_material_file(const MaterialSpec& spec, const std::filesystem::path& file) {
  if (spec.base == MaterialSpec::Base::ogden)
    throw std::invalid_argument("write_material_file: an Ogden material has no material-file form");
  nlohmann::ordered_json json;
  json["name"] = spec.name;
  if (!spec.description.empty()) json["description"] = spec.description;
  if (spec.density > 0.0) json["density_kg_m3"] = spec.density / kg_per_m3;
  if (spec.base == MaterialSpec::Base::hyperfoam) {
    nlohmann::ordered_json terms = nlohmann::ordered_json::array();
    for (const auto& t : spec.hyperfoam)
      terms.push_back({{"mu_kPa", t.mu / kPa}, {"alpha", t.alpha}, {"nu", t.nu}});
    json["hyperfoam"] = {{"terms", terms}};
  } else {
    json["neo_hookean"] = {{"mu_kPa", spec.neo_mu / kPa}, {"lambda_kPa", spec.neo_lambda / kPa}};
  }
  if (!spec.prony.empty()) {
    nlohmann::ordered_json prony = nlohmann::ordered_json::array();
    for (const auto& t : spec.prony) prony.push_back({{"g", t.g}, {"tau_s", t.tau}});
    json["viscoelastic"] = {{"moduli", spec.moduli == ModuliConvention::long_term ? "long_term" : "instantaneous"},
                            {"prony", prony}};
  }
  if (!spec.effects.empty()) {
    nlohmann::ordered_json effects = nlohmann::ordered_json::array();
    for (const auto& effect : spec.effects) {
      nlohmann::ordered_json item;
      item["kind"] = effect.kind;
      for (const auto& [name, value] : effect.parameters) item[name] = value;
      effects.push_back(item);
    }
    json["effects"] = effects;
  }
  io::write_file_atomically(file, json.dump(2) + "\n");
}

}  // namespace cushion::material
