#include "solver/dynamics/steady_state_spec.hpp"

#include <cmath>

#include "material/io/json_reader.hpp"
#include "material/io/text_support.hpp"

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
  o.expect_object({"frequencies", "frequencies_Hz", "excitation", "held", "measure", "damping", "base_stress",
                   "area_mm2", "thickness_mm", "output"});
  SteadyStateSpec s;
  s.key = path;
  s.frequencies = parse_frequencies(o);

  const JsonNode x = o.at("excitation");
  x.expect_object({"set", "dof", "acceleration_amplitude_m_s2", "amplitude_is", "displacement_amplitude_mm"});
  s.excitation = parse_set_dofs(x, {"x", "y", "z"}, set_exists);
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
  s.measure = o.at("measure").string();
  if (!set_exists(s.measure)) o.at("measure").fail("unknown set \"" + s.measure + "\" (define it under \"sets\")");
  const int c = s.excitation.dofs[0] ? 0 : s.excitation.dofs[1] ? 1 : 2;
  bool measured = s.measure == s.excitation.set;
  for (const SetDofs& h : s.held) measured = measured || (h.set == s.measure && h.dofs[c]);
  if (!measured)
    o.at("measure").fail("set \"" + s.measure + "\" must be the excitation set or held in the excitation's dof "
                         "(its reaction is the measured force)");

  if (o.has("damping")) {
    const JsonNode d = o.at("damping");
    d.expect_object({"rayleigh_alpha_1_s", "rayleigh_beta_s", "structural"});
    if (d.has("rayleigh_alpha_1_s")) s.alpha = d.at("rayleigh_alpha_1_s").number_where(non_negative, ">= 0");
    if (d.has("rayleigh_beta_s")) s.beta = d.at("rayleigh_beta_s").number_where(non_negative, ">= 0");
    if (d.has("structural")) s.structural = d.at("structural").number_where(non_negative, ">= 0");
  }
  if (o.has("base_stress")) s.relaxed_base = o.at("base_stress").choice({"relaxed", "as_left"}) == "relaxed";
  s.area = o.at("area_mm2").number_where(positive, "> 0");
  s.thickness = o.at("thickness_mm").number_where(positive, "> 0");
  if (o.has("output")) {
    const JsonNode out = o.at("output");
    out.expect_object({"vtk"});
    if (out.has("vtk")) s.vtk = out.at("vtk").boolean();
  }
  return s;
}

}  // namespace cushion::solver::dynamics
