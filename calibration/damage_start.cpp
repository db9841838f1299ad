#include "calibration/damage_start.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>

#include "calibration/refit.hpp"
#include "calibration/segments.hpp"
#include "material/effect_mullins.hpp"

namespace cushion::calibration {
namespace {

/// The unloading samples of a record within (0, peak strain] beside its loading stress at the same strain (the loading
/// branch interpolated), and the viscous ratio expected there without damage: the reference model's unloading over its
/// loading at that strain, in [0, 1] (1 without a reference).
struct UnloadingPairs {
  std::vector<double> strain, unloading, loading, viscous_ratio;  ///< [-], [MPa], [MPa], [-]
};
UnloadingPairs unloading_pairs(const StressStrainRecord& rec, const Segments& s, const TestCompare* reference) {
  const MonotoneBranch loading = monotone_branch(rec.strain, rec.stress, s.load_begin, s.load_end, true);
  std::optional<MonotoneBranch> model_loading, model_unloading;
  const std::size_t n = reference ? reference->x.size() : 0;
  if (n > 0 && reference->unload_begin > 0 && reference->unload_begin < n) {
    model_loading = monotone_branch(reference->x, reference->model, 0, reference->unload_begin - 1, true);
    model_unloading = monotone_branch(reference->x, reference->model, reference->unload_begin, n - 1, false);
  }
  UnloadingPairs p;
  for (std::size_t j = s.unload_begin; j <= s.unload_end; ++j) {
    const double e = rec.strain[j];
    if (!(e > 0.0) || e > s.peak_strain) continue;
    p.strain.push_back(e);
    p.unloading.push_back(rec.stress[j]);
    p.loading.push_back(interpolate(loading.x, loading.y, e));
    double ratio = 1.0;
    if (model_loading && model_loading->x.size() > 1 && model_unloading->x.size() > 1) {
      const double load = interpolate(model_loading->x, model_loading->y, e);
      ratio = load > 0.0 ? std::clamp(interpolate(model_unloading->x, model_unloading->y, e) / load, 0.0, 1.0) : 1.0;
    }
    p.viscous_ratio.push_back(ratio);
  }
  return p;
}

/// Sum of squared differences [MPa^2] between the unloading and the loading times its viscous ratio times
/// (1 - d(e_p))/(1 - d(e)).
double unloading_misfit(const UnloadingPairs& p, double peak_strain, const LoadingDamage& d) {
  const double at_peak = d.factor(peak_strain);
  double sum = 0.0;
  for (std::size_t j = 0; j < p.strain.size(); ++j) {
    const double r = p.unloading[j] - p.loading[j] * p.viscous_ratio[j] * at_peak / d.factor(p.strain[j]);
    sum += r * r;
  }
  return sum;
}

/// The first loading of `t` as a refit target: its stresses over 1 - d(e), its segments cut at the peak (no hold, no
/// unloading), each sample weighed by its noise estimate. `scaled` holds the test with the divided record.
QuasiStaticTarget first_loading_target(const QuasiStaticTest& t, const TestNoise& noise, const LoadingDamage& d,
                                       QuasiStaticTest& scaled) {
  scaled = t;
  QuasiStaticTarget q{&scaled, detect_segments(t.record), {}};
  q.segments.unload_begin = q.segments.unload_end = q.segments.load_end + 1;
  q.segments.hold_duration = 0.0;
  q.segments.lift_off = false;
  for (double local : noise.stress_local) q.stress_sigma.push_back(noise.stress_weighting(local));
  for (std::size_t i = q.segments.load_begin; i <= q.segments.load_end; ++i) {  // stress and its noise over 1 - d
    const double factor = d.factor(std::max(0.0, scaled.record.strain[i]));
    scaled.record.stress[i] /= factor;
    if (i < q.stress_sigma.size()) q.stress_sigma[i] /= factor;
  }
  return q;
}

}  // namespace

double LoadingDamage::factor(double e_max) const {
  return material::MullinsEffect::damage_factor(limit, strain, e_max);
}

std::optional<LoadingDamage> estimate_loading_damage(const Campaign& campaign, const CompareResult* reference) {
  const QuasiStaticTest* slowest = nullptr;
  for (const QuasiStaticTest& t : campaign.quasi_static)
    if (t.prior.preflex_cycles == 0 && (!slowest || t.rate < slowest->rate)) slowest = &t;
  if (!slowest) return std::nullopt;
  const Segments s = detect_segments(slowest->record);
  if (s.load_end <= s.load_begin || s.unload_end <= s.unload_begin) return std::nullopt;
  const TestCompare* model = nullptr;
  if (reference)
    for (const TestCompare& t : reference->tests)
      if (t.kind == "quasi_static" && t.name == slowest->name && t.failure.empty() && t.noise.known &&
          t.noise_ratio() <= reference_noise_ratio)
        model = &t;
  const UnloadingPairs pairs = unloading_pairs(slowest->record, s, model);
  LoadingDamage best;
  double best_misfit = std::numeric_limits<double>::infinity();
  for (int k = 0; k <= 24; ++k)
    for (int n = 0; n <= 49; ++n) {
      const LoadingDamage d{0.02 * n, 0.03 * std::pow(100.0, k / 24.0)};
      const double misfit = unloading_misfit(pairs, s.peak_strain, d);
      if (misfit < best_misfit) best_misfit = misfit, best = d;
    }
  return best;
}

std::optional<material::MaterialSpec> damaged_loading_base(const material::MaterialSpec& base, const Campaign& campaign,
                                                           const std::vector<TestNoise>& noise,
                                                           const LoadingDamage& damage) {
  if (base.base != material::MaterialSpec::Base::hyperfoam || base.hyperfoam.empty() || base.prony.empty() ||
      base.moduli != material::ModuliConvention::long_term)
    return std::nullopt;
  try {
    std::vector<QuasiStaticTest> scaled(campaign.quasi_static.size());  // the targets point into it
    std::vector<QuasiStaticTarget> loadings;
    for (std::size_t k = 0; k < campaign.quasi_static.size(); ++k) {
      const QuasiStaticTest& t = campaign.quasi_static[k];
      if (t.prior.preflex_cycles > 0 || !noise[k].known) continue;  // not a virgin specimen; no weights
      QuasiStaticTarget q = first_loading_target(t, noise[k], damage, scaled[k]);
      if (q.segments.load_end + 2 < t.record.time.size()) loadings.push_back(std::move(q));
    }
    if (loadings.empty()) return std::nullopt;
    RefitOptions o;
    o.noise_weighted = true;
    const RefitResult r = refit({base.hyperfoam, base.prony}, campaign.specimen, loadings, {}, o);
    if (!r.converged || !r.stable) return std::nullopt;
    material::MaterialSpec s = base;
    s.hyperfoam = r.material.terms;
    return s;
  } catch (const std::exception&) {
    return std::nullopt;  // no usable refit: the start is not made
  }
}

}  // namespace cushion::calibration
