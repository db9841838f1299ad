// Steps, conditions and output requests of a deck (deck_parts.hpp): *AMPLITUDE, *BOUNDARY, *CLOAD,
// *STEP, *STATIC, *VISCO, *END STEP, *NODE PRINT, *EL PRINT, *NODE FILE, *EL FILE. Conditions persist
// from step to step (ABAQUS OP=MOD) and OP=NEW removes those in effect; each StepSpec gets the
// complete list in effect at its *END STEP, as a case file's step does.
#include <algorithm>
#include <array>
#include <cctype>

#include "io/input_error.hpp"
#include "io/text_support.hpp"
#include "solver/deck/deck_parts.hpp"
#include "solver/dynamics/modes.hpp"

namespace cushion::solver::deck {

namespace {

StepSpec& open_step(State& s, const Block& b) {
  if (!s.step) fail(b, b.keyword, "must come inside a *STEP");
  return s.out.spec.steps[*s.step];
}

/// Degree of freedom 1..3 as a component 0..2 (rotations 4..6 refused).
int component(const Block& b, const Line& line, const std::string& field) {
  const int dof = integer(b, line, field);
  if (dof >= 4 && dof <= 6) fail(b, line, "degree of freedom " + field + " is a rotation: solid elements have none");
  if (dof < 1 || dof > 6) fail(b, line, "degree of freedom must be 1, 2 or 3, found " + field);
  return dof - 1;
}

/// AMPLITUDE= of *BOUNDARY / *CLOAD: the (upper-case) name of a defined amplitude.
std::optional<std::string> amplitude_parameter(const State& s, const Block& b) {
  const auto name = parameter(b, "AMPLITUDE");
  if (!name) return std::nullopt;
  if (!s.step) fail(b, b.keyword, "AMPLITUDE= is only allowed inside a *STEP");
  if (!s.out.spec.amplitudes.count(io::upper_case(*name))) fail(b, b.keyword, "unknown amplitude '" + *name + "'");
  return io::upper_case(*name);
}

/// OP=MOD (default) or OP=NEW (true: the conditions in effect are removed first).
bool op_new(const State& s, const Block& b) {
  const auto op = parameter(b, "OP");
  if (!op || io::upper_case(*op) == "MOD") return false;
  if (io::upper_case(*op) != "NEW") fail(b, b.keyword, "OP must be MOD or NEW");
  if (!s.step) fail(b, b.keyword, "OP=NEW is only allowed inside a *STEP");
  return true;
}

/// Components a *BOUNDARY type word fixes (solids: symmetry planes fix one translation).
std::optional<std::array<bool, 3>> boundary_type(const std::string& word) {
  const std::string w = io::upper_case(word);
  if (w == "ENCASTRE" || w == "PINNED") return std::array<bool, 3>{true, true, true};
  if (w == "XSYMM") return std::array<bool, 3>{true, false, false};
  if (w == "YSYMM") return std::array<bool, 3>{false, true, false};
  if (w == "ZSYMM") return std::array<bool, 3>{false, false, true};
  return std::nullopt;
}

/// Adds a one-component condition, replacing one in effect on the same set and component.
void put_boundary(State& s, BoundarySpec bc, int c) {
  bc.dofs = {c == 0, c == 1, c == 2};
  auto same = [&](const BoundarySpec& o) { return o.set == bc.set && o.dofs[c]; };
  s.boundary.erase(std::remove_if(s.boundary.begin(), s.boundary.end(), same), s.boundary.end());
  s.boundary.push_back(std::move(bc));
}

/// "initial, total, min, max" of *STATIC / *VISCO (ABAQUS defaults: total 1, initial = total,
/// min = min(initial, 1e-5 total), max = total).
void read_increments(const Block& b, StepSpec& step) {
  if (b.data.size() > 1) fail(b, b.data[1], "expected one data line 'initial, total, min, max'");
  std::vector<std::string> f = b.data.empty() ? std::vector<std::string>{} : mesh::inp_fields(b.data.front().text);
  if (f.size() > 4) fail(b, b.data.front(), "expected 'initial, total, min, max', got " + std::to_string(f.size()) + " fields");
  f.resize(4);
  const Line& line = b.data.empty() ? b.keyword : b.data.front();
  auto value = [&](int k, double fallback) { return f[k].empty() ? fallback : number(b, line, f[k]); };
  step.period = value(1, 1.0);
  step.increment.initial = value(0, step.period);
  step.increment.min = value(2, std::min(step.increment.initial, 1e-5 * step.period));
  step.increment.max = value(3, step.period);
  const IncrementSpec& i = step.increment;
  if (!(step.period > 0.0) || !(i.min > 0.0) || !(i.min <= i.initial) || !(i.initial <= i.max) ||
      !(i.initial <= step.period))
    fail(b, line, "need total > 0 and 0 < min <= initial <= max, initial <= total");
}

void procedure(State& s, const Block& b, StepSpec::Type type) {
  StepSpec& step = open_step(s, b);
  if (s.procedure) fail(b, b.keyword, "the step already has its procedure");
  s.procedure = true;
  step.type = type;
  read_increments(b, step);
}

/// Output variables of a print request: the supported ones; the others are warned about and skipped.
std::vector<std::string> print_variables(State& s, const Block& b, const std::vector<std::string>& supported) {
  std::vector<std::string> out;
  for (const Line& line : b.data)
    for (const std::string& f : mesh::inp_fields(line.text)) {
      const std::string v = io::upper_case(f);
      if (std::find(supported.begin(), supported.end(), v) != supported.end()) out.push_back(v);
      else if (!v.empty())
        s.out.warnings.push_back(where(line) + ": *" + b.name + ": output variable " + f + " skipped (cushion prints " +
                                 (supported.size() > 1 ? supported[0] + " and " + supported[1] : supported[0]) +
                                 " here; frames hold more)");
    }
  return out;
}

/// Output parameters: TIME POINTS= adds its times to the step's frame times (increments end on them, as in
/// CalculiX); the others but the set are warned about and skipped.
void output_parameters(State& s, const Block& b, const std::string& set_key) {
  for (const auto& [key, value] : b.options) {
    if (key == set_key) continue;
    if (key == "TIME POINTS") {
      const auto it = s.time_points.find(io::upper_case(value));
      if (it == s.time_points.end()) fail(b, b.keyword, "unknown *TIME POINTS '" + value + "'");
      std::vector<double>& times = open_step(s, b).output.frame_times;
      times.insert(times.end(), it->second.begin(), it->second.end());
      std::sort(times.begin(), times.end());
      times.erase(std::unique(times.begin(), times.end()), times.end());
      continue;
    }
    s.out.warnings.push_back(where(b.keyword) + ": parameter " + key + " of *" + b.name +
                             " skipped (cushion prints at every frame)");
  }
}

void add_print(State& s, PrintRequest::Kind kind, const std::string& set, const std::vector<std::string>& quantities) {
  auto& prints = s.out.spec.prints;
  auto it = std::find_if(prints.begin(), prints.end(), [&](const PrintRequest& p) { return p.kind == kind && p.set == set; });
  if (it == prints.end()) it = prints.insert(prints.end(), PrintRequest{kind, set, {}});
  for (const std::string& q : quantities)
    if (std::find(it->quantities.begin(), it->quantities.end(), q) == it->quantities.end()) it->quantities.push_back(q);
}

}  // namespace

void amplitude(State& s, const Block& b) {
  check_parameters(b, {"NAME", "TIME", "DEFINITION", "VALUE"});
  const std::string name = io::upper_case(required_parameter(b, "NAME"));
  if (s.out.spec.amplitudes.count(name)) fail(b, b.keyword, "amplitude " + name + " is defined twice");
  const std::string time = io::upper_case(parameter(b, "TIME").value_or("STEP TIME"));
  if (time != "STEP TIME" && time != "TOTAL TIME") fail(b, b.keyword, "TIME must be STEP TIME or TOTAL TIME");
  if (io::upper_case(parameter(b, "DEFINITION").value_or("TABULAR")) != "TABULAR")
    fail(b, b.keyword, "only DEFINITION=TABULAR is supported by cushion run");
  if (io::upper_case(parameter(b, "VALUE").value_or("RELATIVE")) != "RELATIVE")
    fail(b, b.keyword, "only VALUE=RELATIVE is supported by cushion run");
  Amplitude a;
  a.total_time = time == "TOTAL TIME";
  for (const Line& line : b.data) {
    const std::vector<std::string> f = mesh::inp_fields(line.text);
    if (f.size() % 2) fail(b, line, "expected pairs 'time, value'");
    for (std::size_t k = 0; k < f.size(); k += 2) {
      const double t = number(b, line, f[k]);
      if (!a.time.empty() && !(t > a.time.back())) fail(b, line, "times must increase strictly");
      a.time.push_back(t);
      a.value.push_back(number(b, line, f[k + 1]));
    }
  }
  if (a.time.empty()) fail(b, b.keyword, "no 'time, value' pairs");
  s.out.spec.amplitudes[name] = a;
}

void boundary(State& s, const Block& b) {
  check_parameters(b, {"OP", "AMPLITUDE"});
  if (op_new(s, b)) s.boundary.clear();
  const std::optional<std::string> amp = amplitude_parameter(s, b);
  for (const Line& line : b.data) {
    const std::vector<std::string> f = mesh::inp_fields(line.text);
    if (f.size() < 2 || f.size() > 4) fail(b, line, "expected 'node or set, first dof[, last dof[, value]]'");
    BoundarySpec bc;
    bc.set = node_target(s, b, line, f[0]);
    bc.amplitude = amp;
    bc.key = where(line);
    if (const auto type = boundary_type(f[1])) {
      if (f.size() > 2) fail(b, line, "a type (" + f[1] + ") takes no further fields");
      for (int c = 0; c < 3; ++c)
        if ((*type)[c]) put_boundary(s, bc, c);
      continue;
    }
    const int first = component(b, line, f[1]);
    const int last = f.size() > 2 && !f[2].empty() ? component(b, line, f[2]) : first;
    if (last < first) fail(b, line, "last dof before first dof");
    bc.value = f.size() > 3 ? number(b, line, f[3]) * s.units.length : 0.0;
    if (bc.value != 0.0 && !s.step) fail(b, line, "a non-zero value is only allowed inside a *STEP");
    if (bc.value != 0.0 && s.procedure && s.out.spec.steps[*s.step].perturbation())
      fail(b, line, "a prescribed motion in a linear perturbation step is not supported by cushion run (give the "
                    "excitation as *CLOAD)");
    for (int c = first; c <= last; ++c) put_boundary(s, bc, c);
  }
}

/// *CLOAD in a *STEADY STATE DYNAMICS step: harmonic forces of that step only (a linear perturbation's loads
/// are not carried to later steps, as in ABAQUS).
/// One data line "node or set, dof, magnitude" of *CLOAD: the force [N] per node of the set.
HarmonicLoad cload_line(State& s, const Block& b, const Line& line) {
  const std::vector<std::string> f = mesh::inp_fields(line.text);
  if (f.size() != 3) fail(b, line, "expected 'node or set, dof, magnitude'");
  return {node_target(s, b, line, f[0]), component(b, line, f[1]), number(b, line, f[2]) * s.units.force, where(line)};
}

void harmonic_cload(State& s, const Block& b, SteadyStateSpec& ss) {
  check_parameters(b, {});
  for (const Line& line : b.data) ss.loads.push_back(cload_line(s, b, line));
}

void cload(State& s, const Block& b) {
  StepSpec& step = open_step(s, b);
  if (s.procedure && step.type == StepSpec::Type::steady_state) return harmonic_cload(s, b, step.steady_state);
  check_parameters(b, {"OP", "AMPLITUDE"});
  if (op_new(s, b)) s.loads.clear();
  const std::optional<std::string> amp = amplitude_parameter(s, b);
  for (const Line& line : b.data) {
    HarmonicLoad l = cload_line(s, b, line);
    LoadSpec load{std::move(l.set), l.component, l.force, amp, std::move(l.key)};
    auto same = [&](const LoadSpec& o) { return o.set == load.set && o.component == load.component; };
    s.loads.erase(std::remove_if(s.loads.begin(), s.loads.end(), same), s.loads.end());
    s.loads.push_back(std::move(load));
  }
}

void dload(State& s, const Block& b) {
  check_parameters(b, {"OP", "AMPLITUDE"});
  open_step(s, b);
  if (op_new(s, b))
    for (PressureSpec& p : s.pressures) p.value = 0.0, p.amplitude.reset();  // removed: ramped down to 0
  const std::optional<std::string> amp = amplitude_parameter(s, b);
  for (const Line& line : b.data) {
    const std::vector<std::string> f = mesh::inp_fields(line.text);
    if (f.size() != 3) fail(b, line, "expected 'element or element set, Pn, magnitude'");
    const std::string type = io::upper_case(f[1]);
    if (type.size() != 2 || type[0] != 'P' || type[1] < '1' || type[1] > '6')
      fail(b, line, "load type " + f[1] + " is not supported by cushion run (face pressures P1..P6 only)");
    std::vector<int> elements;
    if (std::isdigit(static_cast<unsigned char>(f[0][0]))) {
      const int label = integer(b, line, f[0]);
      const auto& els = s.out.mesh.elements;
      const auto it = std::find_if(els.begin(), els.end(), [label](const mesh::Element& e) { return e.label == label; });
      if (it == els.end()) fail(b, line, "undefined element label " + f[0]);
      elements.push_back(static_cast<int>(it - els.begin()));
    } else {
      elements = s.out.mesh.element_sets.at(element_set(s, b, line, f[0]));
    }
    const double value = number(b, line, f[2]) * s.units.stress();
    for (int e : elements) {
      const int face = type[1] - '1';
      if (face >= mesh::faces_per_element(s.out.mesh.elements[e].type))
        fail(b, line, "element " + std::to_string(s.out.mesh.elements[e].label) + " has no face " + f[1]);
      auto it = std::find_if(s.pressures.begin(), s.pressures.end(),
                             [&](const PressureSpec& p) { return p.face.element == e && p.face.face == face; });
      if (it == s.pressures.end()) it = s.pressures.insert(s.pressures.end(), PressureSpec{{e, face}, 0.0, 0.0, {}, ""});
      it->value = value, it->amplitude = amp, it->key = where(line);
    }
  }
}

void step(State& s, const Block& b) {
  check_parameters(b, {"NLGEOM", "INC", "NAME"});
  if (s.step) fail(b, b.keyword, "a *STEP inside a *STEP (missing *END STEP)");
  StepSpec step;
  step.name = parameter(b, "NAME").value_or("Step-" + std::to_string(s.out.spec.steps.size() + 1));
  for (const StepSpec& other : s.out.spec.steps)
    if (io::upper_case(other.name) == io::upper_case(step.name)) fail(b, b.keyword, "step name " + step.name + " is used twice");
  if (const auto inc = parameter(b, "INC")) {
    step.increment.max_increments = integer(b, b.keyword, *inc);
    if (step.increment.max_increments < 1) fail(b, b.keyword, "INC must be >= 1");
  }
  const auto nlgeom = parameter(b, "NLGEOM");
  if (!nlgeom || io::upper_case(*nlgeom) == "NO")
    s.out.warnings.push_back(where(b.keyword) +
                             ": *STEP without NLGEOM: cushion always solves the geometrically nonlinear problem");
  else if (!nlgeom->empty() && io::upper_case(*nlgeom) != "YES")
    fail(b, b.keyword, "NLGEOM must be YES or NO");
  s.out.spec.steps.push_back(step);
  s.step = s.out.spec.steps.size() - 1;
  for (PressureSpec& p : s.pressures) p.start_value = p.amplitude ? 0.0 : p.value;  // ramps start at the last value
  s.procedure = false;
}

void static_procedure(State& s, const Block& b) {
  check_parameters(b, {"DIRECT", "LONG TERM"});
  procedure(s, b, StepSpec::Type::static_);
  StepSpec& step = open_step(s, b);
  step.long_term = parameter(b, "LONG TERM").has_value();
  step.increment.fixed = parameter(b, "DIRECT").has_value();
}

void visco_procedure(State& s, const Block& b) {
  check_parameters(b, {"DIRECT"});
  procedure(s, b, StepSpec::Type::visco);
  open_step(s, b).increment.fixed = parameter(b, "DIRECT").has_value();
}

void dynamic_procedure(State& s, const Block& b) {
  check_parameters(b, {"DIRECT", "ALPHA"});
  procedure(s, b, StepSpec::Type::dynamic);
  StepSpec& step = open_step(s, b);
  step.increment.fixed = parameter(b, "DIRECT").has_value();
  DynamicSpec& d = step.dynamic;
  d.key = where(b.keyword);
  // HHT alpha (ABAQUS and CalculiX default -0.05), gamma = 1/2 - alpha, beta = (1 - alpha)^2 / 4.
  d.hht_alpha = parameter(b, "ALPHA") ? number(b, b.keyword, *parameter(b, "ALPHA")) : -0.05;
  if (!(d.hht_alpha >= -1.0 / 3.0 && d.hht_alpha <= 0.0)) fail(b, b.keyword, "ALPHA must be in [-1/3, 0]");
  d.gamma = 0.5 * (1.0 - 2.0 * d.hht_alpha);
  d.beta = 0.25 * (d.gamma + 0.5) * (d.gamma + 0.5);
}

void frequency_procedure(State& s, const Block& b) {
  check_parameters(b, {"STORAGE", "SOLVER"});
  StepSpec& step = open_step(s, b);
  if (s.procedure) fail(b, b.keyword, "the step already has its procedure");
  s.procedure = true;
  step.type = StepSpec::Type::frequency;
  step.frequency.key = where(b.keyword);
  // number of frequencies, lower and upper bound of the range of interest [Hz] (CalculiX; the shift is not used).
  if (b.data.size() != 1) fail(b, b.keyword, "expected one data line 'number of frequencies[, low, high]'");
  const Line& line = b.data.front();
  std::vector<std::string> f = mesh::inp_fields(line.text);
  f.resize(std::max<std::size_t>(f.size(), 3));
  step.frequency.modes = integer(b, line, f[0]);
  if (step.frequency.modes < 1) fail(b, line, "the number of frequencies must be >= 1");
  if (!f[1].empty()) step.frequency.low = number(b, line, f[1]);
  if (!f[2].empty()) step.frequency.high = number(b, line, f[2]);
  if (!(step.frequency.low >= 0.0) || !(step.frequency.high >= 0.0) ||
      (step.frequency.high > 0.0 && step.frequency.high < step.frequency.low))
    fail(b, line, "need 0 <= low <= high (high 0: no upper bound)");
}

void steady_state_procedure(State& s, const Block& b) {
  check_parameters(b, {"DIRECT"});
  StepSpec& step = open_step(s, b);
  if (s.procedure) fail(b, b.keyword, "the step already has its procedure");
  s.procedure = true;
  step.type = StepSpec::Type::steady_state;
  SteadyStateSpec& ss = step.steady_state;
  ss.key = where(b.keyword);
  // low, high [Hz], points (default 20), bias (default 3 around resonances, 1 for DIRECT: ABAQUS).
  if (b.data.size() != 1) fail(b, b.keyword, "expected one data line 'low, high[, points, bias]' (one range)");
  const Line& line = b.data.front();
  std::vector<std::string> f = mesh::inp_fields(line.text);
  if (f.size() < 2 || f.size() > 4) fail(b, line, "expected 'low, high[, points, bias]'");
  f.resize(4);
  const bool direct = parameter(b, "DIRECT").has_value();
  ResonancePoints p{number(b, line, f[0]), number(b, line, f[1]), f[2].empty() ? 20 : integer(b, line, f[2]),
                    f[3].empty() ? (direct ? 1.0 : 3.0) : number(b, line, f[3])};
  if (!(p.low > 0.0) || !(p.high >= p.low) || p.points < 2 || p.points > 10000 || !(p.bias >= 1.0))
    fail(b, line, "need 0 < low <= high [Hz], 2 <= points <= 10000, bias >= 1");
  if (direct) {
    ss.frequencies = dynamics::frequency_points(p.low, p.high, p.points, p.bias, {});
    return;
  }
  const bool after_frequency = std::any_of(s.out.spec.steps.begin(), s.out.spec.steps.end() - 1,
                                           [](const StepSpec& o) { return o.type == StepSpec::Type::frequency; });
  if (!after_frequency)
    fail(b, b.keyword, "a modal steady state needs a preceding *FREQUENCY step (or give DIRECT)");
  s.out.warnings.push_back(where(b.keyword) + ": *STEADY STATE DYNAMICS (modal) solved directly: cushion solves the "
                                              "full system at each frequency (no modal truncation), the frequencies "
                                              "placed around the resonances as CalculiX places them");
  ss.resonance_points = p;
}

void end_step(State& s, const Block& b) {
  check_parameters(b, {});
  StepSpec& step = open_step(s, b);
  if (!s.procedure)
    fail(b, b.keyword, "the step has no procedure (*STATIC, *VISCO, *DYNAMIC, *FREQUENCY or *STEADY STATE DYNAMICS)");
  if (step.type == StepSpec::Type::steady_state) {
    SteadyStateSpec& ss = step.steady_state;
    if (ss.loads.empty()) fail(b, b.keyword, "the *STEADY STATE DYNAMICS step has no *CLOAD (its excitation)");
    ss.vtk = true;
  }
  step.boundary = s.boundary;
  step.loads = s.loads;
  step.pressures = s.pressures;
  auto removed = [](const PressureSpec& p) { return p.value == 0.0 && !p.amplitude; };
  s.pressures.erase(std::remove_if(s.pressures.begin(), s.pressures.end(), removed), s.pressures.end());
  s.step.reset();
}

void node_print(State& s, const Block& b) {
  StepSpec& step = open_step(s, b);
  output_parameters(s, b, "NSET");
  const std::string set = node_target(s, b, b.keyword, required_parameter(b, "NSET"));
  if (s.procedure && step.type == StepSpec::Type::steady_state) {  // complex U per frequency
    print_variables(s, b, {"U"});
    if (std::find(step.steady_state.prints.begin(), step.steady_state.prints.end(), set) == step.steady_state.prints.end())
      step.steady_state.prints.push_back(set);
    return;
  }
  add_print(s, PrintRequest::Kind::node, set, print_variables(s, b, {"U", "RF"}));
}

void el_print(State& s, const Block& b) {
  open_step(s, b);
  output_parameters(s, b, "ELSET");
  const std::string set = element_set(s, b, b.keyword, required_parameter(b, "ELSET"));
  add_print(s, PrintRequest::Kind::element, set, print_variables(s, b, {"S"}));
}

void result_file(State& s, const Block& b) {
  open_step(s, b);  // the frames (results.pvd) hold every field anyway
  output_parameters(s, b, b.name == "NODE FILE" ? "NSET" : "ELSET");
}

void time_points(State& s, const Block& b) {
  check_parameters(b, {"NAME", "TIME", "GENERATE"});
  const std::string name = io::upper_case(required_parameter(b, "NAME"));
  if (s.time_points.count(name)) fail(b, b.keyword, "time points " + name + " are defined twice");
  if (io::upper_case(parameter(b, "TIME").value_or("STEP TIME")) != "STEP TIME")
    fail(b, b.keyword, "only TIME=STEP TIME is supported by cushion run");
  std::vector<double> times;
  for (const Line& line : b.data) {
    std::vector<double> v;
    for (const std::string& f : mesh::inp_fields(line.text))
      if (!f.empty()) v.push_back(number(b, line, f));
    if (!parameter(b, "GENERATE")) {
      times.insert(times.end(), v.begin(), v.end());
      continue;
    }
    if (v.size() != 3 || !(v[2] > 0.0) || !(v[1] >= v[0]) || (v[1] - v[0]) / v[2] > 1e6)
      fail(b, line, "GENERATE expects 'start, end, increment' with end >= start and 0 < increment");
    for (int k = 0; v[0] + k * v[2] <= v[1] * (1.0 + 1e-12); ++k) times.push_back(v[0] + k * v[2]);
  }
  if (times.empty()) fail(b, b.keyword, "no times");
  for (std::size_t k = 0; k < times.size(); ++k)
    if (!(times[k] >= 0.0) || (k > 0 && !(times[k] > times[k - 1]))) fail(b, b.keyword, "times must be >= 0 and increase");
  s.time_points[name] = times;
}

void finish_steps(State& s) {
  for (StepSpec& step : s.out.spec.steps)
    if (step.type == StepSpec::Type::steady_state)
      for (const BoundarySpec& bc : step.boundary) step.steady_state.held.push_back({bc.set, bc.dofs, bc.key});
}

}  // namespace cushion::solver::deck
