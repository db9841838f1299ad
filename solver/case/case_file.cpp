#include "solver/case/case_file.hpp"

#include <algorithm>
#include <cmath>

#include "io/input_error.hpp"
#include "io/json_reader.hpp"
#include "io/text_support.hpp"
#include "mesh/selectors.hpp"

namespace cushion::solver {

namespace {

using nlohmann::json;

std::string join(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }

/// Unit suffixes used in key names and what they mean (for "wrong unit" messages).
const std::vector<std::pair<std::string, std::string>> kUnits = {
    {"s", "seconds"}, {"mm", "millimetres"}, {"mm3", "cubic millimetres"}, {"deg", "degrees"}};

/// Suffixes that look like a unit (so "time_period_ms" is a wrong unit, "initial_ss" a misspelling).
const std::set<std::string> kUnitLike = {"s",  "ms", "us", "min", "h",   "mm",  "m",  "cm", "um",
                                         "in", "mm3", "m3", "cm3", "deg", "rad", "mm2", "m2"};

/// Key stem and unit suffix: "time_period_ms" -> {"time_period", "ms"}; no '_' -> {key, ""}.
std::pair<std::string, std::string> split_unit(const std::string& key) {
  const auto underscore = key.rfind('_');
  if (underscore == std::string::npos) return {key, ""};
  return {key.substr(0, underscore), key.substr(underscore + 1)};
}

/// Context shared by the whole parse: file name for messages, folder for relative paths.
struct Context {
  std::string source;
  std::filesystem::path folder;
};

/// A JSON object whose keys must all be in `allowed`; typed, path-naming getters on top of io::JsonNode.
class Obj {
 public:
  Obj(const json& value, const Context& ctx, std::string path, const std::vector<std::string>& allowed)
      : value_(value), ctx_(ctx), path_(std::move(path)), node_(value, ctx.source, path_) {
    if (value.is_object()) {
      for (const auto& [key, ignored] : value.items()) {
        if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
        // A known key with a different unit suffix: say so (units are fixed by the key name).
        const auto [stem, unit] = split_unit(key);
        for (const auto& a : allowed) {
          const auto [a_stem, a_unit] = split_unit(a);
          if (!kUnitLike.count(unit) || a_unit.empty() || stem != a_stem) continue;
          auto meaning = std::find_if(kUnits.begin(), kUnits.end(), [&](const auto& u) { return u.first == a_unit; });
          io::JsonNode(value[key], ctx.source, join(path_, key))
              .fail("wrong unit '" + unit + "': this quantity is given as '" + a + "'" +
                    (meaning != kUnits.end() ? " (" + meaning->second + ")" : std::string{}));
        }
      }
    }
    node_.expect_object(allowed);
  }

  bool has(const std::string& key) const { return value_.contains(key); }
  io::JsonNode at(const std::string& key) const { return node_.at(key); }
  const json& raw(const std::string& key) const {
    node_.at(key);  // "missing key" if absent
    return value_.at(key);
  }
  std::string path(const std::string& key) const { return join(path_, key); }
  const std::string& here() const { return path_; }
  [[noreturn]] void fail(const std::string& key, const std::string& problem) const {
    io::JsonNode(value_, ctx_.source, path(key)).fail(problem);
  }
  [[noreturn]] void fail_here(const std::string& problem) const { node_.fail(problem); }

  double number(const std::string& key) const { return at(key).number(); }
  double positive(const std::string& key) const {
    const double x = number(key);
    if (!(x > 0.0)) fail(key, "must be > 0, found " + io::format_double(x));
    return x;
  }
  double positive_or(const std::string& key, double fallback) const { return has(key) ? positive(key) : fallback; }
  long long integer(const std::string& key, long long min) const {
    const double x = number(key);
    if (x != std::floor(x) || std::abs(x) > 1e15) fail(key, "must be an integer, found " + io::format_double(x));
    if (x < static_cast<double>(min))
      fail(key, "must be >= " + std::to_string(min) + ", found " + io::format_double(x));
    return static_cast<long long>(x);
  }
  std::string string(const std::string& key) const { return at(key).string(); }
  std::string choice(const std::string& key, const std::vector<std::string>& choices) const {
    return at(key).choice(choices);
  }
  std::string choice_or(const std::string& key, const std::vector<std::string>& choices,
                        const std::string& fallback) const {
    return has(key) ? choice(key, choices) : fallback;
  }
  /// Existing file named relative to the case folder.
  std::filesystem::path file(const std::string& key) const {
    const std::string name = string(key);
    if (name.empty()) fail(key, "must name a file");
    const std::filesystem::path p = ctx_.folder / name;
    if (!std::filesystem::is_regular_file(p)) fail(key, "file not found: " + p.string());
    return p;
  }
  /// Array of exactly `n` finite numbers.
  std::vector<double> numbers(const std::string& key, std::size_t n_min, std::size_t n_max) const {
    const io::JsonNode array = at(key);
    const std::size_t n = array.expect_array(n_min, n_max);
    std::vector<double> out(n);
    for (std::size_t i = 0; i < n; ++i) out[i] = array[i].number();
    return out;
  }
  const Context& ctx() const { return ctx_; }

 private:
  const json& value_;
  const Context& ctx_;
  std::string path_;
  io::JsonNode node_;
};

mesh::ElementType element_type(const std::string& name) {
  if (name == "hex8") return mesh::ElementType::hex8;
  if (name == "tet4") return mesh::ElementType::tet4;
  return mesh::ElementType::tet10;
}

mesh::AxisGrading parse_axis_grading(const Obj& o) {
  mesh::AxisGrading g;
  g.ratio = o.positive("ratio");
  g.kind = mesh::AxisGrading::Kind::geometric;
  if (o.has("focus_mm")) {
    g.kind = mesh::AxisGrading::Kind::focus;
    g.focus = o.number("focus_mm");
  }
  return g;
}

GenerateMeshSpec parse_generate(const Obj& o) {
  GenerateMeshSpec g;
  g.type = element_type(o.choice("type", {"hex8", "tet4", "tet10"}));
  const auto box = o.numbers("box_mm", 6, 6);
  for (int axis = 0; axis < 3; ++axis) {
    g.low[axis] = box[2 * axis];
    g.high[axis] = box[2 * axis + 1];
    if (!(g.low[axis] < g.high[axis]))
      o.fail("box_mm", "must be [x0, x1, y0, y1, z0, z1] with x0 < x1, y0 < y1, z0 < z1");
  }
  const io::JsonNode n = o.at("elements");
  n.expect_array(3, 3);
  for (int axis = 0; axis < 3; ++axis) {
    const double x = n[axis].number();
    if (x != std::floor(x) || x < 1 || x > 1e6) n[axis].fail("must be an integer >= 1");
    g.elements[axis] = static_cast<int>(x);
  }
  if (o.has("grading")) {
    const Obj grading(o.raw("grading"), o.ctx(), o.path("grading"), {"x", "y", "z"});
    const char* axes[] = {"x", "y", "z"};
    for (int axis = 0; axis < 3; ++axis) {
      if (!grading.has(axes[axis])) continue;
      const Obj a(grading.raw(axes[axis]), o.ctx(), grading.path(axes[axis]), {"ratio", "focus_mm"});
      g.grading[axis] = parse_axis_grading(a);
      if (g.grading[axis].kind == mesh::AxisGrading::Kind::focus &&
          (g.grading[axis].focus < g.low[axis] || g.grading[axis].focus > g.high[axis]))
        a.fail("focus_mm", "must lie inside the box along " + std::string(axes[axis]));
    }
  }
  return g;
}

MeshSpec parse_mesh(const Obj& o) {
  MeshSpec m;
  const int sources = int(o.has("generate")) + int(o.has("inp")) + int(o.has("stl"));
  if (sources != 1) o.fail_here("must contain exactly one of \"generate\", \"inp\", \"stl\"");
  bool hex_possible = true;
  if (o.has("generate")) {
    m.source = MeshSpec::Source::generate;
    m.generate = parse_generate(Obj(o.raw("generate"), o.ctx(), o.path("generate"),
                                    {"type", "box_mm", "elements", "grading"}));
    hex_possible = m.generate.type == mesh::ElementType::hex8;
  } else if (o.has("inp")) {
    m.source = MeshSpec::Source::inp;
    m.inp_file = o.file("inp");
  } else {
    m.source = MeshSpec::Source::stl;
    hex_possible = false;
    m.stl.file = o.file("stl");
    m.stl.max_volume = o.positive("max_volume_mm3");
    m.stl.quadratic = o.choice_or("type", {"tet4", "tet10"}, "tet4") == "tet10";
    m.stl.max_radius_edge = o.positive_or("max_radius_edge", 1.5);
    m.stl.min_dihedral = o.has("min_dihedral_deg") ? o.number("min_dihedral_deg") : 0.0;
    if (m.stl.min_dihedral < 0.0 || m.stl.min_dihedral >= 70.0)
      o.fail("min_dihedral_deg", "must be in [0, 70) degrees");
  }
  if (o.has("type") && !o.has("stl")) o.fail("type", "is an option of \"stl\" meshes (use generate.type)");
  for (const char* k : {"max_volume_mm3", "max_radius_edge", "min_dihedral_deg"})
    if (o.has(k) && !o.has("stl")) o.fail(k, "is an option of \"stl\" meshes only");
  m.formulation = o.choice_or("formulation", {"full", "fbar"}, "full") == "fbar" ? HexFormulation::fbar
                                                                                 : HexFormulation::full;
  if (m.formulation == HexFormulation::fbar && !hex_possible)
    o.fail("formulation", "\"fbar\" applies to hex8 elements only");
  return m;
}

/// {"type": "sine", "frequency_Hz": f, "start_s"?: t0, "time"?: ...} (case_spec.hpp).
Amplitude parse_sine_amplitude(const Obj& o) {
  Amplitude a;
  a.kind = Amplitude::Kind::sine;
  a.frequency = o.positive("frequency_Hz");
  if (o.has("start_s")) a.start = o.number("start_s");
  if (a.start < 0.0) o.fail("start_s", "must be >= 0, found " + io::format_double(a.start));
  a.total_time = o.choice_or("time", {"step", "total"}, "step") == "total";
  return a;
}

Amplitude parse_amplitude(const Obj& o) {
  if (o.has("type")) o.choice("type", {"tabular"});  // "sine" is dispatched by the caller
  Amplitude a;
  a.time = o.numbers("time_s", 1, 1000000);
  a.value = o.numbers("value", 1, 1000000);
  if (a.value.size() != a.time.size())
    o.fail("value", "must have as many entries as time_s (" + std::to_string(a.time.size()) + "), found " +
                        std::to_string(a.value.size()));
  for (std::size_t i = 0; i < a.time.size(); ++i) {
    if (a.time[i] < 0.0) o.fail("time_s", "must be >= 0, found " + io::format_double(a.time[i]));
    if (i > 0 && !(a.time[i] > a.time[i - 1]))
      o.fail("time_s", "must be strictly increasing (entry " + std::to_string(i) + ")");
  }
  a.total_time = o.choice_or("time", {"step", "total"}, "step") == "total";
  return a;
}

IncrementSpec parse_increment(const Obj* o, double period) {
  IncrementSpec inc{period, 1e-5 * period, period, 100};
  if (!o) return inc;
  if (o->has("fixed")) inc.fixed = o->at("fixed").boolean();
  inc.initial = o->positive_or("initial_s", period);
  inc.min = o->positive_or("min_s", std::min(1e-5 * period, inc.initial));
  inc.max = o->positive_or("max_s", period);
  if (o->has("max_increments")) inc.max_increments = static_cast<int>(o->integer("max_increments", 1));
  if (inc.initial > period) o->fail("initial_s", "must not exceed the step's time_period_s");
  if (inc.min > inc.initial) o->fail("min_s", "must not exceed initial_s");
  if (inc.initial > inc.max) o->fail("max_s", "must be >= initial_s");
  return inc;
}

BoundarySpec parse_boundary(const Obj& o, const CaseSpec& spec) {
  BoundarySpec bc;
  bc.key = o.here();
  bc.set = o.string("set");
  if (!spec.sets.count(bc.set) && spec.mesh.source != MeshSpec::Source::inp)
    o.fail("set", "unknown set \"" + bc.set + "\"" + io::did_you_mean(bc.set, [&] {
      std::vector<std::string> names;
      for (const auto& [name, ignored] : spec.sets) names.push_back(name);
      return names;
    }()) + " (define it under \"sets\")");
  const std::string type = o.choice_or("type", {"displacement", "symmetry_x", "symmetry_y", "symmetry_z", "fixed"},
                                       "displacement");
  if (type == "displacement") {
    const std::string dof = o.choice("dof", {"x", "y", "z", "xy", "xz", "yz", "xyz"});
    for (char c : dof) bc.dofs[c - 'x'] = true;
    bc.value = o.number("value_mm");
    if (o.has("amplitude")) {
      bc.amplitude = o.string("amplitude");
      if (!spec.amplitudes.count(*bc.amplitude))
        o.fail("amplitude", "unknown amplitude \"" + *bc.amplitude + "\" (define it under \"amplitudes\")");
    }
    return bc;
  }
  for (const char* k : {"dof", "value_mm", "amplitude"})
    if (o.has(k)) o.fail(k, "does not apply to a \"" + type + "\" condition");
  if (type == "fixed") {
    bc.kind = BoundarySpec::Kind::fixed;
    bc.dofs = {true, true, true};
  } else {
    bc.kind = BoundarySpec::Kind::symmetry;
    bc.dofs[type.back() - 'x'] = true;
  }
  return bc;
}

HistoryQuantity history_quantity(const io::JsonNode& n) {
  const std::string q = n.choice({"U1", "U2", "U3", "RF1", "RF2", "RF3"});
  const int component = q.back() - '1';
  return static_cast<HistoryQuantity>((q[0] == 'R' ? 3 : 0) + component);
}

OutputSpec parse_output(const Obj& o, const CaseSpec& spec) {
  OutputSpec out;
  if (o.has("frames_every_s") && o.has("frame_every_increments"))
    o.fail("frames_every_s", "give either frames_every_s or frame_every_increments, not both");
  if (o.has("frames_every_s")) out.frames_every = o.positive("frames_every_s");
  if (o.has("frame_every_increments"))
    out.frame_every_increments = static_cast<int>(o.integer("frame_every_increments", 1));
  if (o.has("history")) {
    const io::JsonNode list = o.at("history");
    const std::size_t n = list.expect_array(0, 10000);
    for (std::size_t i = 0; i < n; ++i) {
      const std::string path = o.path("history") + "[" + std::to_string(i) + "]";
      const Obj h(o.raw("history")[i], o.ctx(), path, {"set", "quantities"});
      HistoryRequest request;
      request.set = h.string("set");
      if (!spec.sets.count(request.set) && spec.mesh.source != MeshSpec::Source::inp)
        h.fail("set", "unknown set \"" + request.set + "\" (define it under \"sets\")");
      const io::JsonNode q = h.at("quantities");
      const std::size_t nq = q.expect_array(1, 6);
      for (std::size_t k = 0; k < nq; ++k) request.quantities.push_back(history_quantity(q[k]));
      out.history.push_back(std::move(request));
    }
  }
  return out;
}

Vec3 vec3(const Obj& o, const std::string& key, std::size_t n = 3) {
  const auto v = o.numbers(key, n, n);
  Vec3 out = Vec3::Zero();
  for (std::size_t i = 0; i < n; ++i) out(static_cast<int>(i)) = v[i];
  return out;
}

/// "indenter": the keys allowed depend on "type" (contact_spec.hpp).
IndenterSpec parse_indenter(const json& value, const Context& ctx, const std::string& path) {
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
    const Obj p = allowed({"lowest_z_mm", "spacing_mm", "a_mm", "b_mm", "c_mm", "blend_mm", "plate_x_mm",
                           "plate_y_mm", "plate_edge_mm", "centre_mm"});
    in.type = IndenterSpec::Type::sitbar;
    SitBarShape& s = in.sitbar;
    if (p.has("lowest_z_mm")) s.lowest_z = p.number("lowest_z_mm");
    if (p.has("spacing_mm")) s.it_spacing = p.number("spacing_mm");
    if (s.it_spacing < 0.0) p.fail("spacing_mm", "must be >= 0");
    s.a = p.positive_or("a_mm", s.a), s.b = p.positive_or("b_mm", s.b), s.c = p.positive_or("c_mm", s.c);
    s.blend = p.positive_or("blend_mm", s.blend);
    s.plate_x = p.positive_or("plate_x_mm", s.plate_x), s.plate_y = p.positive_or("plate_y_mm", s.plate_y);
    s.plate_edge = p.positive_or("plate_edge_mm", s.plate_edge);
    if (2 * s.plate_edge >= std::min(s.plate_x, s.plate_y)) p.fail("plate_edge_mm", "must be less than half the plate size");
    if (p.has("centre_mm")) {
      const Vec3 c = vec3(p, "centre_mm", 2);
      s.centre_x = c.x(), s.centre_y = c.y();
    }
  } else {
    const Obj p = allowed({"file"});
    in.type = IndenterSpec::Type::stl, in.stl_file = p.file("file");
  }
  return in;
}

ContactSpec parse_contact(const Obj& o, const CaseSpec& spec, const StepSpec& step) {
  ContactSpec c;
  c.key = o.here();
  c.name = o.string("name");
  if (c.name.empty() || c.name.find_first_of(" ,\"/") != std::string::npos)
    o.fail("name", "must be a non-empty name without spaces, commas, quotes or slashes");
  for (const ContactSpec& other : step.contact)
    if (other.name == c.name) o.fail("name", "duplicate contact name \"" + c.name + "\" in this step");
  c.set = o.string("set");
  if (!spec.sets.count(c.set) && spec.mesh.source != MeshSpec::Source::inp)
    o.fail("set", "unknown set \"" + c.set + "\" (define it under \"sets\")");
  c.indenter = parse_indenter(o.raw("indenter"), o.ctx(), o.path("indenter"));
  c.motion = vec3(o, "motion_mm");
  if (o.has("amplitude")) {
    c.amplitude = o.string("amplitude");
    if (!spec.amplitudes.count(*c.amplitude))
      o.fail("amplitude", "unknown amplitude \"" + *c.amplitude + "\" (define it under \"amplitudes\")");
  }
  ContactParameters& p = c.parameters;
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
  if (o.has("max_augmentations")) p.max_augmentations = static_cast<int>(o.integer("max_augmentations", 0));
  c.force_factor = o.positive_or("force_factor", 1.0);
  return c;
}

/// "damping" and "newmark" of a dynamic step (case_spec.hpp).
DynamicSpec parse_dynamic(const Obj& o) {
  DynamicSpec d;
  d.key = o.here();
  auto non_negative = [](const Obj& x, const std::string& key) {
    const double v = x.number(key);
    if (!(v >= 0.0)) x.fail(key, "must be >= 0, found " + io::format_double(v));
    return v;
  };
  if (o.has("damping")) {
    const Obj damping(o.raw("damping"), o.ctx(), o.path("damping"), {"rayleigh_alpha_1_s", "rayleigh_beta_s"});
    if (damping.has("rayleigh_alpha_1_s")) d.rayleigh_alpha = non_negative(damping, "rayleigh_alpha_1_s");
    if (damping.has("rayleigh_beta_s")) d.rayleigh_beta = non_negative(damping, "rayleigh_beta_s");
  }
  if (o.has("newmark")) {
    const Obj newmark(o.raw("newmark"), o.ctx(), o.path("newmark"), {"alpha", "gamma", "beta"});
    if (newmark.has("alpha")) {
      d.alpha = newmark.number("alpha");
      if (!(d.alpha >= -1.0 / 3.0 && d.alpha <= 0.0))
        newmark.fail("alpha", "HHT alpha must be in [-1/3, 0] (ABAQUS: -0.05 moderate, -1/3 most dissipation), found " +
                                  io::format_double(d.alpha));
      d.gamma = 0.5 * (1.0 - 2.0 * d.alpha);
    }
    if (newmark.has("gamma")) d.gamma = newmark.number("gamma");
    if (!(d.gamma >= 0.5 && d.gamma <= 1.5))
      newmark.fail("gamma", "must be in [0.5, 1.5] (gamma < 1/2 amplifies the response: unstable), found " +
                                io::format_double(d.gamma));
    const double beta_min = 0.25 * (d.gamma + 0.5) * (d.gamma + 0.5);
    d.beta = newmark.has("beta") ? newmark.number("beta") : beta_min;
    if (!(d.beta >= beta_min * (1.0 - 1e-12)) || d.beta > 1.0)
      newmark.fail("beta", "must be in [(gamma + 1/2)^2 / 4, 1] = [" + io::format_double(beta_min) +
                               ", 1] for unconditional stability, found " + io::format_double(d.beta));
  }
  return d;
}

StepSpec parse_step(const Obj& o, const CaseSpec& spec) {
  StepSpec step;
  step.name = o.string("name");
  const std::string type = o.at("type").string();
  if (type == "steady_state") {  // a linear perturbation step: solver/dynamics/steady_state_spec.hpp
    for (const char* k : {"long_term", "time_period_s", "increment", "boundary", "contact", "output", "damping", "newmark"})
      if (o.has(k)) o.fail(k, "does not apply to a \"steady_state\" step (see its \"steady_state\" object)");
    step.type = StepSpec::Type::steady_state;
    step.steady_state = dynamics::parse_steady_state_spec(
        o.raw("steady_state"), o.ctx().source, o.path("steady_state"),
        [&](const std::string& set) { return spec.sets.count(set) > 0 || spec.mesh.source == MeshSpec::Source::inp; },
        spec.steps.empty());
    return step;
  }
  if (o.has("steady_state")) o.fail("steady_state", "applies to \"steady_state\" steps only");
  const std::string kind = o.choice("type", {"static", "visco", "dynamic"});
  step.type = kind == "visco" ? StepSpec::Type::visco : kind == "dynamic" ? StepSpec::Type::dynamic : StepSpec::Type::static_;
  if (step.type == StepSpec::Type::dynamic) step.dynamic = parse_dynamic(o);
  for (const char* k : {"damping", "newmark"})
    if (o.has(k) && step.type != StepSpec::Type::dynamic) o.fail(k, "applies to \"dynamic\" steps only");
  if (o.has("long_term")) {
    if (step.type != StepSpec::Type::static_) o.fail("long_term", "applies to \"static\" steps only");
    step.long_term = o.at("long_term").boolean();
  }
  step.period = o.positive("time_period_s");
  if (o.has("increment")) {
    const std::vector<std::string> keys{"initial_s", "min_s", "max_s", "max_increments", "fixed"};
    const Obj inc(o.raw("increment"), o.ctx(), o.path("increment"), keys);
    step.increment = parse_increment(&inc, step.period);
  } else {
    step.increment = parse_increment(nullptr, step.period);
  }
  const io::JsonNode list = o.at("boundary");
  const std::size_t n = list.expect_array(0, 100000);
  for (std::size_t i = 0; i < n; ++i) {
    const std::string path = o.path("boundary") + "[" + std::to_string(i) + "]";
    step.boundary.push_back(parse_boundary(
        Obj(o.raw("boundary")[i], o.ctx(), path, {"set", "type", "dof", "value_mm", "amplitude"}), spec));
  }
  if (o.has("contact")) {
    const io::JsonNode contacts = o.at("contact");
    const std::size_t nc = contacts.expect_array(0, 100);
    for (std::size_t i = 0; i < nc; ++i)
      step.contact.push_back(parse_contact(
          Obj(o.raw("contact")[i], o.ctx(), o.path("contact") + "[" + std::to_string(i) + "]",
              {"name", "set", "indenter", "motion_mm", "amplitude", "penalty_MPa_per_mm",
               "tangential_penalty_MPa_per_mm", "friction", "tolerance_mm", "smoothing_mm", "max_augmentations", "force_factor"}),
          spec, step));
  }
  if (o.has("output")) {
    const Obj out(o.raw("output"), o.ctx(), o.path("output"), {"frames_every_s", "frame_every_increments", "history"});
    step.output = parse_output(out, spec);
  }
  return step;
}

SolverSpec parse_solver(const Obj& o) {
  SolverSpec s;
  if (o.has("threads")) s.threads = static_cast<int>(o.integer("threads", 0));
  const std::string ls = o.choice_or("linear_solver", {"auto", "cholmod", "umfpack"}, "auto");
  s.linear_solver = ls == "cholmod"   ? SolverSpec::LinearSolver::cholmod
                    : ls == "umfpack" ? SolverSpec::LinearSolver::umfpack
                                      : SolverSpec::LinearSolver::automatic;
  s.residual_tolerance = o.positive_or("residual_tolerance", s.residual_tolerance);
  s.correction_tolerance = o.positive_or("correction_tolerance", s.correction_tolerance);
  if (o.has("max_iterations")) s.max_iterations = static_cast<int>(o.integer("max_iterations", 1));
  if (o.has("max_cutbacks")) s.max_cutbacks = static_cast<int>(o.integer("max_cutbacks", 0));
  s.cutback_factor = o.positive_or("cutback_factor", s.cutback_factor);
  if (s.cutback_factor >= 1.0) o.fail("cutback_factor", "must be < 1");
  s.growth_factor = o.positive_or("growth_factor", s.growth_factor);
  if (s.growth_factor < 1.0) o.fail("growth_factor", "must be >= 1");
  s.tangent_reuse = o.choice_or("newton", {"full", "modified"}, "full") == "modified";
  s.max_contraction = o.positive_or("max_contraction", s.max_contraction);
  if (s.max_contraction >= 1.0) o.fail("max_contraction", "must be < 1");
  return s;
}

/// io::parse_json, plus numbers too large for a double (nlohmann out_of_range 406, which
/// io::parse_json does not catch) reported as InputError with line and the key before them.
json parse_json_finite(const std::string& text, const std::string& source) {
  try {
    return io::parse_json(text, source);
  } catch (const json::out_of_range& e) {
    const std::string what = e.what();
    const auto open = what.find('\''), close = what.rfind('\'');
    const std::string token = open < close ? what.substr(open + 1, close - open - 1) : std::string{};
    const std::size_t at = token.empty() ? std::string::npos : text.find(token);
    std::string where;
    if (at != std::string::npos) {
      const std::string head = text.substr(0, at);
      where = ":" + std::to_string(1 + std::count(head.begin(), head.end(), '\n'));
      const auto colon = head.rfind(':');
      const auto key_end = colon == std::string::npos ? std::string::npos : head.rfind('"', colon);
      const auto key_begin = key_end == std::string::npos || key_end == 0 ? std::string::npos : head.rfind('"', key_end - 1);
      if (key_begin != std::string::npos)
        where += ": key '" + head.substr(key_begin + 1, key_end - key_begin - 1) + "'";
    }
    throw InputError(source + where + ": invalid JSON: number '" + token + "' is out of range (numbers must be finite)");
  }
}

}  // namespace

CaseSpec parse_case_json(const std::string& text, const std::filesystem::path& file) {
  const Context ctx{file.string(), file.parent_path()};
  const json root = parse_json_finite(text, ctx.source);
  const Obj top(root, ctx, "", {"description", "mesh", "material", "sets", "amplitudes", "steps", "solver"});
  CaseSpec spec;
  spec.file = file;
  if (top.has("description")) spec.description = top.string("description");
  spec.mesh = parse_mesh(Obj(top.raw("mesh"), ctx, "mesh", {"generate", "inp", "stl", "formulation", "type",
                                                            "max_volume_mm3", "max_radius_edge", "min_dihedral_deg"}));
  spec.material_file = Obj(top.raw("material"), ctx, "material", {"file"}).file("file");
  if (top.has("sets")) {
    const json& sets = top.raw("sets");
    if (!sets.is_object()) top.fail("sets", "must be an object {\"name\": \"selector\", ...}");
    for (const auto& [name, value] : sets.items()) {
      const std::string selector = io::JsonNode(value, ctx.source, "sets." + name).string();
      mesh::parse_selector(selector, ctx.source + ": sets." + name);  // syntax check now
      spec.sets[name] = selector;
    }
  }
  if (top.has("amplitudes")) {
    const json& amplitudes = top.raw("amplitudes");
    if (!amplitudes.is_object()) top.fail("amplitudes", "must be an object {\"name\": {...}, ...}");
    for (const auto& [name, value] : amplitudes.items()) {
      const std::string path = "amplitudes." + name;
      const bool sine = value.is_object() && value.contains("type") &&
                        io::JsonNode(value, ctx.source, path).at("type").choice({"tabular", "sine"}) == "sine";
      spec.amplitudes[name] = sine ? parse_sine_amplitude(Obj(value, ctx, path, {"type", "frequency_Hz", "start_s", "time"}))
                                   : parse_amplitude(Obj(value, ctx, path, {"type", "time_s", "value", "time"}));
    }
  }
  const io::JsonNode steps = top.at("steps");
  const std::size_t n = steps.expect_array(1, 10000);
  for (std::size_t i = 0; i < n; ++i)
    spec.steps.push_back(parse_step(Obj(top.raw("steps")[i], ctx, "steps[" + std::to_string(i) + "]",
                                        {"name", "type", "long_term", "time_period_s", "increment", "boundary",
                                         "contact", "output", "steady_state", "damping", "newmark"}),
                                    spec));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < i; ++k)
      if (spec.steps[i].name == spec.steps[k].name)
        io::JsonNode(root, ctx.source, "steps[" + std::to_string(i) + "].name")
            .fail("duplicate step name \"" + spec.steps[i].name + "\"");
  if (top.has("solver"))
    spec.solver = parse_solver(Obj(top.raw("solver"), ctx, "solver",
                                   {"threads", "linear_solver", "residual_tolerance", "correction_tolerance",
                                    "max_iterations", "max_cutbacks", "cutback_factor", "growth_factor", "newton",
                                    "max_contraction"}));
  return spec;
}

CaseSpec read_case_file(const std::filesystem::path& file) {
  return parse_case_json(io::read_text_file(file.string()), file);
}

}  // namespace cushion::solver
