#pragma once
/// `cushion fit`: the paper's identification method (sections 3.2-3.4, steps 1-6), the conversion of
/// the Prony moduli for the solver (step 7) and the consistency refit (step 8), from a campaign to a
/// material, keeping every intermediate result for the report. Units: mm, N, s, MPa; strains and
/// stresses nominal, compression positive.
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "calibration/campaign.hpp"
#include "calibration/decomposition.hpp"
#include "calibration/fit_prony_conversion.hpp"
#include "calibration/hereditary_fit.hpp"
#include "calibration/refit.hpp"

namespace cushion::calibration {

enum class DefaultMaterial { paper, refit };

struct FitOptions {
  int terms = 3;                       ///< hyperfoam N (paper: 3)
  std::optional<double> nu = 0.0;      ///< fixed Poisson ratio; empty: fitted
  std::vector<double> tau = {0.01, 0.1, 1.0, 10.0, 100.0};  ///< Prony times [s]
  bool refit = true;                   ///< run step 8
  bool refit_on_all_tests = false;     ///< step 8 on every test (all rates and preloads), not only the calibration ones
  /// Step 8 weighs each residual by the test's own noise estimate (chi2, as compare and diagnose do) instead of relative
  /// to the peak stress and moduli: the base `diagnose` fits from raw data.
  bool noise_weighted_refit = false;
  /// Step 8 also refits with N + 1 hyperfoam terms (the exponent search and polish from the same start, the extra term
  /// starting at mu = 0) and keeps it when accepted and its joint cost is below extra_term_gain times the N-term
  /// refit's: a foam whose curve N terms cannot follow (a 4-term foam fitted with 3: long-term curve 1.01 % off, 0.29 %
  /// with 4). In a campaign with noise the cost floor is the noise, so the extra term seldom halves it. 0: N only.
  int extra_refit_terms = 1;
  double extra_term_gain = 0.5;
  DefaultMaterial default_material = DefaultMaterial::refit;  ///< the refit if accepted, else the paper's
  PronyNormalisation normalisation = PronyNormalisation::tangent;  ///< step 7 choice for the paper's material
  /// Step 6: E_inf = the hyperfoam's long-term tangent K_hf at the preload, only E_i fitted (1-20 Hz data cannot
  /// separate E_inf from the 100 s term; the free fit may return E_inf = 0). false: E_inf fitted (the paper's).
  bool prony_long_term_from_hyperfoam = true;
  HereditaryFitOptions hereditary;
  RefitOptions refit_options;          ///< its `schedule` is set from the two options below
  DynamicSchedule dynamic_schedule;    ///< paper 2.3 timing: 30 mm/min preload ramp, 20 cycles, last 10 measured
  bool relaxed_preload = false;        ///< model the dynamic test about a relaxed preload instead
};

/// Model (paper's material and refit) vs one test of the campaign.
struct TestComparison {
  std::string name, kind, use;  ///< kind "quasi_static" | "dynamic"; use "calibration" | "validation"
  std::optional<QuasiStaticPrediction> quasi_static_paper, quasi_static_refit;
  std::optional<DynamicPrediction> dynamic_paper, dynamic_refit;
  double error_paper = 0.0, error_refit = 0.0;  ///< qs: RMS/peak [-]; dynamic: RMS of |E*| relative error [-]
  /// Why the material's prediction of this test failed (its error NaN, reported "n/a (reason)"); empty: it ran.
  /// A failing prediction (e.g. the point driver not converging) never aborts the fit.
  std::string failure_paper, failure_refit;
};

struct FitResult {
  FitOptions options;
  std::string quasi_static_name, dynamic_name;
  // steps 1-2
  Segments segments;
  double pair_interval = 1.0;  ///< [s] loading-time interval of the pairs (paper: 1 s)
  StrainPairs pairs;
  std::vector<std::string> warnings;
  // step 3
  HereditaryFit hereditary;
  ProtocolCurve table2_curve;   ///< paper Table 2 modes on the paper protocol
  ProtocolCurve fitted_curve;   ///< fitted modes on the same protocol
  // step 4
  Decomposition decomposition;
  // step 5
  HyperfoamFit hyperfoam;
  // step 6
  PronyFit prony;       ///< used for the paper's material (E_inf per options.prony_long_term_from_hyperfoam)
  PronyFit prony_free;  ///< the paper's fit with E_inf free, always reported
  // step 7
  PronyConversion conversion;
  DynamicPrediction dynamic_normalisation_paper, dynamic_normalisation_tangent;       ///< calibration dynamic test
  QuasiStaticPrediction quasi_static_normalisation_paper, quasi_static_normalisation_tangent;
  PronyNormalisation run_normalisation = PronyNormalisation::tangent;  ///< used (options' unless unusable)
  std::string normalisation_failure_paper, normalisation_failure_tangent;  ///< why a normalisation gives no usable material (its errors n/a); empty: usable
  ViscoHyperfoam paper_material;  ///< hyperfoam + Prony with run_normalisation
  // step 8
  std::optional<RefitResult> refit;
  ViscoHyperfoam default_material;
  DefaultMaterial default_choice = DefaultMaterial::paper;
  std::string default_reason;
  std::string paper_problem, refit_problem;  ///< why a material file would be rejected (empty: usable; not written then)
  std::vector<TestComparison> comparisons;  ///< every test of the campaign
  std::vector<std::pair<std::string, double>> timings;  ///< stage, seconds
};

/// Runs the method on the campaign's calibration tests and compares with every test. Throws
/// InputError (naming the file) when the campaign lacks a calibration test of either kind or a
/// record does not look like a load/unload test.
FitResult fit_pipeline(const Campaign& campaign, const FitOptions& options, std::ostream& log);

/// The options of the base `cushion diagnose` fits from raw data: the defaults with the refit on every test
/// (all rates and preloads), each residual weighed by its noise, as diagnose weighs them, and the Prony times free
/// within half a decade (`cushion fit --refit-on all --refit-weights noise --free-tau`).
FitOptions diagnose_base_fit_options();

}  // namespace cushion::calibration
