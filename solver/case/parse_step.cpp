// The "steps" part of the case grammar (case_spec.hpp): step type, increments, boundary conditions,
// output requests; contact, dynamic and steady-state keys are read by their own files.
#include <algorithm>

#include "io/text_support.hpp"
#include "solver/case/case_parts.hpp"

namespace cushion::solver::case_parse {

namespace {

IncrementSpec parse_increment(const Obj* o, double period) {
  IncrementSpec inc{period, 1e-5 * period, period, 100};
  if (!o) return inc;
  if (o->has("fixed")) inc.fixed = o->at("fixed").boolean();
  inc.initial = o->positive_or("initial_s", period);
  inc.min = o->positive_or("min_s", std::min(1e-5 * period, inc.initial));
  inc.max = o->positive_or("max_s", period);
  if (o->has("max_increments")) inc.max_increments = o->integer("max_increments", 1, 10000000);
  if (inc.initial > period) o->fail("initial_s", "must not exceed the step's time_period_s");
  if (inc.min > inc.initial) o->fail("min_s", "must not exceed initial_s");
  if (inc.initial > inc.max) o->fail("max_s", "must be >= initial_s");
  return inc;
}

BoundarySpec parse_boundary(const Obj& o, const CaseSpec& spec) {
  BoundarySpec bc;
  bc.key = o.here();
  bc.set = o.string("set");
  check_set_defined(o, "set", bc.set, spec);
  const std::string type = o.choice_or("type", {"displacement", "symmetry_x", "symmetry_y", "symmetry_z", "fixed"},
                                       "displacement");
  if (type == "displacement") {
    const std::string dof = o.choice("dof", {"x", "y", "z", "xy", "xz", "yz", "xyz"});
    for (char c : dof) bc.dofs[c - 'x'] = true;
    bc.value = o.number("value_mm");
    if (o.has("amplitude")) {
      bc.amplitude = o.string("amplitude");
      check_amplitude_defined(o, "amplitude", *bc.amplitude, spec);
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
    out.frame_every_increments = o.integer("frame_every_increments", 1, 10000000);
  if (!o.has("history")) return out;
  const std::size_t n = o.at("history").expect_array(0, 10000);
  for (std::size_t i = 0; i < n; ++i) {
    const Obj h = o.element("history", i, {"set", "quantities"});
    HistoryRequest request;
    request.set = h.string("set");
    check_set_defined(h, "set", request.set, spec);
    const io::JsonNode q = h.at("quantities");
    const std::size_t nq = q.expect_array(1, 6);
    for (std::size_t k = 0; k < nq; ++k) request.quantities.push_back(history_quantity(q[k]));
    out.history.push_back(std::move(request));
  }
  return out;
}

/// A "steady_state" step: only name, type and the "steady_state" object (steady_state_spec.hpp).
StepSpec parse_steady_state_step(const Obj& o, const CaseSpec& spec, StepSpec step) {
  for (const char* k :
       {"long_term", "time_period_s", "increment", "boundary", "contact", "output", "damping", "newmark"})
    if (o.has(k)) o.fail(k, "does not apply to a \"steady_state\" step (see its \"steady_state\" object)");
  step.type = StepSpec::Type::steady_state;
  o.raw("steady_state");  // "missing key" first
  if (spec.steps.empty())
    o.fail("steady_state",
           "a steady_state step needs a preceding static or visco step (its end state is the base state)");
  step.steady_state = parse_steady_state(
      o.child("steady_state", {"frequencies", "frequencies_Hz", "excitation", "held", "indenters", "measure",
                               "damping", "base_stress", "area_mm2", "thickness_mm", "output", "linear_solver",
                               "gmres_tolerance"}),
      spec);
  return step;
}

/// The type-specific keys of a static, visco or dynamic step.
void parse_step_type(const Obj& o, StepSpec& step) {
  const std::string kind = o.choice("type", {"static", "visco", "dynamic"});
  step.type = kind == "visco"     ? StepSpec::Type::visco
              : kind == "dynamic" ? StepSpec::Type::dynamic
                                  : StepSpec::Type::static_;
  if (step.type == StepSpec::Type::dynamic) step.dynamic = parse_dynamic(o);
  for (const char* k : {"damping", "newmark"})
    if (o.has(k) && step.type != StepSpec::Type::dynamic) o.fail(k, "applies to \"dynamic\" steps only");
  if (o.has("long_term")) {
    if (step.type != StepSpec::Type::static_) o.fail("long_term", "applies to \"static\" steps only");
    step.long_term = o.at("long_term").boolean();
  }
}

}  // namespace

void check_set_defined(const Obj& o, const std::string& key, const std::string& set, const CaseSpec& spec,
                       const std::string& hint) {
  if (spec.sets.count(set) || spec.mesh.source == MeshSpec::Source::inp) return;
  std::vector<std::string> names;
  for (const auto& [name, ignored] : spec.sets) names.push_back(name);
  o.fail(key, "unknown set \"" + set + "\"" + io::did_you_mean(set, names) + " (" + hint + ")");
}

void check_amplitude_defined(const Obj& o, const std::string& key, const std::string& name, const CaseSpec& spec) {
  if (!spec.amplitudes.count(name))
    o.fail(key, "unknown amplitude \"" + name + "\" (define it under \"amplitudes\")");
}

StepSpec parse_step(const Obj& o, const CaseSpec& spec) {
  StepSpec step;
  step.name = o.string("name");
  if (o.at("type").string() == "steady_state") return parse_steady_state_step(o, spec, std::move(step));
  if (o.has("steady_state")) o.fail("steady_state", "applies to \"steady_state\" steps only");
  parse_step_type(o, step);
  step.period = o.positive("time_period_s");
  if (o.has("increment")) {
    const Obj inc = o.child("increment", {"initial_s", "min_s", "max_s", "max_increments", "fixed"});
    step.increment = parse_increment(&inc, step.period);
  } else {
    step.increment = parse_increment(nullptr, step.period);
  }
  const std::size_t n = o.at("boundary").expect_array(0, 100000);
  for (std::size_t i = 0; i < n; ++i)
    step.boundary.push_back(
        parse_boundary(o.element("boundary", i, {"set", "type", "dof", "value_mm", "amplitude"}), spec));
  const std::size_t nc = o.has("contact") ? o.at("contact").expect_array(0, 100) : 0;
  for (std::size_t i = 0; i < nc; ++i)
    step.contact.push_back(parse_contact(
        o.element("contact", i,
                  {"name", "set", "indenter", "motion_mm", "amplitude", "penalty_MPa_per_mm",
                   "tangential_penalty_MPa_per_mm", "friction", "tolerance_mm", "smoothing_mm", "max_augmentations",
                   "force_factor", "pressure_overclosure"}),
        spec, step));
  if (o.has("output"))
    step.output = parse_output(o.child("output", {"frames_every_s", "frame_every_increments", "history"}), spec);
  return step;
}

}  // namespace cushion::solver::case_parse
