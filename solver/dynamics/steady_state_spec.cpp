#include "solver/dynamics/steady_state_spec.hpp"

#include <cmath>

#include "io/json_reader.hpp"
#include "io/text_support.hpp"

namespace cushion::solver::dynamics {
namespace {

using io::JsonNode;

bool positive(double x) { return x > 0.0; }
bool non_negative(double x) { return x >= 0.0; }

SetDofs parse_set_dofs(const JsonNode& n, const std::vector<std::string>& dof_choices,
                       const std::function<bool(const std::string&)>& set_exists) {
  SetDofs s;
  s.key = n.path();
  s.set = n.at("set").string();
  if (!set_exists(s.set)) n.at("set").fail("unknown set \"" + s.set + "\" (define it under \"sets\")");
  for (char c : n.at("dof").choice(dof_choices)) s.dofs[c - 'x'] = true;
  return s;
}

std::vector<double> parse_frequencies(const JsonNode& o) {
  std::vector<double> f;
  if (o.has("frequencies") == o.has("frequencies_Hz"))
    o.fail("give exactly one of \"frequencies\" {start_Hz, end_Hz, step_Hz} or \"frequencies_Hz\" [...]");
  if (o.has("frequencies_Hz")) {
    const JsonNode list = o.at("frequencies_Hz");
    const std::size_t n = list.expect_array(1, 100000);
    for (std::size_t i = 0; i < n; ++i) f.push_back(list[i].number_where(positive, "> 0 Hz"));
    return f;
  }
  const JsonNode r = o.at("frequencies");
  r.expect_object({"start_Hz", "end_Hz", "step_Hz"});
  const double start = r.at("start_Hz").number_where(positive, "> 0 Hz");
  const double end = r.at("end_Hz").number_where(positive, "> 0 Hz");
  const double step = r.at("step_Hz").number_where(positive, "> 0 Hz");
  if (end < start) r.at("end_Hz").fail("must be >= start_Hz");
  const double count = std::floor((end - start) / step * (1.0 + 1e-12)) + 1.0;
  if (count > 100000) r.at("step_Hz").fail("gives more than 100000 frequencies");
  for (int i = 0; i < static_cast<int>(count); ++i) f.push_back(start + i * step);
  return f;
}

}  // namespace

SteadyStateSpec parse_steady_state_spec(const nlohmann::json& value, const std::string& source,
                                        const std::string& path,
                                        const std::function<bool(const std::string&)>& set_exists, bool first_step) {
  const JsonNode o(value, source, path);
  if (first_step)
    o.fail("a steady_state step needs a preceding static or visco step (its end state is the base state)");
  o.expect_object({"frequencies", "frequencies_Hz", "excitation", "held", "indenters", "measure", "damping",
                   "base_stress", "area_mm2", "thickness_mm", "output", "linear_solver", "gmres_tolerance"});
  SteadyStateSpec s;
  s.key = path;
  s.frequencies = parse_frequencies(o);

  const JsonNode x = o.at("excitation");
  x.expect_object({"set", "contact", "dof", "acceleration_amplitude_m_s2", "amplitude_is", "displacement_amplitude_mm"});
  if (x.has("set") == x.has("contact")) x.fail("give exactly one of \"set\" (a node set) or \"contact\" (an indenter)");
  if (x.has("set")) {
    s.excitation = parse_set_dofs(x, {"x", "y", "z"}, set_exists);
  } else {
    s.excitation.key = x.path();
    s.excitation_contact = x.at("contact").string();
    for (char c : x.at("dof").choice({"x", "y", "z"})) s.excitation.dofs[c - 'x'] = true;
  }
  if (x.has("acceleration_amplitude_m_s2") == x.has("displacement_amplitude_mm"))
    x.fail("give exactly one of \"acceleration_amplitude_m_s2\" or \"displacement_amplitude_mm\"");
  if (x.has("acceleration_amplitude_m_s2")) {
    s.acceleration = 1e3 * x.at("acceleration_amplitude_m_s2").number_where(positive, "> 0");  // m/s^2 -> mm/s^2
    if (x.has("amplitude_is")) s.peak_to_peak = x.at("amplitude_is").choice({"peak_to_peak", "peak"}) == "peak_to_peak";
  } else {
    if (x.has("amplitude_is")) x.at("amplitude_is").fail("applies to acceleration_amplitude_m_s2 only");
    s.from_acceleration = false;
    s.displacement = x.at("displacement_amplitude_mm").number_where(positive, "> 0");
  }

  if (o.has("held")) {
    const JsonNode list = o.at("held");
    const std::size_t n = list.expect_array(0, 10000);
    for (std::size_t i = 0; i < n; ++i) {
      list[i].expect_object({"set", "dof"});
      s.held.push_back(parse_set_dofs(list[i], {"x", "y", "z", "xy", "xz", "yz", "xyz"}, set_exists));
    }
  }
  if (o.has("indenters")) {
    const JsonNode list = o.at("indenters");
    const std::size_t n = list.expect_array(0, 100);
    for (std::size_t i = 0; i < n; ++i) {
      const JsonNode e = list[i];
      e.expect_object({"contact", "motion", "mass_kg"});
      IndenterMotion m;
      m.key = e.path();
      m.contact = e.at("contact").string();
      if (m.contact == s.excitation_contact) e.at("contact").fail("is the excited indenter (it cannot also be held or free)");
      for (const IndenterMotion& other : s.indenters)
        if (other.contact == m.contact) e.at("contact").fail("listed twice");
      m.free = e.at("motion").choice({"held", "free"}) == "free";
      if (m.free) m.mass = 1e-3 * e.at("mass_kg").number_where(positive, "> 0 kg (a free indenter needs a mass)");
      else if (e.has("mass_kg")) e.at("mass_kg").fail("applies to a \"free\" indenter only");
      s.indenters.push_back(m);
    }
  }
  const int c = s.excitation.dofs[0] ? 0 : s.excitation.dofs[1] ? 1 : 2;
  if (value.contains("measure") && value["measure"].is_object()) {
    const JsonNode m = o.at("measure");
    m.expect_object({"contact"});
    s.measure_contact = m.at("contact").string();
  } else {
    s.measure = o.at("measure").string();
    if (!set_exists(s.measure))
      o.at("measure").fail("unknown set \"" + s.measure + "\" (define it under \"sets\", or give {\"contact\": name})");
    bool measured = s.measure == s.excitation.set;
    for (const SetDofs& h : s.held) measured = measured || (h.set == s.measure && h.dofs[c]);
    if (!measured)
      o.at("measure").fail("set \"" + s.measure + "\" must be the excitation set or held in the excitation's dof "
                           "(its reaction is the measured force)");
  }

  if (o.has("damping")) {
    const JsonNode d = o.at("damping");
    d.expect_object({"rayleigh_alpha_1_s", "rayleigh_beta_s", "structural"});
    if (d.has("rayleigh_alpha_1_s")) s.alpha = d.at("rayleigh_alpha_1_s").number_where(non_negative, ">= 0");
    if (d.has("rayleigh_beta_s")) s.beta = d.at("rayleigh_beta_s").number_where(non_negative, ">= 0");
    if (d.has("structural")) s.structural = d.at("structural").number_where(non_negative, ">= 0");
  }
  if (o.has("base_stress")) s.relaxed_base = o.at("base_stress").choice({"relaxed", "as_left"}) == "relaxed";
  if (value.contains("area_mm2") && value["area_mm2"].is_string()) {
    if (o.at("area_mm2").choice({"contact"}) == "contact" && s.measure_contact.empty())
      o.at("area_mm2").fail("\"contact\" needs a measured indenter (\"measure\": {\"contact\": name})");
    s.area_from_contact = true;
  } else {
    s.area = o.at("area_mm2").number_where(positive, "> 0");
  }
  s.thickness = o.at("thickness_mm").number_where(positive, "> 0");
  if (o.has("output")) {
    const JsonNode out = o.at("output");
    out.expect_object({"vtk"});
    if (out.has("vtk")) s.vtk = out.at("vtk").boolean();
  }
  if (o.has("linear_solver")) s.iterative = o.at("linear_solver").choice({"iterative", "direct"}) == "iterative";
  if (o.has("gmres_tolerance"))
    s.gmres_tolerance = o.at("gmres_tolerance").number_where([](double x) { return x > 0.0 && x <= 1e-3; }, "in (0, 1e-3]");
  return s;
}

}  // namespace cushion::solver::dynamics
