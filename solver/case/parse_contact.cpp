// The "contact" part of the case grammar (contact_spec.hpp): rigid indenters and contact parameters.
#include <algorithm>

#include "solver/case/case_parts.hpp"

namespace cushion::solver::case_parse {

namespace {

Vec3 vec3(const Obj& o, const std::string& key, std::size_t n = 3) {
  const auto v = o.numbers(key, n, n);
  Vec3 out = Vec3::Zero();
  for (std::size_t i = 0; i < n; ++i) out(static_cast<int>(i)) = v[i];
  return out;
}

SitBarShape parse_sitbar(const Obj& p) {
  SitBarShape s;
  if (p.has("lowest_z_mm")) s.lowest_z = p.number("lowest_z_mm");
  if (p.has("spacing_mm")) s.it_spacing = p.number("spacing_mm");
  if (s.it_spacing < 0.0) p.fail("spacing_mm", "must be >= 0");
  s.a = p.positive_or("a_mm", s.a), s.b = p.positive_or("b_mm", s.b), s.c = p.positive_or("c_mm", s.c);
  s.blend = p.positive_or("blend_mm", s.blend);
  s.plate_x = p.positive_or("plate_x_mm", s.plate_x), s.plate_y = p.positive_or("plate_y_mm", s.plate_y);
  s.plate_edge = p.positive_or("plate_edge_mm", s.plate_edge);
  if (2 * s.plate_edge >= std::min(s.plate_x, s.plate_y))
    p.fail("plate_edge_mm", "must be less than half the plate size");
  if (p.has("centre_mm")) {
    const Vec3 c = vec3(p, "centre_mm", 2);
    s.centre_x = c.x(), s.centre_y = c.y();
  }
  return s;
}

/// "indenter": the keys allowed depend on "type" (contact_spec.hpp).
IndenterSpec parse_indenter(const nlohmann::json& value, const Context& ctx, const std::string& path) {
  IndenterSpec in;
  if (!value.is_object()) io::JsonNode(value, ctx.source, path).fail("must be an object {\"type\": ...}");
  const std::string type = io::JsonNode(value, ctx.source, path)
                               .at("type")
                               .choice({"plane", "sphere", "cylinder", "flat_punch", "sitbar", "stl"});
  const auto allowed = [&](std::vector<std::string> keys) {
    keys.push_back("type");
    return Obj(value, ctx, path, keys);
  };
  if (type == "plane") {
    const Obj p = allowed({"point_mm", "normal"});
    in.type = IndenterSpec::Type::plane, in.point = vec3(p, "point_mm"), in.direction = vec3(p, "normal");
    if (in.direction.norm() == 0.0) p.fail("normal", "must not be zero");
  } else if (type == "sphere") {
    const Obj p = allowed({"centre_mm", "radius_mm"});
    in.type = IndenterSpec::Type::sphere, in.point = vec3(p, "centre_mm"), in.radius = p.positive("radius_mm");
  } else if (type == "cylinder") {
    const Obj p = allowed({"point_mm", "axis", "radius_mm"});
    in.type = IndenterSpec::Type::cylinder, in.point = vec3(p, "point_mm"), in.direction = vec3(p, "axis");
    in.radius = p.positive("radius_mm");
    if (in.direction.norm() == 0.0) p.fail("axis", "must not be zero");
  } else if (type == "flat_punch") {
    const Obj p = allowed({"centre_mm", "bottom_z_mm", "radius_mm", "edge_radius_mm"});
    in.type = IndenterSpec::Type::flat_punch;
    in.point = vec3(p, "centre_mm", 2);
    in.point.z() = p.number("bottom_z_mm");
    in.radius = p.positive_or("radius_mm", 100.0);
    in.edge_radius = p.positive_or("edge_radius_mm", 1.0);
    if (in.edge_radius > in.radius) p.fail("edge_radius_mm", "must not exceed radius_mm");
  } else if (type == "sitbar") {
    in.type = IndenterSpec::Type::sitbar;
    in.sitbar = parse_sitbar(allowed({"lowest_z_mm", "spacing_mm", "a_mm", "b_mm", "c_mm", "blend_mm", "plate_x_mm",
                                      "plate_y_mm", "plate_edge_mm", "centre_mm"}));
  } else {
    const Obj p = allowed({"file"});
    in.type = IndenterSpec::Type::stl, in.stl_file = p.file("file");
  }
  return in;
}

ContactParameters parse_contact_parameters(const Obj& o) {
  ContactParameters p;
  p.penalty = o.positive_or("penalty_MPa_per_mm", p.penalty);
  p.tangential_penalty = o.positive_or("tangential_penalty_MPa_per_mm", 0.1 * p.penalty);
  if (o.has("friction")) p.friction = o.number("friction");
  if (p.friction < 0.0) o.fail("friction", "must be >= 0");
  p.tolerance = o.positive_or("tolerance_mm", p.tolerance);
  if (o.has("smoothing_mm")) {
    p.smoothing = o.number("smoothing_mm");
    if (!(p.smoothing >= 0.0) || !(p.smoothing <= 10.0 * p.tolerance))
      o.fail("smoothing_mm", "must be >= 0 and at most 10 x tolerance_mm [mm]");
  }
  if (o.has("max_augmentations")) p.max_augmentations = o.integer("max_augmentations", 0, 1000);
  p.augmented = o.choice_or("pressure_overclosure", {"hard", "linear"}, "hard") == "hard";
  return p;
}

}  // namespace

ContactSpec parse_contact(const Obj& o, const CaseSpec& spec, const StepSpec& step) {
  ContactSpec c;
  c.key = o.here();
  c.name = o.string("name");
  if (c.name.empty() || c.name.find_first_of(" ,\"/") != std::string::npos)
    o.fail("name", "must be a non-empty name without spaces, commas, quotes or slashes");
  for (const ContactSpec& other : step.contact)
    if (other.name == c.name) o.fail("name", "duplicate contact name \"" + c.name + "\" in this step");
  c.set = o.string("set");
  check_set_defined(o, "set", c.set, spec);
  c.indenter = parse_indenter(o.raw("indenter"), o.ctx(), o.path("indenter"));
  c.motion = vec3(o, "motion_mm");
  if (o.has("amplitude")) {
    c.amplitude = o.string("amplitude");
    check_amplitude_defined(o, "amplitude", *c.amplitude, spec);
  }
  c.parameters = parse_contact_parameters(o);
  c.force_factor = o.positive_or("force_factor", 1.0);
  return c;
}

}  // namespace cushion::solver::case_parse
