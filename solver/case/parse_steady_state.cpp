// The "steady_state" part of the case grammar (steady_state_spec.hpp).
#include <algorithm>
#include <cmath>

#include "solver/case/case_parts.hpp"

namespace cushion::solver::case_parse {

namespace {

bool positive(double x) { return x > 0.0; }

/// Throws InputError at `o.contact` unless `name` is a contact of the base state: of the last static,
/// visco or dynamic step before this one (`spec.steps`).
void check_base_contact(const Obj& o, const std::string& name, const CaseSpec& spec) {
  const auto previous = std::find_if(spec.steps.rbegin(), spec.steps.rend(),
                                     [](const StepSpec& s) { return s.type != StepSpec::Type::steady_state; });
  std::string names;
  if (previous != spec.steps.rend())
    for (const ContactSpec& c : previous->contact) {
      if (c.name == name) return;
      names += (names.empty() ? "'" : ", '") + c.name + "'";
    }
  o.fail("contact", "\"" + name + "\" is not a contact of the base state (contacts of the previous step: " +
                        (names.empty() ? "none" : names) + ")");
}

SetDofs parse_set_dofs(const Obj& o, const std::vector<std::string>& dof_choices, const CaseSpec& spec) {
  SetDofs s;
  s.key = o.here();
  s.set = o.string("set");
  check_set_defined(o, "set", s.set, spec);
  for (char c : o.choice("dof", dof_choices)) s.dofs[c - 'x'] = true;
  return s;
}

std::vector<double> parse_frequencies(const Obj& o) {
  std::vector<double> f;
  if (o.has("frequencies") == o.has("frequencies_Hz"))
    o.fail_here("give exactly one of \"frequencies\" {start_Hz, end_Hz, step_Hz} or \"frequencies_Hz\" [...]");
  if (o.has("frequencies_Hz")) {
    const io::JsonNode list = o.at("frequencies_Hz");
    const std::size_t n = list.expect_array(1, 100000);
    for (std::size_t i = 0; i < n; ++i) f.push_back(list[i].number_where(positive, "> 0 Hz"));
    return f;
  }
  const Obj r = o.child("frequencies", {"start_Hz", "end_Hz", "step_Hz"});
  const double start = r.at("start_Hz").number_where(positive, "> 0 Hz");
  const double end = r.at("end_Hz").number_where(positive, "> 0 Hz");
  const double step = r.at("step_Hz").number_where(positive, "> 0 Hz");
  if (end < start) r.fail("end_Hz", "must be >= start_Hz");
  const double count = std::floor((end - start) / step * (1.0 + 1e-12)) + 1.0;
  if (count > 100000) r.fail("step_Hz", "gives more than 100000 frequencies");
  for (int i = 0; i < static_cast<int>(count); ++i) f.push_back(start + i * step);
  return f;
}

/// "excitation": a set or an indenter, one component, an acceleration or a displacement amplitude.
void parse_excitation(const Obj& x, const CaseSpec& spec, SteadyStateSpec& s) {
  if (x.has("set") == x.has("contact"))
    x.fail_here("give exactly one of \"set\" (a node set) or \"contact\" (an indenter)");
  if (x.has("set")) {
    s.excitation = parse_set_dofs(x, {"x", "y", "z"}, spec);
  } else {
    s.excitation.key = x.here();
    s.excitation_contact = x.string("contact");
    check_base_contact(x, s.excitation_contact, spec);
    for (char c : x.choice("dof", {"x", "y", "z"})) s.excitation.dofs[c - 'x'] = true;
  }
  if (x.has("acceleration_amplitude_m_s2") == x.has("displacement_amplitude_mm"))
    x.fail_here("give exactly one of \"acceleration_amplitude_m_s2\" or \"displacement_amplitude_mm\"");
  if (x.has("acceleration_amplitude_m_s2")) {
    s.acceleration = 1e3 * x.at("acceleration_amplitude_m_s2").number_where(positive, "> 0");  // m/s^2 -> mm/s^2
    if (x.choice_or("amplitude_is", {"peak_to_peak", "peak"}, "peak_to_peak") == "peak")
      s.reading = AccelerationReading::peak;
  } else {
    if (x.has("amplitude_is")) x.fail("amplitude_is", "applies to acceleration_amplitude_m_s2 only");
    s.from_acceleration = false;
    s.displacement = x.at("displacement_amplitude_mm").number_where(positive, "> 0");
  }
}

/// "indenters": held or free (with a mass) indenters other than the excited one.
void parse_indenters(const Obj& o, const CaseSpec& spec, SteadyStateSpec& s) {
  const std::size_t n = o.at("indenters").expect_array(0, 100);
  for (std::size_t i = 0; i < n; ++i) {
    const Obj e = o.element("indenters", i, {"contact", "motion", "mass_kg"});
    IndenterMotion m;
    m.key = e.here();
    m.contact = e.string("contact");
    check_base_contact(e, m.contact, spec);
    if (m.contact == s.excitation_contact)
      e.fail("contact", "is the excited indenter (it cannot also be held or free)");
    for (const IndenterMotion& other : s.indenters)
      if (other.contact == m.contact) e.fail("contact", "listed twice");
    m.free = e.choice("motion", {"held", "free"}) == "free";
    if (m.free) m.mass = 1e-3 * e.at("mass_kg").number_where(positive, "> 0 kg (a free indenter needs a mass)");
    else if (e.has("mass_kg")) e.fail("mass_kg", "applies to a \"free\" indenter only");
    s.indenters.push_back(m);
  }
}

/// "measure": an indenter {"contact": name} or a set driven or held in the excitation's component.
void parse_measure(const Obj& o, const CaseSpec& spec, SteadyStateSpec& s) {
  if (o.is_object("measure")) {
    const Obj m = o.child("measure", {"contact"});
    s.measure_contact = m.string("contact");
    check_base_contact(m, s.measure_contact, spec);
    return;
  }
  s.measure = o.string("measure");
  check_set_defined(o, "measure", s.measure, spec, "define it under \"sets\", or give {\"contact\": name}");
  bool measured = s.measure == s.excitation.set;
  for (const SetDofs& h : s.held) measured = measured || (h.set == s.measure && h.dofs[s.component()]);
  if (!measured)
    o.fail("measure", "set \"" + s.measure + "\" must be the excitation set or held in the excitation's dof "
                      "(its reaction is the measured force)");
}

/// "area_mm2" (a number or "contact"), "thickness_mm".
void parse_geometry(const Obj& o, SteadyStateSpec& s) {
  if (o.is_string("area_mm2")) {
    o.choice("area_mm2", {"contact"});
    if (s.measure_contact.empty())
      o.fail("area_mm2", "\"contact\" needs a measured indenter (\"measure\": {\"contact\": name})");
    s.area_from_contact = true;
  } else {
    s.area = o.at("area_mm2").number_where(positive, "> 0");
  }
  s.thickness = o.at("thickness_mm").number_where(positive, "> 0");
}

/// "output", "linear_solver", "gmres_tolerance".
void parse_sweep_options(const Obj& o, SteadyStateSpec& s) {
  if (o.has("output")) {
    const Obj out = o.child("output", {"vtk"});
    if (out.has("vtk")) s.vtk = out.at("vtk").boolean();
  }
  s.iterative = o.choice_or("linear_solver", {"iterative", "direct"}, "iterative") == "iterative";
  if (o.has("gmres_tolerance"))
    s.gmres_tolerance =
        o.at("gmres_tolerance").number_where([](double x) { return x > 0.0 && x <= 1e-3; }, "in (0, 1e-3]");
}

}  // namespace

SteadyStateSpec parse_steady_state(const Obj& o, const CaseSpec& spec) {
  SteadyStateSpec s;
  s.key = o.here();
  s.frequencies = parse_frequencies(o);
  parse_excitation(o.child("excitation", {"set", "contact", "dof", "acceleration_amplitude_m_s2", "amplitude_is",
                                          "displacement_amplitude_mm"}),
                   spec, s);
  const std::size_t n_held = o.has("held") ? o.at("held").expect_array(0, 10000) : 0;
  for (std::size_t i = 0; i < n_held; ++i)
    s.held.push_back(
        parse_set_dofs(o.element("held", i, {"set", "dof"}), {"x", "y", "z", "xy", "xz", "yz", "xyz"}, spec));
  if (o.has("indenters")) parse_indenters(o, spec, s);
  parse_measure(o, spec, s);
  s.damping = parse_damping(o, true);
  if (o.choice_or("base_stress", {"relaxed", "as_left"}, "relaxed") == "as_left") s.base_stress = BaseStress::as_left;
  parse_geometry(o, s);
  parse_sweep_options(o, s);
  return s;
}

}  // namespace cushion::solver::case_parse
