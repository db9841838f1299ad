// Test-data generation for the diagnose benchmark, independent of cushion's material/ and calibration/:
// the effect forms of foreign_effects.hpp (one small class each) and their random shape parameters.
#include "foreign_effects.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace foreign_bench {

namespace {

double sign_of(double x) { return x > 0.0 ? 1.0 : x < 0.0 ? -1.0 : 0.0; }
double stretch_of(double strain) { return 1.0 - strain; }

/// (1 - exp(-x))/x, 1 at x -> 0.
double relaxation_average(double x) { return x < 1e-12 ? 1.0 : -std::expm1(-x) / x; }

double param(const EffectSpec& s, const std::string& key) {
  const auto it = s.parameters.find(key);
  if (it == s.parameters.end()) throw std::invalid_argument(s.family + "/" + s.form + ": missing parameter " + key);
  return it->second;
}

// --- pneumatic ---------------------------------------------------------------------------------------

/// Maxwell branch whose modulus and time grow with compression (air trapped in closing cells).
class StretchMaxwell : public Effect {
 public:
  explicit StretchMaxwell(const EffectSpec& s)
      : modulus_kPa_(param(s, "modulus_kPa")), modulus_exponent_(param(s, "modulus_exponent")),
        time_s_(param(s, "time_s")), time_exponent_(param(s, "time_exponent")) {}
  double extra_stress_kPa(const Increment& inc) override {
    const double l = stretch_of(inc.strain_mid());
    const double modulus = modulus_kPa_ * std::pow(l, -modulus_exponent_);
    const double tau = time_s_ * std::pow(l, -time_exponent_);
    const double x = inc.dt_s / tau;
    branch_kPa_ = std::exp(-x) * branch_kPa_ + modulus * relaxation_average(x) * (inc.strain_new - inc.strain_old);
    return branch_kPa_;
  }

 private:
  double modulus_kPa_, modulus_exponent_, time_s_, time_exponent_;
  double branch_kPa_ = 0.0;
};

/// Darcy flow out of the specimen: s = C e'/l^(n+1) (pressure eta R^2/(8 K) (dJ/dt)/J, J = l, K = K0 l^n).
class Darcy : public Effect {
 public:
  explicit Darcy(const EffectSpec& s)
      : resistance_kPa_s_(param(s, "resistance_kPa_s")), exponent_(param(s, "permeability_exponent")) {}
  double extra_stress_kPa(const Increment& inc) override {
    const double l = stretch_of(inc.strain_new);
    return resistance_kPa_s_ * inc.strain_rate_per_s() / std::pow(l, exponent_ + 1.0);
  }

 private:
  double resistance_kPa_s_, exponent_;
};

/// Non-Newtonian air dashpot growing with compression.
class PowerLawDashpot : public Effect {
 public:
  explicit PowerLawDashpot(const EffectSpec& s)
      : coefficient_(param(s, "coefficient_kPa_s_pow_q")), rate_exponent_(param(s, "rate_exponent_q")),
        stretch_exponent_(param(s, "stretch_exponent_m")) {}
  double extra_stress_kPa(const Increment& inc) override {
    const double rate = inc.strain_rate_per_s();
    return coefficient_ * std::pow(stretch_of(inc.strain_new), -stretch_exponent_) *
           std::pow(std::abs(rate), rate_exponent_) * sign_of(rate);
  }

 private:
  double coefficient_, rate_exponent_, stretch_exponent_;
};

// --- friction ----------------------------------------------------------------------------------------

/// Spring in series with a Coulomb slider (elastic-perfectly plastic, rate independent).
class Jenkins : public Effect {
 public:
  explicit Jenkins(const EffectSpec& s)
      : yield_kPa_(param(s, "yield_stress_kPa")), stiffness_kPa_(yield_kPa_ / param(s, "yield_strain")) {}
  double extra_stress_kPa(const Increment& inc) override {
    slider_kPa_ = std::clamp(slider_kPa_ + stiffness_kPa_ * (inc.strain_new - inc.strain_old), -yield_kPa_, yield_kPa_);
    return slider_kPa_;
  }

 private:
  double yield_kPa_, stiffness_kPa_;
  double slider_kPa_ = 0.0;
};

/// Smooth hysteresis integrated in strain with RK2 sub-steps of at most 2 % of the yield strain.
class StrainOde : public Effect {
 public:
  StrainOde(double yield_kPa, double yield_strain) : yield_kPa_(yield_kPa), yield_strain_(yield_strain) {}
  double extra_stress_kPa(const Increment& inc) override {
    const double de = inc.strain_new - inc.strain_old;
    if (de == 0.0) return z_kPa_;
    const int n = std::max(1, static_cast<int>(std::ceil(std::abs(de) / (0.02 * yield_strain_))));
    const double h = de / n;
    for (int k = 0; k < n; ++k) {
      const double k1 = slope(z_kPa_, h);
      const double k2 = slope(z_kPa_ + 0.5 * h * k1, h);
      z_kPa_ += h * k2;
    }
    return z_kPa_;
  }

 protected:
  virtual double slope(double z_kPa, double de) const = 0;  ///< dz/de
  double yield_kPa_, yield_strain_;
  double z_kPa_ = 0.0;
};

class BoucWen : public StrainOde {
 public:
  explicit BoucWen(const EffectSpec& s)
      : StrainOde(param(s, "yield_stress_kPa"), param(s, "yield_strain")), b_(param(s, "loading_share_b")),
        n_(param(s, "exponent_n")) {}

 private:
  double slope(double z, double de) const override {
    const double shape = b_ * sign_of(z * de) + (1.0 - b_);
    return yield_kPa_ / yield_strain_ * (1.0 - shape * std::pow(std::abs(z / yield_kPa_), n_));
  }
  double b_, n_;
};

class Dahl : public StrainOde {
 public:
  explicit Dahl(const EffectSpec& s)
      : StrainOde(param(s, "yield_stress_kPa"), param(s, "yield_strain")), a_(param(s, "exponent_a")) {}

 private:
  double slope(double z, double de) const override {
    return yield_kPa_ / yield_strain_ * std::pow(std::max(0.0, 1.0 - z * sign_of(de) / yield_kPa_), a_);
  }
  double a_;
};

// --- mullins -----------------------------------------------------------------------------------------

/// Remembers the largest strain reached (the virgin curve's energy is monotone in e).
class MaxStrainMemory : public Effect {
 protected:
  void remember(const Increment& inc) { strain_max_ = std::max(strain_max_, inc.strain_new); }
  double strain_max_ = 0.0;
};

class OgdenRoxburgh : public MaxStrainMemory {
 public:
  OgdenRoxburgh(const EffectSpec& s, const BaseFoam& foam)
      : foam_(foam), inverse_r_(param(s, "inverse_r")), m_kPa_(param(s, "m_kPa")), beta_(param(s, "beta")) {}
  double soften_kPa(const Increment& inc, double elastic_kPa) override {
    remember(inc);
    const double w = foam_.energy_kPa(inc.strain_new), w_max = foam_.energy_kPa(strain_max_);
    return (1.0 - inverse_r_ * std::erf((w_max - w) / (m_kPa_ + beta_ * w_max))) * elastic_kPa;
  }

 private:
  const BaseFoam& foam_;
  double inverse_r_, m_kPa_, beta_;
};

class ExponentialDamage : public MaxStrainMemory {
 public:
  explicit ExponentialDamage(const EffectSpec& s)
      : damage_limit_(param(s, "damage_limit")), damage_strain_(param(s, "damage_strain")) {}
  double soften_kPa(const Increment& inc, double elastic_kPa) override {
    remember(inc);
    return (1.0 - damage_limit_ * (1.0 - std::exp(-strain_max_ / damage_strain_))) * elastic_kPa;
  }

 private:
  double damage_limit_, damage_strain_;
};

class QiBoyceLike : public MaxStrainMemory {
 public:
  explicit QiBoyceLike(const EffectSpec& s)
      : softening_limit_(param(s, "softening_limit")), softening_strain_(param(s, "softening_strain")),
        recovery_exponent_(param(s, "recovery_exponent")) {}
  double soften_kPa(const Increment& inc, double elastic_kPa) override {
    remember(inc);
    if (strain_max_ <= 0.0) return elastic_kPa;
    const double below_max = 1.0 - std::pow(std::max(0.0, inc.strain_new) / strain_max_, recovery_exponent_);
    return (1.0 - softening_limit_ * std::tanh(strain_max_ / softening_strain_) * below_max) * elastic_kPa;
  }

 private:
  double softening_limit_, softening_strain_, recovery_exponent_;
};

// --- stiffness_damping -------------------------------------------------------------------------------

class StiffnessProportional : public Effect {
 public:
  StiffnessProportional(const EffectSpec& s, const BaseFoam& foam) : foam_(foam), beta_s_(param(s, "beta_s")) {}
  double extra_stress_kPa(const Increment& inc) override {
    return beta_s_ * foam_.elastic_tangent_kPa(inc.strain_new) * inc.strain_rate_per_s();
  }

 private:
  const BaseFoam& foam_;
  double beta_s_;
};

class SecantProportional : public Effect {
 public:
  SecantProportional(const EffectSpec& s, const BaseFoam& foam) : foam_(foam), beta_s_(param(s, "beta_s")) {}
  double extra_stress_kPa(const Increment& inc) override {
    const double e = inc.strain_new;
    const double secant = std::abs(e) < 1e-9 ? foam_.elastic_tangent_kPa(0.0) : foam_.elastic_stress_kPa(e) / e;
    return beta_s_ * secant * inc.strain_rate_per_s();
  }

 private:
  const BaseFoam& foam_;
  double beta_s_;
};

/// c D^q e as a bank of Maxwell branches sampling the spring-pot's relaxation spectrum
/// H(tau) = c sin(q pi)/pi tau^-q (so that sum_k E_k i w tau_k/(1 + i w tau_k) ~ c (i w)^q).
class FractionalDamping : public Effect {
 public:
  explicit FractionalDamping(const EffectSpec& s) {
    const double c = param(s, "coefficient_kPa_s_pow_q"), q = param(s, "order_q");
    const double step_ln = std::log(10.0) / branches_per_decade;
    for (int k = 0; k <= 9 * branches_per_decade; ++k) {
      const double tau = std::pow(10.0, -5.0 + static_cast<double>(k) / branches_per_decade);
      times_s_.push_back(tau);
      moduli_kPa_.push_back(c * std::sin(q * std::numbers::pi) / std::numbers::pi * std::pow(tau, -q) * step_ln);
      branches_kPa_.push_back(0.0);
    }
  }
  double extra_stress_kPa(const Increment& inc) override {
    const double de = inc.strain_new - inc.strain_old;
    double s = 0.0;
    for (std::size_t k = 0; k < times_s_.size(); ++k) {
      const double x = inc.dt_s / times_s_[k];
      branches_kPa_[k] = std::exp(-x) * branches_kPa_[k] + moduli_kPa_[k] * relaxation_average(x) * de;
      s += branches_kPa_[k];
    }
    return s;
  }
  static constexpr int branches_per_decade = 3;

 private:
  std::vector<double> times_s_, moduli_kPa_, branches_kPa_;
};

// --- strain_dependent_prony --------------------------------------------------------------------------

class PronyPowerLaw : public Effect {
 public:
  explicit PronyPowerLaw(const EffectSpec& s) : c_(param(s, "exponent_c")) {}
  double prony_factor(std::size_t, const Increment& inc) const override {
    return std::pow(stretch_of(inc.strain_mid()), -c_);
  }

 private:
  double c_;
};

class PronyExponential : public Effect {
 public:
  explicit PronyExponential(const EffectSpec& s) : k_(param(s, "rate_k")) {}
  double prony_factor(std::size_t, const Increment& inc) const override { return std::exp(k_ * inc.strain_mid()); }

 private:
  double k_;
};

class PronyLinearPerTerm : public Effect {
 public:
  explicit PronyLinearPerTerm(const EffectSpec& s) : slope_(param(s, "slope_K")) {
    for (int j = 0;; ++j) {
      const auto it = s.parameters.find("weight_" + std::to_string(j));
      if (it == s.parameters.end()) break;
      weights_.push_back(it->second);
    }
  }
  double prony_factor(std::size_t term, const Increment& inc) const override {
    const double w = term < weights_.size() ? weights_[term] : 1.0;
    return 1.0 + slope_ * w * std::max(0.0, inc.strain_mid());
  }

 private:
  double slope_;
  std::vector<double> weights_;
};

}  // namespace

std::unique_ptr<Effect> make_effect(const EffectSpec& s, const BaseFoam& foam) {
  const std::string key = s.family + "/" + s.form;
  if (key == "pneumatic/stretch_maxwell") return std::make_unique<StretchMaxwell>(s);
  if (key == "pneumatic/darcy") return std::make_unique<Darcy>(s);
  if (key == "pneumatic/power_law_dashpot") return std::make_unique<PowerLawDashpot>(s);
  if (key == "friction/jenkins") return std::make_unique<Jenkins>(s);
  if (key == "friction/bouc_wen") return std::make_unique<BoucWen>(s);
  if (key == "friction/dahl") return std::make_unique<Dahl>(s);
  if (key == "mullins/ogden_roxburgh") return std::make_unique<OgdenRoxburgh>(s, foam);
  if (key == "mullins/exponential_damage") return std::make_unique<ExponentialDamage>(s);
  if (key == "mullins/qi_boyce_like") return std::make_unique<QiBoyceLike>(s);
  if (key == "stiffness_damping/stiffness_proportional") return std::make_unique<StiffnessProportional>(s, foam);
  if (key == "stiffness_damping/fractional") return std::make_unique<FractionalDamping>(s);
  if (key == "stiffness_damping/secant_proportional") return std::make_unique<SecantProportional>(s, foam);
  if (key == "strain_dependent_prony/power_law") return std::make_unique<PronyPowerLaw>(s);
  if (key == "strain_dependent_prony/exponential") return std::make_unique<PronyExponential>(s);
  if (key == "strain_dependent_prony/linear_per_term") return std::make_unique<PronyLinearPerTerm>(s);
  throw std::invalid_argument("unknown effect form " + key);
}

const std::vector<EffectForm>& effect_forms() {
  static const std::vector<EffectForm> forms{
      {"pneumatic", "stretch_maxwell", "modulus_kPa", 1e-4, 1e4, "h' = E0 l^-p e' - h/(tau0 l^-m), s = h"},
      {"pneumatic", "darcy", "resistance_kPa_s", 1e-6, 1e4, "s = C e'/l^(n+1), C = eta R^2/(8 K0)"},
      {"pneumatic", "power_law_dashpot", "coefficient_kPa_s_pow_q", 1e-5, 1e4, "s = c0 l^-m |e'|^q sign(e')"},
      {"friction", "jenkins", "yield_stress_kPa", 1e-5, 1e3, "z += k de, |z| <= s_y, k = s_y/e_y, s = z"},
      {"friction", "bouc_wen", "yield_stress_kPa", 1e-5, 1e3,
       "dz/de = (s_y/e_y)[1 - (b sign(z de) + 1 - b)|z/s_y|^n], s = z"},
      {"friction", "dahl", "yield_stress_kPa", 1e-5, 1e3, "dz/de = (s_y/e_y) max(0, 1 - z sign(de)/s_y)^a, s = z"},
      {"mullins", "ogden_roxburgh", "inverse_r", 1e-5, 1.0, "s = [1 - erf((W_max - W)/(m + beta W_max))/r] s_e"},
      {"mullins", "exponential_damage", "damage_limit", 1e-5, 0.95, "s = [1 - d_inf (1 - exp(-e_max/e_d))] s_e"},
      {"mullins", "qi_boyce_like", "softening_limit", 1e-5, 0.95,
       "s = [1 - a_inf tanh(e_max/e_s)(1 - (e/e_max)^p)] s_e"},
      {"stiffness_damping", "stiffness_proportional", "beta_s", 1e-9, 10.0, "s = beta E_t(e) e'"},
      {"stiffness_damping", "fractional", "coefficient_kPa_s_pow_q", 1e-6, 1e4,
       "s = c D^q e (Maxwell bank of H(tau) = c sin(q pi)/pi tau^-q)"},
      {"stiffness_damping", "secant_proportional", "beta_s", 1e-9, 10.0, "s = beta (s_e(e)/e) e'"},
      {"strain_dependent_prony", "power_law", "exponent_c", 1e-5, 8.0, "a_j -> a_j l^-c"},
      {"strain_dependent_prony", "exponential", "rate_k", 1e-5, 8.0, "a_j -> a_j exp(k e)"},
      {"strain_dependent_prony", "linear_per_term", "slope_K", 1e-5, 50.0, "a_j -> a_j (1 + K w_j e)"},
  };
  return forms;
}

const std::vector<std::string>& effect_families() {
  static const std::vector<std::string> families{"pneumatic", "friction", "mullins", "stiffness_damping",
                                                 "strain_dependent_prony"};
  return families;
}

std::vector<const EffectForm*> forms_of_family(const std::string& family) {
  std::vector<const EffectForm*> out;
  for (const auto& f : effect_forms())
    if (f.family == family) out.push_back(&f);
  return out;
}

const EffectForm& find_form(const std::string& family, const std::string& form) {
  for (const auto& f : effect_forms())
    if (f.family == family && f.form == form) return f;
  throw std::invalid_argument("unknown effect form " + family + "/" + form);
}

EffectSpec draw_effect_shape(const EffectForm& form, const BaseFoam& foam, Random& random) {
  EffectSpec s{form.family, form.form, {}};
  auto& p = s.parameters;
  p[form.magnitude] = std::sqrt(form.magnitude_lo * form.magnitude_hi);
  const std::string key = form.family + "/" + form.form;
  if (key == "pneumatic/stretch_maxwell") {
    p["modulus_exponent"] = random.uniform(1.0, 3.0);
    p["time_s"] = random.log_uniform(0.005, 0.2);
    p["time_exponent"] = random.uniform(0.5, 2.0);
  } else if (key == "pneumatic/darcy") {
    p["permeability_exponent"] = random.uniform(1.0, 3.0);
    p["air_viscosity_Pa_s"] = 1.8e-5;
    p["drainage_length_mm"] = 40.0;
  } else if (key == "pneumatic/power_law_dashpot") {
    p["rate_exponent_q"] = random.uniform(0.5, 0.8);
    p["stretch_exponent_m"] = random.uniform(0.5, 2.0);
  } else if (form.family == "friction") {
    p["yield_strain"] = random.log_uniform(0.003, 0.03);
    if (form.form == "bouc_wen") {
      p["loading_share_b"] = random.uniform(0.5, 0.9);
      p["exponent_n"] = random.uniform(1.0, 2.0);
    } else if (form.form == "dahl") {
      p["exponent_a"] = random.uniform(0.5, 2.0);
    }
  } else if (key == "mullins/ogden_roxburgh") {
    p["m_kPa"] = random.uniform(0.05, 0.3) * foam.energy_kPa(0.75);
    p["beta"] = random.uniform(0.05, 0.3);
  } else if (key == "mullins/exponential_damage") {
    p["damage_strain"] = random.uniform(0.1, 0.5);
  } else if (key == "mullins/qi_boyce_like") {
    p["softening_strain"] = random.uniform(0.1, 0.5);
    p["recovery_exponent"] = random.uniform(1.0, 3.0);
  } else if (key == "stiffness_damping/fractional") {
    p["order_q"] = random.uniform(0.3, 0.7);
  } else if (key == "strain_dependent_prony/linear_per_term") {
    for (std::size_t j = 0; j < foam.prony.size(); ++j) p["weight_" + std::to_string(j)] = random.uniform(0.2, 1.0);
  }
  return s;
}

void add_derived_parameters(EffectSpec& s) {
  auto& p = s.parameters;
  if (s.family == "pneumatic" && s.form == "darcy") {
    // C = eta R^2/(8 K0): eta [kPa s] = 1e-3 x [Pa s], R [mm], K0 [mm^2].
    const double eta_kPa_s = p["air_viscosity_Pa_s"] * 1e-3, R = p["drainage_length_mm"];
    p["permeability_mm2"] = eta_kPa_s * R * R / (8.0 * p["resistance_kPa_s"]);
  }
  if (s.family == "friction") p["stiffness_kPa"] = p["yield_stress_kPa"] / p["yield_strain"];
  if (s.family == "mullins" && s.form == "ogden_roxburgh") p["r"] = 1.0 / p["inverse_r"];
}

}  // namespace foreign_bench
