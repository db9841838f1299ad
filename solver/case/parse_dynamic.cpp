// Step damping (damping.hpp, shared by dynamic and steady-state steps) and the Newmark keys of a
// "dynamic" step (case_spec.hpp).
#include "io/text_support.hpp"
#include "solver/case/case_parts.hpp"

namespace cushion::solver::case_parse {

namespace {

/// "newmark": HHT alpha, gamma, beta with the defaults that follow from alpha (case_spec.hpp).
void parse_newmark(const Obj& newmark, DynamicSpec& d) {
  if (newmark.has("alpha")) {
    d.hht_alpha = newmark.number("alpha");
    if (!(d.hht_alpha >= -1.0 / 3.0 && d.hht_alpha <= 0.0))
      newmark.fail("alpha", "HHT alpha must be in [-1/3, 0] (ABAQUS: -0.05 moderate, -1/3 most dissipation), found " +
                                io::format_double(d.hht_alpha));
    d.gamma = 0.5 * (1.0 - 2.0 * d.hht_alpha);
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

}  // namespace

Damping parse_damping(const Obj& step, bool structural_allowed) {
  Damping d;
  if (!step.has("damping")) return d;
  std::vector<std::string> keys{"rayleigh_alpha_1_s", "rayleigh_beta_s"};
  if (structural_allowed) keys.push_back("structural");
  const Obj damping = step.child("damping", keys);
  if (damping.has("rayleigh_alpha_1_s")) d.rayleigh_alpha = damping.non_negative("rayleigh_alpha_1_s");
  if (damping.has("rayleigh_beta_s")) d.rayleigh_beta = damping.non_negative("rayleigh_beta_s");
  if (damping.has("structural")) d.structural = damping.non_negative("structural");
  return d;
}

DynamicSpec parse_dynamic(const Obj& step) {
  DynamicSpec d;
  d.key = step.here();
  d.damping = parse_damping(step, false);
  if (step.has("newmark")) parse_newmark(step.child("newmark", {"alpha", "gamma", "beta"}), d);
  return d;
}

}  // namespace cushion::solver::case_parse
