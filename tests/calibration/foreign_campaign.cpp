#include "foreign_campaign.hpp"

#include <cmath>
#include <fstream>
#include <memory>
#include <vector>

#include <nlohmann/json.hpp>

#include "calibration/lab.hpp"
#include "material/hyperfoam.hpp"
#include "io/csv.hpp"
#include "material/viscoelastic.hpp"

namespace cushion::foreign {

namespace {

namespace fs = std::filesystem;
using material::Material;
using material::PointResponse;

/// One increment of the axial law: nominal compression before/after, time step, and the base model's
/// nominal compressive stress at e_new with its derivative d s_base / d e.
struct Step {
  double e_old = 0.0, e_new = 0.0, dt = 0.0, s_base = 0.0, ds_base = 0.0;
};

/// An extra nominal compressive stress [MPa] as a function of the axial history (own state).
class AxialLaw {
 public:
  virtual ~AxialLaw() = default;
  virtual std::size_t size() const { return 0; }
  virtual double stress(const Step& s, std::span<const double> old, std::span<double> now) const = 0;
};

/// Wraps a model and adds the law's stress to S11 (F = diag(l, 1, 1): P11 = l S11, e = 1 - l).
/// Tangent: d s / d e by central differences of the law (state updates discarded).
class AxialLawMaterial final : public Material {
 public:
  AxialLawMaterial(std::shared_ptr<const Material> inner, std::shared_ptr<const AxialLaw> law)
      : inner_(std::move(inner)), law_(std::move(law)) {}
  std::size_t state_size() const override { return inner_->state_size() + law_->size(); }
  void initial_state(std::span<double> state) const override {
    inner_->initial_state(state.first(inner_->state_size()));
    for (double& x : state.subspan(inner_->state_size())) x = 0.0;
  }
  PointResponse integrate(const Mat3& F_old, const Mat3& F_new, double dt, std::span<const double> state_old,
                          std::span<double> state_new) const override {
    const std::size_t n = inner_->state_size();
    PointResponse r = inner_->integrate(F_old, F_new, dt, state_old.first(n), state_new.first(n));
    if (r.status == material::Status::failed) return r;
    const double l = F_new(0, 0);
    Step st{1.0 - F_old(0, 0), 1.0 - l, dt, -l * r.S(0), r.S(0) + l * l * r.dS_dE(0, 0)};
    const auto old = state_old.subspan(n);
    const auto now = state_new.subspan(n);
    const double s = law_->stress(st, old, now);
    std::vector<double> scratch(law_->size());
    const double h = 1e-7;
    Step p = st, m = st;
    p.e_new += h, p.s_base += h * st.ds_base;
    m.e_new -= h, m.s_base -= h * st.ds_base;
    const double ds = (law_->stress(p, old, scratch) - law_->stress(m, old, scratch)) / (2.0 * h);
    r.S(0) += -s / l;
    r.dS_dE(0, 0) += (ds / l + s / (l * l)) / l;
    return r;
  }
  Mat6c complex_tangent(const Mat3& F_base, double omega) const override {
    return inner_->complex_tangent(F_base, omega);  // unused: the lab measures in the time domain
  }
  std::string describe() const override { return "foreign axial law over " + inner_->describe(); }

 private:
  std::shared_ptr<const Material> inner_;
  std::shared_ptr<const AxialLaw> law_;
};

double rate(const Step& s) { return s.dt > 0.0 ? (s.e_new - s.e_old) / s.dt : 0.0; }

/// (1 - e^-x)/x, 1 at x = 0.
double relax_weight(double x) { return x > 1e-12 ? -std::expm1(-x) / x : 1.0; }

class PowerLawDashpot final : public AxialLaw {
 public:
  double eta = 0.0, m = 0.0, q = 1.0, regular = 1e-5;  ///< [MPa s^q], [-], [-], [1/s]
  double stress(const Step& s, std::span<const double>, std::span<double>) const override {
    const double v = rate(s);
    return eta * std::pow(1.0 / (1.0 - s.e_new), m) * v * std::pow(v * v + regular * regular, 0.5 * (q - 1.0));
  }
};

class BoucWen final : public AxialLaw {
 public:
  double A = 0.0, beta = 0.0, gamma = 0.0;  ///< [MPa], [1/-], [1/-]
  std::size_t size() const override { return 1; }
  double stress(const Step& s, std::span<const double> old, std::span<double> now) const override {
    const int sub = 16;
    const double de = (s.e_new - s.e_old) / sub;
    double z = old[0];
    auto f = [&](double zz) { return A - (beta * (zz * de >= 0.0 ? 1.0 : -1.0) + gamma) * std::abs(zz); };
    for (int k = 0; k < sub; ++k) {  // RK4 in e
      const double k1 = f(z), k2 = f(z + 0.5 * de * k1), k3 = f(z + 0.5 * de * k2), k4 = f(z + de * k3);
      z += de / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4);
    }
    now[0] = z;
    return z;
  }
};

class ExponentialDamage final : public AxialLaw {
 public:
  double d = 0.0, e_c = 1.0;
  std::size_t size() const override { return 1; }
  double stress(const Step& s, std::span<const double> old, std::span<double> now) const override {
    const double e_max = std::max(old[0], s.e_new);
    now[0] = e_max;
    return -d * (1.0 - std::exp(-(e_max - s.e_new) / e_c)) * s.s_base;
  }
};

class ExponentialPreloadProny final : public AxialLaw {
 public:
  std::shared_ptr<const material::Hyperelastic> base;
  std::vector<double> a, tau;
  double k = 0.0;
  std::size_t size() const override { return a.size(); }
  double s_inf(double e) const {
    Mat3 F = Mat3::Identity();
    F(0, 0) = 1.0 - e;
    return -(1.0 - e) * base->evaluate(F).S(0);
  }
  double stress(const Step& s, std::span<const double> old, std::span<double> now) const override {
    const double scale = std::exp(k * 0.5 * (s.e_old + s.e_new)) - 1.0;
    const double dS = s_inf(s.e_new) - s_inf(s.e_old);
    double sum = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) {
      const double x = s.dt / tau[i];
      now[i] = std::exp(-x) * old[i] + relax_weight(x) * scale * a[i] * dS;
      sum += now[i];
    }
    return sum;
  }
};

class MaxwellBank final : public AxialLaw {
 public:
  std::vector<double> E, tau;  ///< [MPa], [s]
  std::size_t size() const override { return E.size(); }
  double stress(const Step& s, std::span<const double> old, std::span<double> now) const override {
    double sum = 0.0;
    for (std::size_t i = 0; i < E.size(); ++i) {
      const double x = s.dt / tau[i];
      now[i] = std::exp(-x) * old[i] + relax_weight(x) * E[i] * (s.e_new - s.e_old);
      sum += now[i];
    }
    return sum;
  }
};

/// c (i w)^alpha over about 1e-3..1e3 rad/s by Maxwell elements one per half decade:
/// E_k = c tau_k^-alpha sin(alpha pi)/pi ln(10)/2 (quadrature of the power-law relaxation spectrum).
std::shared_ptr<MaxwellBank> fractional_bank(double c, double alpha) {
  auto b = std::make_shared<MaxwellBank>();
  for (int j = -8; j <= 6; ++j) {
    const double t = std::pow(10.0, 0.5 * j);
    b->tau.push_back(t);
    b->E.push_back(c * std::pow(t, -alpha) * std::sin(alpha * M_PI) / M_PI * std::log(10.0) * 0.5);
  }
  return b;
}

fs::path hidden_dir() { return fs::path(CUSHION_SOURCE_DIR) / "cases" / "hidden_effects"; }

}  // namespace

std::string to_string(ForeignCase c) {
  switch (c) {
    case ForeignCase::power_law_dashpot: return "power_law_dashpot";
    case ForeignCase::bouc_wen: return "bouc_wen";
    case ForeignCase::exponential_damage: return "exponential_damage";
    case ForeignCase::exponential_prony: return "exponential_prony";
    case ForeignCase::fractional_damping: return "fractional_damping";
    case ForeignCase::base_off: return "base_off";
    case ForeignCase::control: return "control";
  }
  return "?";
}

ForeignCampaign make_foreign_campaign(ForeignCase c, const fs::path& dir) {
  ForeignCampaign out;
  out.truth_base = material::read_material_file(hidden_dir() / "base_material.json").spec;
  material::MaterialSpec truth = out.truth_base;
  if (c == ForeignCase::base_off) truth.hyperfoam.push_back({0.0015, 6.0, 0.0});  // 1.5 kPa, alpha 6
  const material::MaterialDefinition def = material::build_material(truth, "foreign truth");
  std::shared_ptr<const Material> model = def.model;
  std::shared_ptr<const AxialLaw> law;
  switch (c) {
    case ForeignCase::power_law_dashpot: {
      auto p = std::make_shared<PowerLawDashpot>();
      p->eta = 0.6e-3, p->m = 1.5, p->q = 0.6;
      law = p, out.family = "pneumatic";
      break;
    }
    case ForeignCase::bouc_wen: {
      auto p = std::make_shared<BoucWen>();
      p->A = 0.012, p->beta = 0.75 * 0.012 / 0.35e-3, p->gamma = 0.25 * 0.012 / 0.35e-3;  // saturates at 0.35 kPa
      law = p, out.family = "friction";
      break;
    }
    case ForeignCase::exponential_damage: {
      auto p = std::make_shared<ExponentialDamage>();
      p->d = 0.25, p->e_c = 0.08;
      law = p, out.family = "mullins";
      break;
    }
    case ForeignCase::exponential_prony: {
      auto p = std::make_shared<ExponentialPreloadProny>();
      const auto* v = dynamic_cast<const material::Viscoelastic*>(def.model.get());
      p->base = def.elastic, p->a = v->relative_to_long_term(), p->k = 1.2;
      for (const auto& t : v->terms()) p->tau.push_back(t.tau);
      law = p, out.family = "strain_dependent_prony";
      break;
    }
    case ForeignCase::fractional_damping:
      law = fractional_bank(0.4e-3, 0.5);  // 0.4 kPa s^0.5; linear viscoelastic: the base Prony can represent it
      break;
    case ForeignCase::base_off:
    case ForeignCase::control:
      break;
  }
  if (law) model = std::make_shared<AxialLawMaterial>(model, law);

  calibration::LabSpecimen specimen;  // 80 mm cube, 65 kg/m^3
  calibration::LabNoise noise{4242, 0.005, 0.002};
  fs::remove_all(dir);
  fs::create_directories(dir);
  nlohmann::json manifest;
  manifest["description"] = "SYNTHETIC foreign campaign (test support, " + to_string(c) + ")";
  manifest["specimen"] = {{"length_mm", specimen.length}, {"width_mm", specimen.width},
                          {"thickness_mm", specimen.thickness}, {"density_kg_m3", specimen.density_kg_m3}};
  manifest["tests"] = nlohmann::json::array();
  unsigned long long stream = 0;
  const std::vector<std::pair<double, double>> rates{{30.0, 0.5}, {120.0, 2.0}, {480.0, 8.0}};  // mm/min, Hz (coarse)
  for (const auto& [rate_mm_min, hz] : rates) {
    calibration::QuasiStaticProtocol p;
    p.name = "qs_" + std::to_string(static_cast<int>(rate_mm_min));
    p.rate_mm_min = rate_mm_min, p.sample_hz = hz, p.prior.preflex_cycles = 0;
    calibration::QuasiStaticRecord rec = calibration::run_quasi_static(*model, specimen, p);
    calibration::add_force_noise(rec, noise, stream++);
    write_csv(dir / (p.name + ".csv"), {"time_s", "displacement_mm", "force_N"},
              {rec.time_s, rec.displacement_mm, rec.force_N}, {"SYNTHETIC foreign test " + p.name});
    manifest["tests"].push_back({{"kind", "quasi_static"}, {"name", p.name}, {"file", p.name + ".csv"},
                                 {"rate_mm_min", rate_mm_min}, {"use", rate_mm_min == 120.0 ? "calibration" : "validation"}});
  }
  for (double preload : {0.25, 0.40}) {
    calibration::DynamicProtocol p;
    p.name = "dyn_" + std::to_string(static_cast<int>(std::lround(preload * 100)));
    p.preload_strain = preload;
    p.frequencies_Hz = {1, 1.5, 2.5, 4, 6.5, 10, 15, 20};
    p.cycles = 8, p.fit_cycles = 4, p.steps_per_cycle = 64;
    const calibration::DynamicRecord rec = calibration::run_dynamic(*model, specimen, p, noise, stream++);
    write_csv(dir / (p.name + ".csv"), {"frequency_Hz", "dynamic_modulus_kPa", "phase_deg"},
              {rec.frequency_Hz, rec.dynamic_modulus_kPa, rec.phase_deg}, {"SYNTHETIC foreign test " + p.name});
    manifest["tests"].push_back({{"kind", "dynamic"}, {"name", p.name}, {"file", p.name + ".csv"},
                                 {"preload_strain", preload}, {"acceleration_amplitude_m_s2", p.acceleration_amplitude},
                                 {"cycles", p.cycles}, {"fit_cycles", p.fit_cycles},  // the protocol as run
                                 {"use", preload == 0.25 ? "calibration" : "validation"}});
  }
  out.manifest = dir / "campaign.json";
  std::ofstream(out.manifest) << manifest.dump(2) << "\n";
  return out;
}

}  // namespace cushion::foreign
