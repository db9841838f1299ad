// The start scan of a joint candidate (diagnose.cpp, Scan::effect: the effect's own parameters in turn with the base
// factors held, then half a decade either side, a value kept only when it lowers chi2 by 0.1 %), on data of the independent generator
// (tests/foreign, its own program): campaign c047 of seed 2025 (the benchmark's): Jenkins friction z += k de,
// |z| <= s_y (k 1.11 kPa, s_y 0.0080 kPa: it yields at 0.72 % strain) on a stiff 65 kg/m3 foam. The fitted base leaves
// the 25 % sweep at 1.9x noise: at 20 Hz the displacement amplitude is small enough for the slider to stick, at 1 Hz it
// slides, so |E*| rises with frequency. From raw data, as a user runs it (`cushion diagnose CAMPAIGN --candidates
// friction`, fit included):
//  - friction is named and brings every test within 1.5x noise;
//  - its fitted stiffness and yield stress are within a factor 3 of the truth's (our friction branch with no hardening is
//    a Jenkins element, in Green-Lagrange strain, which is the engineering strain at these amplitudes; the base refitted
//    with it takes up part of the slider's stiffness: measured k 0.92 kPa, s_y 0.0035 kPa).
// The session-14 scan (every parameter in turn, the base factors too, no half-decade step, any lower chi2 kept) ended
// at a yield stress 40x too small and dBIC -25 (measured 2026-11-25): "the base calibration is the first suspect".
//
// A pair's start (Scan::added_effect): the best single's fit and the added effect's own single fit, only the added
// effect's parameters scanned. Campaign c015 of the same seed: a Maxwell air branch whose modulus and time grow with
// compression (h' = E0 l^-p e' - h/(tau0 l^-m)) plus Jenkins friction, on a soft 50 kg/m3 foam. Rescanning both
// effects' parameters (session 15) ended the friction + air-flow pair at dBIC 1392 and named friction +
// strain-dependent Prony (1398); from this start the pair reaches 1964 and chi2/N 1.77 (measured 2026-11-25, all five
// candidates).
//
// Two parameters scanned together (the catalogue's scan_with: pneumatic's permeability K and trapped-air modulus M, which
// set the Maxwell time eta R^2/(8 K M) between them). Campaign c038 of the same seed with every effect sized by what a
// base refitted by the generator leaves (`--base-refit scale`, 30x noise): a Maxwell air branch
// h' = E0 l^-p e' - h/(tau0 l^-m) (E0 8.6 kPa, p 1.12, tau0 77 ms, m 1.09) on a soft 50 kg/m3 foam. Scanned in turn,
// no single move of K or M from the start (K 1e-3 mm^2, M 100 kPa: a Maxwell time of 36 us) found the branch and
// Levenberg-Marquardt switched it off (M at its 1e6 kPa bound: dBIC 691, below the base refit's 715; measured
// 2026-11-27). Scanned together (2026-11-28): dBIC 29711 against the base refit's 749, with the truth's spring and time
// (fitted M 7.9 kPa, Maxwell time c0/M at J = 1 83 ms; our spring is M J^-2 in a uniaxial test at nu = 0).
//
// The scan scored with the base compensated (diagnose.cpp TrialScore: each trial's chi2 after the best linear step of
// the base factors, the start then moved by that step). Campaign c036 of seed 2025: the same Maxwell air branch (E0
// 0.89 kPa, p 1.93, tau0 7.0 ms, m 1.60) on a stiff 65 kg/m3 foam, which `cushion fit` took largely into its 16 ms Prony
// term (g 0.18 against the truth's base 0.11): the fitted base leaves the sweeps at 2.5x noise. Scored with the base
// held, every trial of the air flow only added to that term, the scan kept the branch off and Levenberg-Marquardt ended
// in a soft-spring basin (M 0.06 kPa, K at its bound: dBIC -25.6, "the base calibration is the first suspect";
// 2026-11-28 benchmark). Compensated (2026-11-29): pneumatic, dBIC 109.6, every test within 1.5x noise, M 1.55 kPa and
// Maxwell time 11 ms (our spring is M J^-2 at nu = 0: M is E0 there).
//
// The air flow's drag (pneumatic pressure_share 0, the form diagnose fits: catalogue diagnose_value). Campaign c025 of the scale set: a 1D Darcy pressure
// s = C e'/l^(n+1) (C 0.055 kPa s, n 2.03: K0 6.5e-5 mm^2) on a soft 50 kg/m3 foam. Our isotropic pressure also pushes
// the free laterals of the dynamic tests out, so its damping saturates (45x and 74x noise on the sweeps with the truth's
// base and air); the pneumatic fit ended at chi2/N 38 and stiffness damping was named first (2026-11-28, before the
// drag). With the drag: pneumatic first, every test within 2x noise, K0 and the exponent n - 1 near the truth's.
//
// The hyperfoam exponents refitted with the candidate (`--refit-exponents`, diagnose base_exponents; off by default,
// docs/physics.md 9.8). Scale-set c054, our own strain-dependent Prony form a_j l^-c (c 0.46) on a stiff 65 kg/m3 foam:
// with only the mu_i refitted the single stopped at chi2/N 3.15 (c 0.28) and friction + air flow was named (2026-11-28,
// as in the default run); with the exponents, strain-dependent Prony, every test within 1.5x noise, c within 0.15.
//
// The leading singles polished (diagnose polished_singles, default 2: refitted from their own fit with every Prony time
// and hyperfoam exponent free too, and ranked by that fit). Scale-set c024, a_j l^-c (c 1.23) on a random foam: without
// the polish strain-dependent Prony is named but leaves dyn_25 at 6.0x noise (c 0.88; chi2/N 14.7, converged; on the
// truth's exact base the same candidate reaches chi2/N 1.01 with c 1.226: the base `cushion fit` placed, not the
// effect's form, stops it); polished, every test within 1.5x and c within 0.15. Scale-set c012, a_j (1 + K w_j e)
// with its own weight per Prony term (not our form): without the polish friction is named first (chi2 1793 against
// strain-dependent Prony's 4600, 2026-11-28 benchmark); polished, strain-dependent Prony first.
//
// The air flow's second start (catalogue second_start: its trapped-air modulus 0, a Darcy dashpot, beside the Maxwell
// start at 100 kPa), where its rate exponent q is fitted too (catalogue fitted_only_without: held at 1 in the Maxwell
// branch), with a permeability exponent n_K down to -2. Scale-set c037, a power-law dashpot s = c0 l^-m |e'|^q (q 0.71,
// m 1.21) on a stiff 65 kg/m3 foam. From the Maxwell start alone (q and n_K free there too) the air flow stopped in a
// soft-spring basin (M 0.46 kPa, dBIC 565) and stiffness damping was named (dBIC 2559, 2026-11-28); from the dashpot
// start the air flow reaches dBIC 2749 with q 0.734 and n_K + 2 = 1.31 (the truth's m: our drag's nominal stress goes
// as l^-(n_K + 2)).
//
// Mullins' second start (catalogue second_start: strain_scale 0.3, the softening driven by the Biot strain norm instead
// of the energy, docs/physics.md 5.2 and 9.10). Scale-set c035, exponential damage s = [1 - d_inf (1 - exp(-e_max/e_d))]
// s_e (d_inf 0.15, e_d 0.29) on a random foam: from the energy start alone Mullins was switched off (r at its bound
// 1000, dBIC -56) and friction was named (2026-11-28); from the strain start Mullins reaches dBIC 227, chi2/N 1.01, every
// test within 1.83x noise (since the composition of Mullins' relaxation share with strain-dependent Prony, 2026-11-29:
// Mullins + strain-dependent Prony, dBIC 253.8, chi2/N 0.90, the same 1.83x on dyn_25). Since the damage start reads
// its estimate relative to the base refit's hysteresis (docs/physics.md 9.28, 2026-12-05) Mullins is fitted best from
// the damage start there (d_inf 0.160, e_d 0.114 against the truth's 0.154, 0.294; dBIC 239.6, chi2/N 0.94, dyn_25 at
// 1.98x, the sweep the truth itself leaves at 2.79x on the seed-2025 set without scaling). Scale-set c052, Qi-Boyce-like s = s_e [1 - a tanh(e_max/e_s)(1 - (e/e_max)^p)] (a 0.42,
// e_s 0.19, p 2.13) on a soft 50 kg/m3 foam: the energy start's Mullins (dBIC 2.595e4) was below friction's (2.855e4)
// and friction + Mullins was named; from the strain start Mullins leads (3.128e4) and Mullins + friction is named.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "foreign_program.hpp"
#include "material/effect_catalog.hpp"

namespace fs = std::filesystem;

namespace {

/// Campaign `name` of the benchmark's set of `seed` (default 2025; 60 campaigns, 10 pairs, 10 controls), generated alone
/// (`--only`, the same as in the whole set) in a fresh folder, and its truth.json; `options`: more generator options.
struct BenchCampaign {
  fs::path set, dir;
  nlohmann::json truth;
};
BenchCampaign bench_campaign(const std::string& tag, const std::string& name, const std::string& options = "",
                             int seed = 2025) {
  BenchCampaign c;
  c.set = cushion::foreign_program::generate(tag, 60, seed, 10, 10, options + " --only " + name);
  c.dir = c.set / name;
  std::ifstream in(c.dir / "truth.json");
  c.truth = nlohmann::json::parse(in);
  return c;
}

/// Diagnoses campaign c from raw data with stiffness damping and air flow the candidates: stiffness damping named and
/// every test within 1.5x noise after it. Returns the stiffness-damping entry of the fragment (null when not named).
nlohmann::json expect_stiffness_damping_named(const BenchCampaign& c) {
  const nlohmann::json d = cushion::foreign_program::diagnose_raw(c.dir, "--candidates stiffness_damping,pneumatic");
  if (d.at("winner") != "stiffness_damping") {
    ADD_FAILURE() << d.at("verdict");
    return nullptr;
  }
  for (const auto& t : d.at("candidates").at(0).at("compare").at("tests"))
    EXPECT_LT(t.at("error_over_noise").get<double>(), 1.5) << t.at("name");
  return d.at("fragment").at("effects").at(0);
}

/// A fitted pneumatic fragment entry's spring M [kPa] and Maxwell time at J = 1, c0/M with c0 = eta R^2/(8 K) [kPa s],
/// each within a factor 3 of the truth's stretch-Maxwell E0 and tau0 (the fragment lists the fitted parameters; the
/// rest are the catalogue's defaults).
void expect_air_branch_within_3x(const nlohmann::json& air, const nlohmann::json& maxwell) {
  auto value = [&air](const std::string& key) {
    for (const auto& p : cushion::material::find_effect("pneumatic")->parameters)
      if (p.name == key) return air.value(key, p.default_value);
    throw std::invalid_argument(key);
  };
  const double eta_kPa_s = value("air_viscosity_Pa_s") * 1e-3, R = value("drainage_length_mm");
  const double c0_kPa_s = eta_kPa_s * R * R / (8.0 * value("permeability_mm2"));
  const double spring = value("air_modulus_kPa") / maxwell.at("modulus_kPa").get<double>();
  const double time = c0_kPa_s / value("air_modulus_kPa") / maxwell.at("time_s").get<double>();
  EXPECT_LT(std::abs(std::log(spring)), std::log(3.0)) << "fitted/truth spring " << spring;
  EXPECT_LT(std::abs(std::log(time)), std::log(3.0)) << "fitted/truth Maxwell time " << time;
}

/// Diagnoses an Ogden-Roxburgh campaign from raw data (by default with Mullins the only candidate): Mullins named, every
/// test within 1.5x noise after it, and r, m, beta within 10 % of the truth's (a tolerance on the fit; each test gives
/// the misfit measured). Returns the report.
nlohmann::json expect_ogden_roxburgh_recovered(const BenchCampaign& c,
                                               const std::string& options = "--candidates mullins",
                                               const std::string& output = "diag") {
  EXPECT_EQ(c.truth.at("forms").at(0).get<std::string>(), "ogden_roxburgh") << "the generator's mix changed";
  const nlohmann::json& truth = c.truth.at("parameters").at("mullins");
  const nlohmann::json d = cushion::foreign_program::diagnose_raw(c.dir, options, output);
  if (d.at("winner") != "mullins") {
    ADD_FAILURE() << d.at("verdict");
    return d;
  }
  for (const auto& t : d.at("candidates").at(0).at("compare").at("tests"))
    EXPECT_LT(t.at("error_over_noise").get<double>(), 1.5) << t.at("name");
  const nlohmann::json& mullins = d.at("fragment").at("effects").at(0);
  for (const char* key : {"r", "m_kPa", "beta"})
    EXPECT_NEAR(mullins.value(key, 0.0), truth.at(key).get<double>(), 0.1 * truth.at(key).get<double>()) << key;
  return d;
}

}  // namespace

TEST(DiagnoseStart, WeakJenkinsFrictionIsFoundFromTheScanOfItsOwnParameters) {
  const BenchCampaign c = bench_campaign("diagnose_start", "c047");
  ASSERT_EQ(c.truth.at("forms").at(0).get<std::string>(), "jenkins") << "the generator's mix changed";
  const nlohmann::json& jenkins = c.truth.at("parameters").at("friction");

  const nlohmann::json d = cushion::foreign_program::diagnose_raw(c.dir, "--candidates friction");
  ASSERT_EQ(d.at("winner"), "friction") << d.at("verdict");
  EXPECT_TRUE(d.at("winner_at_noise_level").get<bool>()) << d.at("verdict");
  const nlohmann::json& fitted = d.at("fragment").at("effects").at(0);
  // The generator's Jenkins element is nominal: the named friction, fitted again at stretch exponent 1 (the nominal
  // element in this test, docs/physics.md 5.2b; diagnose step 4c), keeps that form, and its k and s_y are then the
  // truth's own, within 30 % (measured 2026-12-08: 0.92 and 0.83 of the truth's; dBIC 6.1 at n = 0 -> 23.9).
  EXPECT_EQ(fitted.value("stretch_exponent", 0.0), 1.0);
  for (const char* key : {"stiffness_kPa", "yield_stress_kPa"}) {
    const double ratio = fitted.at(key).get<double>() / jenkins.at(key).get<double>();
    EXPECT_LT(std::abs(std::log(ratio)), std::log(1.3)) << key << ": fitted/truth " << ratio;
  }
  fs::remove_all(c.set);
}

TEST(DiagnoseStart, AirFlowWithJenkinsFrictionIsNamedAsAPairFromTheScanOfTheAddedEffect) {
  const BenchCampaign c = bench_campaign("diagnose_pair_start", "c015");
  ASSERT_EQ(c.truth.at("forms"), nlohmann::json({"stretch_maxwell", "jenkins"})) << "the generator's mix changed";

  const nlohmann::json d =
      cushion::foreign_program::diagnose_raw(c.dir, "--candidates friction,pneumatic,strain_dependent_prony");
  const std::string winner = d.at("winner");
  EXPECT_TRUE(winner == "friction + pneumatic" || winner == "pneumatic + friction") << d.at("verdict");
  fs::remove_all(c.set);
}

TEST(DiagnoseStart, MaxwellAirFlowIsFoundFromTheScanOfPermeabilityAndAirModulusTogether) {
  const BenchCampaign c = bench_campaign("diagnose_air_start", "c038", "--base-refit scale");
  ASSERT_EQ(c.truth.at("forms").at(0).get<std::string>(), "stretch_maxwell") << "the generator's mix changed";
  const nlohmann::json& maxwell = c.truth.at("parameters").at("pneumatic");

  const nlohmann::json d = cushion::foreign_program::diagnose_raw(c.dir, "--candidates pneumatic");
  ASSERT_EQ(d.at("winner"), "pneumatic") << d.at("verdict");
  EXPECT_GT(d.at("candidates").at(0).at("delta_bic").get<double>(),
            10.0 * d.at("base_refit").at("delta_bic").get<double>());
  expect_air_branch_within_3x(d.at("fragment").at("effects").at(0), maxwell);
  fs::remove_all(c.set);
}

TEST(DiagnoseStart, MaxwellAirFlowAbsorbedByTheFittedPronyIsFoundFromTheBaseCompensatedScan) {
  const BenchCampaign c = bench_campaign("diagnose_air_absorbed", "c036");
  ASSERT_EQ(c.truth.at("forms").at(0).get<std::string>(), "stretch_maxwell") << "the generator's mix changed";
  const nlohmann::json& maxwell = c.truth.at("parameters").at("pneumatic");

  const nlohmann::json d = cushion::foreign_program::diagnose_raw(c.dir, "--candidates pneumatic,stiffness_damping");
  ASSERT_EQ(d.at("winner"), "pneumatic") << d.at("verdict");
  EXPECT_TRUE(d.at("winner_at_noise_level").get<bool>()) << d.at("verdict");
  expect_air_branch_within_3x(d.at("fragment").at("effects").at(0), maxwell);
  fs::remove_all(c.set);
}

TEST(DiagnoseStart, DarcyAirFlowOnAFreeSpecimenIsNamedWithTheDrag) {
  const BenchCampaign c = bench_campaign("diagnose_air_drag", "c025", "--base-refit scale");
  ASSERT_EQ(c.truth.at("forms").at(0).get<std::string>(), "darcy") << "the generator's mix changed";
  const nlohmann::json& darcy = c.truth.at("parameters").at("pneumatic");

  const nlohmann::json d = cushion::foreign_program::diagnose_raw(c.dir, "--candidates pneumatic,stiffness_damping");
  ASSERT_EQ(d.at("winner").get<std::string>().rfind("pneumatic", 0), 0u) << d.at("verdict");
  for (const auto& t : d.at("candidates").at(0).at("compare").at("tests"))
    EXPECT_LT(t.at("error_over_noise").get<double>(), 2.0) << t.at("name");
  const nlohmann::json& air = d.at("fragment").at("effects").at(0);
  ASSERT_EQ(air.at("kind"), "pneumatic");
  EXPECT_LT(air.at("pressure_share").get<double>(), 0.5);
  const double K = air.at("permeability_mm2").get<double>() / darcy.at("permeability_mm2").get<double>();
  EXPECT_LT(std::abs(std::log(K)), std::log(2.0)) << "fitted/truth K0 " << K;
  EXPECT_NEAR(air.at("permeability_exponent").get<double>(), darcy.at("permeability_exponent").get<double>() - 1.0, 0.5);
  fs::remove_all(c.set);
}

TEST(DiagnoseStart, PowerLawStrainDependentPronyIsNamedWithTheBaseExponentsRefitted) {
  const BenchCampaign c = bench_campaign("diagnose_sdprony_start", "c054", "--base-refit scale");
  ASSERT_EQ(c.truth.at("forms").at(0).get<std::string>(), "power_law") << "the generator's mix changed";
  const double c_truth = c.truth.at("parameters").at("strain_dependent_prony").at("exponent_c").get<double>();

  const nlohmann::json d = cushion::foreign_program::diagnose_raw(
      c.dir, "--refit-exponents --candidates strain_dependent_prony,friction,pneumatic");
  ASSERT_EQ(d.at("winner"), "strain_dependent_prony") << d.at("verdict");
  for (const auto& t : d.at("candidates").at(0).at("compare").at("tests"))
    EXPECT_LT(t.at("error_over_noise").get<double>(), 1.5) << t.at("name");
  EXPECT_NEAR(d.at("fragment").at("effects").at(0).at("coefficient_c").get<double>(), c_truth, 0.15);
  fs::remove_all(c.set);
}

TEST(DiagnoseStart, PowerLawStrainDependentPronyReachesTheNoiseOnceItsBaseIsPolished) {
  const BenchCampaign c = bench_campaign("diagnose_sdprony_polish", "c024", "--base-refit scale");
  ASSERT_EQ(c.truth.at("forms").at(0).get<std::string>(), "power_law") << "the generator's mix changed";
  const double c_truth = c.truth.at("parameters").at("strain_dependent_prony").at("exponent_c").get<double>();

  const nlohmann::json d =
      cushion::foreign_program::diagnose_raw(c.dir, "--candidates strain_dependent_prony,friction");
  ASSERT_EQ(d.at("winner").get<std::string>().rfind("strain_dependent_prony", 0), 0u) << d.at("verdict");
  const nlohmann::json& w = d.at("candidates").at(0);
  EXPECT_TRUE(w.at("polished").get<bool>());
  for (const auto& t : w.at("compare").at("tests"))
    EXPECT_LT(t.at("error_over_noise").get<double>(), 1.5) << t.at("name");
  EXPECT_NEAR(d.at("fragment").at("effects").at(0).at("coefficient_c").get<double>(), c_truth, 0.15);
  fs::remove_all(c.set);
}

TEST(DiagnoseStart, LinearPerTermStrainDependentPronyIsRankedFirstOnceTheLeadersArePolished) {
  const BenchCampaign c = bench_campaign("diagnose_sdprony_rank", "c012", "--base-refit scale");
  ASSERT_EQ(c.truth.at("forms").at(0).get<std::string>(), "linear_per_term") << "the generator's mix changed";

  const nlohmann::json d =
      cushion::foreign_program::diagnose_raw(c.dir, "--candidates strain_dependent_prony,friction");
  ASSERT_EQ(d.at("winner").get<std::string>().rfind("strain_dependent_prony", 0), 0u) << d.at("verdict");
  fs::remove_all(c.set);
}

// A challenger polished against a reference polished alike (diagnose --polish-challengers, default 1), ranked after
// the leader it does not beat by the evidence threshold. Campaign c021 of the seed-2026 scale set (a set this was not
// tuned on): an exponential strain-dependent Prony factor a_j exp(k e) on a random foam, small next to the noise (the
// fitted base leaves it at 1.9x). Before the polish friction (dBIC 25.1) and air flow (18.2) beat the base refit
// (-41.9) and strain-dependent Prony does not (-3.4). With its base's Prony times and exponents free, strain-dependent
// Prony reaches dBIC 141 against the base refit polished alike at -86 and friction polished at 136, and brings every
// test within 1.05x noise (docs/physics.md 9.29). Ranked by dBIC alone that named it; but such near ties went the wrong
// way as often (9.29, 9.48), so a challenger within dBIC 10 of the leader is ranked after it, and the verdict names it
// as the equal rival with the test that would separate the two. Without challengers (0) nothing says that the true
// family explains the data as well.
TEST(DiagnoseStart, ANearMissPolishedAsAChallengerIsTheLeadersEqualNotItsSuccessor) {
  const BenchCampaign c = bench_campaign("diagnose_sdprony_challenger", "c021", "--base-refit scale", 2026);
  ASSERT_EQ(c.truth.at("forms").at(0).get<std::string>(), "exponential") << "the generator's mix changed";
  const std::string candidates = "--candidates strain_dependent_prony,friction,pneumatic";

  const nlohmann::json d = cushion::foreign_program::diagnose_raw(c.dir, candidates);
  ASSERT_EQ(d.at("winner"), "friction") << d.at("verdict");
  const nlohmann::json& sdp = d.at("candidates").at(1);
  ASSERT_EQ(sdp.at("name"), "strain_dependent_prony");
  EXPECT_TRUE(sdp.at("challenger").get<bool>());
  EXPECT_TRUE(sdp.at("supported").get<bool>());
  EXPECT_NE(sdp.at("support_note").get<std::string>().find("ranked after friction"), std::string::npos);
  const double leader = d.at("candidates").at(0).at("delta_bic").get<double>();
  EXPECT_GT(sdp.at("delta_bic").get<double>(), leader);  // ahead by dBIC, within the threshold
  EXPECT_LE(sdp.at("delta_bic").get<double>(), leader + 10.0);
  EXPECT_GT(sdp.at("delta_bic").get<double>(), d.at("polished_base_refit").at("delta_bic").get<double>() + 10.0);
  for (const auto& t : sdp.at("compare").at("tests"))
    EXPECT_LT(t.at("error_over_noise").get<double>(), 1.5) << t.at("name");
  ASSERT_TRUE(d.at("rival").is_object()) << d.at("verdict");
  EXPECT_EQ(d.at("rival").at("name"), "strain_dependent_prony");
  EXPECT_NE(d.at("verdict").get<std::string>().find("cannot tell friction from strain_dependent_prony"),
            std::string::npos)
      << d.at("verdict");

  const nlohmann::json off =
      cushion::foreign_program::diagnose_raw(c.dir, candidates + " --polish-challengers 0", "off");
  EXPECT_EQ(off.at("winner"), "friction") << off.at("verdict");
  EXPECT_FALSE(off.contains("polished_base_refit"));
  EXPECT_FALSE(off.at("rival").is_object() && off.at("rival").at("name") == "strain_dependent_prony");
  fs::remove_all(c.set);
}

// An effect whose fitted base is already within 1.5x noise on every test is named all the same when the candidates'
// evidence says so (DiagnoseOptions::stop_at_noise off, the default; docs/physics.md 9.33). Campaign c052 of the
// seed-2026 scale set: an exponential strain-dependent Prony factor a_j exp(k e) on a random foam; the base `cushion fit` places on it
// leaves 1.44x noise at worst, and before, diagnose stopped there ("No effect is missing"). Measured 2026-12-06:
// strain-dependent Prony at dBIC 57 against the base refit's -44 and friction's 47; on the 20 controls of two sets every
// candidate ended at least 6.6 below the base refit (docs/physics.md 9.33).
TEST(DiagnoseStart, AnEffectWithinTheNoisePerTestIsNamedFromTheEvidenceOfAllResiduals) {
  const BenchCampaign c = bench_campaign("diagnose_at_noise", "c052", "--base-refit scale", 2026);
  ASSERT_EQ(c.truth.at("forms").at(0).get<std::string>(), "exponential") << "the generator's mix changed";
  const std::string candidates = "--candidates strain_dependent_prony,friction";

  const nlohmann::json d = cushion::foreign_program::diagnose_raw(c.dir, candidates);
  EXPECT_TRUE(d.at("at_noise_level").get<bool>());
  ASSERT_EQ(d.at("winner"), "strain_dependent_prony") << d.at("verdict");
  EXPECT_GT(d.at("candidates").at(0).at("delta_bic").get<double>(),
            d.at("base_refit").at("delta_bic").get<double>() + 10.0);
  for (const auto& t : d.at("candidates").at(0).at("compare").at("tests"))
    EXPECT_LT(t.at("error_over_noise").get<double>(), 1.5) << t.at("name");

  const nlohmann::json stop = cushion::foreign_program::diagnose_raw(c.dir, candidates + " --stop-at-noise", "stop");
  EXPECT_TRUE(stop.at("winner").is_null());
  EXPECT_EQ(stop.at("verdict").get<std::string>().rfind("No effect is missing", 0), 0u) << stop.at("verdict");
  EXPECT_TRUE(stop.at("candidates").empty());
  fs::remove_all(c.set);
}

/// A power-law air dashpot campaign diagnosed from raw data with air flow and stiffness damping as the candidates:
/// air flow must be named and bring every test within `max_ratio` x noise. Returns the fitted air-flow entry of the
/// fragment and the truth's dashpot parameters (rate_exponent_q, stretch_exponent_m).
struct DashpotFit {
  nlohmann::json air, truth;
};
DashpotFit diagnose_air_dashpot(const BenchCampaign& c, double max_ratio) {
  EXPECT_EQ(c.truth.at("forms").at(0).get<std::string>(), "power_law_dashpot") << "the generator's mix changed";
  const nlohmann::json d = cushion::foreign_program::diagnose_raw(c.dir, "--candidates pneumatic,stiffness_damping");
  EXPECT_EQ(d.at("winner"), "pneumatic") << d.at("verdict");
  for (const auto& t : d.at("candidates").at(0).at("compare").at("tests"))
    EXPECT_LT(t.at("error_over_noise").get<double>(), max_ratio) << t.at("name");
  const nlohmann::json& air = d.at("fragment").at("effects").at(0);
  EXPECT_EQ(air.at("kind"), "pneumatic");
  return {air, c.truth.at("parameters").at("pneumatic")};
}

TEST(DiagnoseStart, PowerLawAirDashpotIsNamedAirFlowFromItsDashpotStart) {
  const BenchCampaign c = bench_campaign("diagnose_air_dashpot", "c037", "--base-refit scale");
  const DashpotFit f = diagnose_air_dashpot(c, 2.0);
  const double nan = std::nan("");
  EXPECT_NEAR(f.air.value("rate_exponent", nan), f.truth.at("rate_exponent_q").get<double>(), 0.05);
  // our drag's nominal stress goes as l^-(n_K + 2) at nu = 0 (docs/physics.md 5.1), the truth's as l^-m
  EXPECT_NEAR(f.air.value("permeability_exponent", nan) + 2.0, f.truth.at("stretch_exponent_m").get<double>(), 0.3);
  fs::remove_all(c.set);
}

// The dashpot start's rate exponent q and permeability exponent n_K scanned together (catalogue scan_with): between them
// they set how the drag's loss grows with frequency (omega^(2 - q) at a constant acceleration amplitude) and how it
// changes from one preload to the other (l^-(n_K + 2)), so that a move of either alone from the start (q 1, n_K 2) only
// trades one test for the other. Campaign c016 of the seed-2026 scale set (a set the start scan was not tuned on): a
// power-law dashpot s = c0 l^-m |e'|^q (q 0.70, m 0.64: nearly no stretch dependence, n_K = m - q - 1 = -1.06) on a
// stiff 65 kg/m3 foam. Scanned in turn, the dashpot start ended at dBIC 2358 (Levenberg-Marquardt stopped by its 12
// iterations), the Maxwell start's 2828 was kept, and stiffness damping was named (3967 polished against 3097, the
// sweeps at 2.6x and 2.2x noise; 2026-12-05 benchmark). Scanned together: the dashpot start reaches 3327, polished
// 4187, air flow is named and every test falls within 1.2x noise (measured 2026-12-05), q near the truth's.
TEST(DiagnoseStart, PowerLawAirDashpotIsFoundFromTheJointScanOfItsRateAndStretchExponents) {
  const BenchCampaign c = bench_campaign("diagnose_air_dashpot_2026", "c016", "--base-refit scale", 2026);
  const DashpotFit f = diagnose_air_dashpot(c, 1.5);
  EXPECT_NEAR(f.air.value("rate_exponent", std::nan("")), f.truth.at("rate_exponent_q").get<double>(), 0.1);
  fs::remove_all(c.set);
}

/// The mullins entry of a diagnosis' effects fragment (in material::composition_order: strain_dependent_prony first).
const nlohmann::json& mullins_in_fragment(const nlohmann::json& d) {
  for (const auto& e : d.at("fragment").at("effects"))
    if (e.at("kind") == "mullins") return e;
  throw std::runtime_error("no mullins in the fragment");
}

TEST(DiagnoseStart, ExponentialDamageIsNamedMullinsWithAStrainDrivenSoftening) {
  const BenchCampaign c = bench_campaign("diagnose_mullins_strain", "c035", "--base-refit scale");
  ASSERT_EQ(c.truth.at("forms").at(0).get<std::string>(), "exponential_damage") << "the generator's mix changed";

  // Mullins first: since Mullins' relaxation share composes with strain-dependent Prony (docs/physics.md 5.2) the
  // pair Mullins + strain-dependent Prony beats the single by dBIC 27 here (a second family the truth does not have;
  // docs/physics.md 9.10), but it explains only 9-11 % of the chi2 Mullins leaves, and a pair must explain 25 % (9.13).
  // The candidates are Mullins, friction (named before the strain start) and strain-dependent Prony (the spurious pair);
  // the benchmark (tools/bench_diagnose.sh) ranks all five families (docs/ci_time.md: what the other two cost here).
  const nlohmann::json d =
      cushion::foreign_program::diagnose_raw(c.dir, "--candidates mullins,friction,strain_dependent_prony");
  ASSERT_EQ(d.at("winner").get<std::string>().rfind("mullins", 0), 0u) << d.at("verdict");
  for (const auto& t : d.at("candidates").at(0).at("compare").at("tests"))
    EXPECT_LT(t.at("error_over_noise").get<double>(), 2.1) << t.at("name");  // dyn_25 1.98x (above)
  // Driven by the strain, as the truth: the strain start's Biot-norm driver or the damage start's damage (whose
  // d_inf then lies within 0.05 of the truth's).
  const nlohmann::json& m = mullins_in_fragment(d);
  const double damage = m.value("damage_limit", 0.0);
  EXPECT_TRUE(m.value("strain_scale", 0.0) > 0.0 || damage > 0.0) << m.dump();
  if (damage > 0.0) {
    EXPECT_NEAR(damage, c.truth.at("parameters").at("mullins").at("damage_limit").get<double>(), 0.05);
  }
  fs::remove_all(c.set);
}

// Mullins' damage start (docs/physics.md 9.27: d_inf and e_d estimated from the slowest quasi-static test, the base's
// hyperfoam refitted to the first loadings over 1 - d). Campaign c017 of the seed-2027 scale set, exponential damage
// far beyond the noise (d_inf 0.95, e_d 0.423) on a stiff 65 kg/m3 foam: before the damage, friction was named and left
// 21.4x noise (2026-12-05 benchmark); with it (cushion's form, which the truth written in the catalogue follows within
// 1.11x noise) Mullins is named with d_inf 0.947 and e_d 0.4216 (the Ogden-Roxburgh factor at its bounds, off), the
// quasi-static tests within 1.5x noise and the sweeps at 3.8x and 3.9x: the polish may move the base's Prony times only
// within [0.316, 3.16] and the fit put its first time at 3.16 ms against the truth's 15.6 ms. The verdict then proposes
// the follow-up `--candidates mullins --polish-bounds 1,0.5` (a decade on each time, a factor 3.16 on each exponent),
// which brings every test within 1.5x noise (1.41x; docs/physics.md 9.35). With the cheaper Jacobian (9.36) the winner
// is Mullins + a spurious friction (dyn 3.07x), and its follow-up `--candidates mullins,friction --polish-bounds 1,0.5`
// names Mullins alone with every test within 1.5x (chi2/N 0.779). Those runs hold the Mullins beta at 0.1
// (`--no-polish-mullins-beta`) and do not continue a polish stopped by the iteration limit (`--no-continue-polish`:
// continued, Mullins with beta held reaches the noise too, 2026-12-07, docs/physics.md 9.44); by default beta is fitted
// after the polish (9.41-9.42) and Mullins alone brings every test within 1.5x at once (chi2/N 0.785).
TEST(DiagnoseStart, ExponentialDamageFarBeyondTheNoiseIsNamedMullinsFromItsDamageStart) {
  const BenchCampaign c = bench_campaign("diagnose_mullins_damage", "c017", "--base-refit scale", 2027);
  ASSERT_EQ(c.truth.at("forms").at(0).get<std::string>(), "exponential_damage") << "the generator's mix changed";
  const nlohmann::json& truth = c.truth.at("parameters").at("mullins");

  // Mullins against friction, the family named before the damage start.
  const nlohmann::json d = cushion::foreign_program::diagnose_raw(
      c.dir, "--candidates mullins,friction --no-polish-mullins-beta --no-continue-polish");
  ASSERT_EQ(d.at("winner").get<std::string>().rfind("mullins", 0), 0u) << d.at("verdict");
  const nlohmann::json& mullins = mullins_in_fragment(d);
  EXPECT_NEAR(mullins.at("damage_limit").get<double>(), truth.at("damage_limit").get<double>(), 0.05);
  EXPECT_NEAR(mullins.at("damage_strain").get<double>() / truth.at("damage_strain").get<double>(), 1.0, 0.1);
  for (const auto& t : d.at("candidates").at(0).at("compare").at("tests"))
    EXPECT_LT(t.at("error_over_noise").get<double>(), t.at("name").get<std::string>().starts_with("qs") ? 1.5 : 5.0)
        << t.at("name");
  // The follow-up as the verdict prints it: `--candidates WINNER --polish-bounds 1,0.5`, the winner Mullins or, since
  // the cheaper Jacobian (9.36), Mullins with a spurious friction.
  const std::string verdict = d.at("verdict").get<std::string>(), tail = " --polish-bounds 1,0.5";
  const std::size_t from = verdict.find("--candidates mullins"), to = verdict.find(tail, from);
  ASSERT_TRUE(from != std::string::npos && to != std::string::npos) << verdict;
  const std::string follow_up =
      verdict.substr(from, to - from) + tail + " --no-polish-mullins-beta --no-continue-polish";
  // and, after it, the Mullins beta held at 0.1 (docs/physics.md 9.41)
  EXPECT_NE(verdict.find("--polish-mullins-beta", to), std::string::npos) << verdict;

  const nlohmann::json wide = cushion::foreign_program::diagnose_raw(c.dir, follow_up, "diag_wide");
  ASSERT_EQ(wide.at("winner").get<std::string>(), "mullins") << wide.at("verdict");
  for (const auto& t : wide.at("candidates").at(0).at("compare").at("tests"))
    EXPECT_LT(t.at("error_over_noise").get<double>(), 1.5) << t.at("name");
  EXPECT_EQ(wide.at("verdict").get<std::string>().find("--polish-bounds"), std::string::npos) << wide.at("verdict");

  // By default the beta is fitted after the polish: Mullins alone, every test within 1.5x noise, no follow-up.
  const nlohmann::json beta =
      cushion::foreign_program::diagnose_raw(c.dir, "--candidates mullins,friction", "diag_beta");
  ASSERT_EQ(beta.at("winner").get<std::string>(), "mullins") << beta.at("verdict");
  for (const auto& t : beta.at("candidates").at(0).at("compare").at("tests"))
    EXPECT_LT(t.at("error_over_noise").get<double>(), 1.5) << t.at("name");
  EXPECT_EQ(beta.at("verdict").get<std::string>().find("--polish-"), std::string::npos) << beta.at("verdict");
  fs::remove_all(c.set);
}

// The damage start with the recoverable softening off (EffectInfo::recoverable_softening_parameter, docs/physics.md
// 9.48). Campaign c000 of the seed-2026 scale set: an exponential damage d = d_inf (1 - exp(-e/e_d)) alone (d_inf
// 0.133, e_d 0.222; the Ogden-Roxburgh factor off), near the noise (the fitted base leaves 1.65x). The damage start's
// estimate (d_inf 0.06, e_d 0.115 from the slowest test's unloading over loading) is that of a damage alone; started
// beside the catalogue's Ogden-Roxburgh r = 2 it ended at dBIC 64 and friction was named (277.6); with r at its maximum
// the single reaches 294 (308 polished), d_inf 0.135 and e_d 0.208, every test within 1.06x noise.
TEST(DiagnoseStart, AWeakExponentialDamageIsNamedMullinsFromADamageStartWithoutRecoverableSoftening) {
  const BenchCampaign c = bench_campaign("diagnose_pure_damage", "c000", "--base-refit scale", 2026);
  ASSERT_EQ(c.truth.at("forms").at(0).get<std::string>(), "exponential_damage") << "the generator's mix changed";
  const nlohmann::json& truth = c.truth.at("parameters").at("mullins");

  const nlohmann::json d = cushion::foreign_program::diagnose_raw(c.dir, "--candidates mullins,friction");
  ASSERT_EQ(d.at("winner").get<std::string>(), "mullins") << d.at("verdict");
  const nlohmann::json& mullins = mullins_in_fragment(d);
  EXPECT_NEAR(mullins.at("damage_limit").get<double>(), truth.at("damage_limit").get<double>(), 0.02);
  EXPECT_NEAR(mullins.at("damage_strain").get<double>() / truth.at("damage_strain").get<double>(), 1.0, 0.15);
  EXPECT_GT(mullins.at("r").get<double>(), 100.0);  // the recoverable softening below 1 %, as the truth's
  for (const auto& t : d.at("candidates").at(0).at("compare").at("tests"))
    EXPECT_LT(t.at("error_over_noise").get<double>(), 1.5) << t.at("name");
  fs::remove_all(c.set);
}

// Levenberg-Marquardt's Jacobian from the sweeps at 32 steps a fitted cycle (DiagnoseOptions::jacobian_steps_per_cycle,
// docs/physics.md 9.36). Campaign c051 of the seed-2027 scale set: stiffness-proportional damping on a random foam,
// the fitted base within 2.9x noise. With the cheaper Jacobian alone its fit "converged" after 35 model runs at dBIC -56
// (the trust region shrank to nothing where the cheaper direction no longer lowered the cost) and no effect was named;
// a fit that converges early goes on with the model's own Jacobian, and stiffness damping is named as with the
// model's own Jacobian throughout (polished dBIC 164.2 against 163.7), every test within 1.5x noise.
TEST(DiagnoseStart, AFitThatConvergesOnTheCheaperJacobianGoesOnWithTheModelsOwn) {
  const BenchCampaign c = bench_campaign("diagnose_cheaper_jacobian", "c051", "--base-refit scale", 2027);
  ASSERT_EQ(c.truth.at("forms").at(0).get<std::string>(), "stiffness_proportional") << "the generator's mix changed";

  const nlohmann::json d = cushion::foreign_program::diagnose_raw(c.dir, "--candidates stiffness_damping");
  ASSERT_EQ(d.at("winner").get<std::string>(), "stiffness_damping") << d.at("verdict");
  for (const auto& t : d.at("candidates").at(0).at("compare").at("tests"))
    EXPECT_LT(t.at("error_over_noise").get<double>(), 1.5) << t.at("name");
  fs::remove_all(c.set);
}

// The damping time beta_s is scanned in decades (catalogue scan_decades: the start scan tries 1e-7..1e-1 s, then
// Levenberg-Marquardt fits beta itself; docs/physics.md 9.47). Seed-2026 c046 with a third sweep at 65 % preload
// (`--extra-preload 0.65`; the other records as in the set): stiffness-proportional damping s = beta E_t(e) e' (beta
// 3.65e-3 s) on a soft 50 kg/m3 foam. Scanned about 1e-4 s by factors 0, 0.3, 3, 10, the single kept beta at 0, where
// Levenberg-Marquardt found no step (dBIC -31, not supported; air flow named with dyn_50 at 3.3x noise, 2026-12-07).
// Scanned in decades, stiffness damping is named, every test within 1.5x noise, beta within 10 % of the truth's on the
// nominal tangent (measured 3.67e-3 s).
TEST(DiagnoseStart, TheDampingTimeIsScannedInDecadesAndAThirdPreloadSeparatesItFromAirFlow) {
  const BenchCampaign c =
      bench_campaign("diagnose_damping_decades", "c046", "--base-refit scale --extra-preload 0.65", 2026);
  ASSERT_EQ(c.truth.at("forms").at(0).get<std::string>(), "stiffness_proportional") << "the generator's mix changed";
  const double beta_truth = c.truth.at("parameters").at("stiffness_damping").at("beta_s").get<double>();

  const nlohmann::json damping = expect_stiffness_damping_named(c);
  ASSERT_FALSE(damping.is_null());
  EXPECT_NEAR(damping.at("beta_s").get<double>(), beta_truth, 0.1 * beta_truth);
  EXPECT_EQ(damping.at("nominal_tangent_share").get<double>(), 1.0);
  fs::remove_all(c.set);
}

TEST(DiagnoseStart, QiBoyceLikeSofteningIsNamedMullinsFirstFromItsStrainStart) {
  const BenchCampaign c = bench_campaign("diagnose_mullins_qi_boyce", "c052", "--base-refit scale");
  ASSERT_EQ(c.truth.at("forms").at(0).get<std::string>(), "qi_boyce_like") << "the generator's mix changed";

  // Mullins against friction, the family named first before the strain start (the other three trail the polished
  // Mullins by more than dBIC 2.3e4, 2026-12-03).
  const nlohmann::json d = cushion::foreign_program::diagnose_raw(c.dir, "--candidates mullins,friction");
  ASSERT_EQ(d.at("winner").get<std::string>().rfind("mullins", 0), 0u) << d.at("verdict");
  EXPECT_GT(mullins_in_fragment(d).at("strain_scale").get<double>(), 0.0);
  fs::remove_all(c.set);
}

// The extra-damping family's fractional form (docs/physics.md 5.4b: stiffness_damping derivative_order q, a spring-pot
// beta_s (2 pi f_r)^(1-q) C_d D^q E; diagnose fits q from 1). Scale-set c028: the generator's s = c D^q e (q 0.53, a
// Maxwell bank of its own over 1e-5..1e4 s) on a random foam. With the dashpot alone (q held at 1, the code before
// 2026-12-01) stiffness damping was named with a spurious strain-dependent Prony and left 3.6x noise; with q fitted the
// single reaches the noise and q lands within 0.15 of the truth's (measured 0.571).
TEST(DiagnoseStart, FractionalDampingIsNamedStiffnessDampingWithItsOrderFitted) {
  const BenchCampaign c = bench_campaign("diagnose_fractional", "c028", "--base-refit scale");
  ASSERT_EQ(c.truth.at("forms").at(0).get<std::string>(), "fractional") << "the generator's mix changed";
  const double q_truth = c.truth.at("parameters").at("stiffness_damping").at("order_q").get<double>();

  const nlohmann::json damping = expect_stiffness_damping_named(c);
  ASSERT_FALSE(damping.is_null());
  EXPECT_NEAR(damping.at("derivative_order").get<double>(), q_truth, 0.15);
  fs::remove_all(c.set);
}

// The stiffness-damping single is fitted with the Green-Lagrange and with the nominal current tangent (catalogue
// nominal_tangent_share: held, second start 0; docs/physics.md 5.4d, 9.40) and the better kept. Seed-2026 c040: a
// secant-proportional damping s = beta (s_e/e) e' on a soft 50 kg/m3 foam, which no form of the catalogue writes; with
// the Green-Lagrange tangent alone its stiffness damping left 2.71x noise (2026-12-06 benchmark), with the nominal one
// every test is within 1.5x and the fragment says which tangent it took.
TEST(DiagnoseStart, SecantDampingIsNamedStiffnessDampingOnTheNominalTangent) {
  const BenchCampaign c = bench_campaign("diagnose_nominal_tangent", "c040", "--base-refit scale", 2026);
  ASSERT_EQ(c.truth.at("forms").at(0).get<std::string>(), "secant_proportional") << "the generator's mix changed";
  const nlohmann::json damping = expect_stiffness_damping_named(c);
  ASSERT_FALSE(damping.is_null());
  EXPECT_EQ(damping.at("nominal_tangent_share").get<double>(), 1.0);
  fs::remove_all(c.set);
}

// Mullins' beta (the growth of the Ogden-Roxburgh energy scale m + beta W_max), held at 0.1 by the single fits, fitted
// after the polish from the best polished single (DiagnoseOptions::fit_polished_only, on by default; catalogue
// polished_only; docs/physics.md 9.41-9.42). Scale-set c043: Ogden-Roxburgh softening (r 1.78, m 0.50 kPa, beta
// 0.214) on a soft 50 kg/m3 foam. With beta held the polished Mullins single leaves dyn_25 at 4.99x and qs_12 at 3.21x noise
// (2026-12-06 benchmark; checked 2026-12-07 with `--no-polish-mullins-beta`: this test then fails on both counts);
// with it every test is within 1.1x noise and r, m, beta are within 2 % of the truth's (measured 2026-12-07: 1.787,
// 0.497 kPa, 0.212).
TEST(DiagnoseStart, OgdenRoxburghBetaIsFittedAfterThePolish) {
  const BenchCampaign c = bench_campaign("diagnose_mullins_beta", "c043", "--base-refit scale");
  expect_ogden_roxburgh_recovered(c);
  fs::remove_all(c.set);
}

// The best single's polish stopped by the iteration limit with a test beyond noise is continued from there
// (DiagnoseOptions::continue_unfinished_polish, on by default; docs/physics.md 9.44). Seed-2027 c039: a power-law
// strain-dependent Prony series (a_j -> a_j l^-c, c 0.80) on a 79 kg/m3 foam with four hyperfoam terms and five Prony
// terms; the truth written in cushion's catalogue reproduces it within 1.28x noise. The polish alone stops after 12
// iterations at dyn_25 1.64x noise (2026-12-07 benchmark; checked 2026-12-07 with `--no-continue-polish`: this test then
// fails on dyn_25); continued, every test is within 1.4x and c within 10 % of the truth's (measured 1.14x, c 0.78).
TEST(DiagnoseStart, APolishStoppedByTheIterationLimitBeyondNoiseIsContinued) {
  const BenchCampaign c = bench_campaign("diagnose_continue_polish", "c039", "--base-refit scale", 2027);
  ASSERT_EQ(c.truth.at("forms").at(0).get<std::string>(), "power_law") << "the generator's mix changed";
  const double truth_c = c.truth.at("parameters").at("strain_dependent_prony").at("exponent_c").get<double>();

  const nlohmann::json d = cushion::foreign_program::diagnose_raw(c.dir, "--candidates strain_dependent_prony");
  ASSERT_EQ(d.at("winner"), "strain_dependent_prony") << d.at("verdict");
  for (const auto& t : d.at("candidates").at(0).at("compare").at("tests"))
    EXPECT_LT(t.at("error_over_noise").get<double>(), 1.4) << t.at("name");
  EXPECT_NEAR(d.at("fragment").at("effects").at(0).at("coefficient_c").get<double>(), truth_c, 0.1 * truth_c);
  fs::remove_all(c.set);
}

// A single named alone whose fit stopped at the iteration limit with a test beyond noise is fitted on after the ranking
// (DiagnoseOptions::continuation_rounds, 3 by default; docs/physics.md 9.45). Seed-2026 c059: Ogden-Roxburgh Mullins
// (r 1.99, m 0.51 kPa, beta 0.16) on a soft 50 kg/m3 foam. After its polish and beta's continuation Mullins leaves qs_12
// at 3.83x noise (measured 2026-12-07 with `--continuation-rounds 1`: this test then fails on qs_12, qs_120, qs_600 and
// dyn_50); two more rounds take every test within 1.31x and r, m within 2 %, beta within 4 % of the truth's (measured
// 1.998, 0.509 kPa, 0.165).
// With friction a candidate too, the rounds are fitted ahead, beside the Mullins + friction pair, before the ranking
// names Mullins alone (RoundsAhead, docs/physics.md 9.46): the same Mullins model, to the last bit (dBIC 61687.34997 both
// ways, 2026-12-07).
TEST(DiagnoseStart, ANamedSingleStoppedByTheIterationLimitIsFittedOn) {
  const BenchCampaign c = bench_campaign("diagnose_refine_named", "c059", "--base-refit scale", 2026);
  const nlohmann::json alone = expect_ogden_roxburgh_recovered(c);
  const nlohmann::json beside = expect_ogden_roxburgh_recovered(c, "--candidates mullins,friction", "diag_pair");
  bool pair_fitted = false;
  for (const auto& k : beside.at("candidates")) pair_fitted = pair_fitted || k.at("name") == "mullins + friction";
  EXPECT_TRUE(pair_fitted) << "no pair for the rounds to be fitted beside";
  EXPECT_EQ(alone.at("candidates").at(0).at("delta_bic").get<double>(),
            beside.at("candidates").at(0).at("delta_bic").get<double>());
  EXPECT_EQ(alone.at("fragment"), beside.at("fragment"));
  fs::remove_all(c.set);
}

// The continuation starts exactly where the polish ended (a Prony term the polish left at a_i = 0 is not revived from
// a fitted point: with_dead_prony_terms_revived), so it can only lower the chi2. Seed-2027 c024 (Qi-Boyce-like Mullins on a soft 50 kg/m3
// foam), friction alone: its polish stops at the iteration limit (dBIC 8853) with a term at tau 1 s dead (g 1.2e-5);
// revived, the continuation started at chi2 9508 instead of 5459 and ended at dBIC 8645, not kept; from the polish's
// own end it reaches 9083 (2026-12-07).
TEST(DiagnoseStart, APolishContinuationStartsWhereThePolishEnded) {
  const BenchCampaign c = bench_campaign("diagnose_continue_start", "c024", "--base-refit scale", 2027);
  ASSERT_EQ(c.truth.at("forms").at(0).get<std::string>(), "qi_boyce_like") << "the generator's mix changed";
  const nlohmann::json continued = cushion::foreign_program::diagnose_raw(c.dir, "--candidates friction");
  const nlohmann::json polished =
      cushion::foreign_program::diagnose_raw(c.dir, "--candidates friction --no-continue-polish", "diag_polish");
  const nlohmann::json& p = polished.at("candidates").at(0);
  ASSERT_NE(p.at("message").get<std::string>().find("NO_CONVERGENCE"), std::string::npos) << "the polish converged";
  EXPECT_GT(continued.at("candidates").at(0).at("delta_bic").get<double>(), p.at("delta_bic").get<double>() + 10.0);
  fs::remove_all(c.set);
}

// A pair must explain DiagnoseOptions::pair_share (25 %) of the chi2 its best single leaves (docs/physics.md 9.13).
// Scale-set c041: Bouc-Wen friction on a soft 50 kg/m3 foam, a single effect. Friction + Mullins beats friction alone by
// dBIC 17 (the 2026-12-01 benchmark, all candidates) but explains 13 % of the chi2 friction leaves: friction alone is
// named; with the dBIC rule alone (--pair-share 0) the spurious pair is, when friction's polish is not continued
// (`--no-continue-polish`; continued, friction alone ranks above the pair: 2026-12-07, docs/physics.md 9.44).
TEST(DiagnoseStart, ASecondEffectThatExplainsLittleOfWhatTheSingleLeavesIsNotNamed) {
  const BenchCampaign c = bench_campaign("diagnose_pair_share", "c041", "--base-refit scale");
  ASSERT_EQ(c.truth.at("forms").at(0).get<std::string>(), "bouc_wen") << "the generator's mix changed";

  const nlohmann::json d = cushion::foreign_program::diagnose_raw(c.dir, "--candidates friction,mullins");
  EXPECT_EQ(d.at("winner"), "friction") << d.at("verdict");
  bool noted = false;
  for (const auto& k : d.at("candidates"))
    if (k.at("name") == "friction + mullins") noted = !k.at("support_note").get<std::string>().empty();
  EXPECT_TRUE(noted) << "the pair's table row says why it is not named";
  const nlohmann::json d0 = cushion::foreign_program::diagnose_raw(
      c.dir, "--candidates friction,mullins --pair-share 0 --no-continue-polish", "diag_share0");
  EXPECT_EQ(d0.at("winner"), "friction + mullins") << d0.at("verdict");
  fs::remove_all(c.set);
}

// Pairs are the best single with each of the next three that explain something alone (DiagnoseOptions::pairs_from 4;
// docs/physics.md 9.15, 9.27). Seed-2025 c001: Qi-Boyce-like Mullins softening plus an exponentially strain-dependent Prony
// series on a soft 50 kg/m3 foam. Alone, strain-dependent Prony is 4th (dBIC 31.7, behind Mullins 1399, friction 774 and
// air flow 295; 2026-12-02), so with the 3 best singles it was never paired and Mullins alone was named (2.18x noise
// left); paired with the polished Mullins single it is named with it, every test within 1.6x noise.
TEST(DiagnoseStart, ASecondFamilyRankedFourthAloneIsStillPairedWithTheBest) {
  const BenchCampaign c = bench_campaign("diagnose_pairs_from", "c001");
  ASSERT_EQ(c.truth.at("forms").at(0).get<std::string>(), "qi_boyce_like") << "the generator's mix changed";
  ASSERT_EQ(c.truth.at("forms").at(1).get<std::string>(), "exponential") << "the generator's mix changed";

  const nlohmann::json d = cushion::foreign_program::diagnose_raw(c.dir, "");
  ASSERT_EQ(d.at("winner"), "mullins + strain_dependent_prony") << d.at("verdict");
  for (const auto& t : d.at("candidates").at(0).at("compare").at("tests"))  // measured: at most 1.52 (qs_12)
    EXPECT_LT(t.at("error_over_noise").get<double>(), 1.6) << t.at("name");
  fs::remove_all(c.set);
}

// A joint pair whose scanned start leaves its second effect switched off (here: ends no better than its best single
// alone) is fitted again from the plain sum of the two single fits (diagnose.cpp fit_pairs; docs/physics.md 9.19).
// Scale-set c046: Jenkins friction (k 2.29 kPa, s_y 0.0129 kPa) with Ogden-Roxburgh Mullins (r 28.7) on a stiff 65
// kg/m3 foam. The polished Mullins base has taken part of the slider's stiffness, so the friction single's values
// overshoot there; the added-effect scan stepped the friction stiffness down to 1.1e-3 kPa, the pair ended at Mullins'
// own chi2 (dBIC 578 against the single's 590) and Mullins alone was named, dyn_25 at 2.06x noise (2026-12-02
// benchmark). From the sum (2026-12-03): dBIC 675, every test within 1.16x noise, r 28.2, k 4.1 kPa, s_y 0.016 kPa.
TEST(DiagnoseStart, APairWhoseScanSwitchesTheAddedEffectOffIsFittedFromBothSingles) {
  const BenchCampaign c = bench_campaign("diagnose_pair_sum", "c046", "--base-refit scale");
  ASSERT_EQ(c.truth.at("forms").at(0).get<std::string>(), "jenkins") << "the generator's mix changed";
  ASSERT_EQ(c.truth.at("forms").at(1).get<std::string>(), "ogden_roxburgh") << "the generator's mix changed";

  const nlohmann::json d = cushion::foreign_program::diagnose_raw(c.dir, "--candidates mullins,friction");
  ASSERT_EQ(d.at("winner"), "mullins + friction") << d.at("verdict");
  for (const auto& t : d.at("candidates").at(0).at("compare").at("tests"))
    EXPECT_LT(t.at("error_over_noise").get<double>(), 1.5) << t.at("name");
  const nlohmann::json& truth = c.truth.at("parameters");
  for (const auto& e : d.at("fragment").at("effects")) {
    if (e.at("kind") == "mullins") {
      EXPECT_NEAR(e.at("r").get<double>() / truth.at("mullins").at("r").get<double>(), 1.0, 0.25);
    }
    if (e.at("kind") != "friction") continue;
    for (const char* key : {"stiffness_kPa", "yield_stress_kPa"})  // within a factor 3, as for c047 above
      EXPECT_LT(std::abs(std::log(e.at(key).get<double>() / truth.at("friction").at(key).get<double>())), std::log(3.0))
          << key;
  }
  fs::remove_all(c.set);
}

// The refit from the plain sum also runs when the scanned pair beats its single but its second effect explains less
// than DiagnoseOptions::pair_stop_share (2 %) of the chi2 the single leaves: the scan switched it off (docs/physics.md
// 9.37). Seed-2026 c011: a stretch-Maxwell air flow (E0 6.0 kPa, tau0 88 ms) with Ogden-Roxburgh Mullins (r 7.6) on a
// stiff 65 kg/m3 foam. The added-effect scan stepped the air flow down: Mullins + air flow ended 4 dBIC above Mullins
// alone (0.4 % of the chi2 it leaves), so no refit ran and Mullins alone was named (2026-12-06 benchmark). From the sum
// the pair explains 70 % of it (dBIC 1.844e4 against 1.347e4) and is named, the air branch within a factor 3 of the
// truth's (measured: spring 5.6 kPa, Maxwell time 76 ms).
TEST(DiagnoseStart, APairJustAboveItsSingleWithTheAddedEffectSwitchedOffIsFittedFromBothSingles) {
  const BenchCampaign c = bench_campaign("diagnose_pair_share_sum", "c011", "--base-refit scale", 2026);
  ASSERT_EQ(c.truth.at("forms").at(0).get<std::string>(), "stretch_maxwell") << "the generator's mix changed";
  ASSERT_EQ(c.truth.at("forms").at(1).get<std::string>(), "ogden_roxburgh") << "the generator's mix changed";

  const nlohmann::json d = cushion::foreign_program::diagnose_raw(c.dir, "--candidates mullins,pneumatic");
  ASSERT_EQ(d.at("winner"), "mullins + pneumatic") << d.at("verdict");
  for (const auto& e : d.at("fragment").at("effects"))
    if (e.at("kind") == "pneumatic") expect_air_branch_within_3x(e, c.truth.at("parameters").at("pneumatic"));
  fs::remove_all(c.set);
}

// A Prony term the base fit left at g = 0 revived (diagnose.cpp revive_dead_prony_terms: a factor on a_i cannot move a
// zero, so every joint fit kept the term dead). Scale-set c002, Ogden-Roxburgh Mullins (r 4.39, m 1.15 kPa, beta 0.13)
// on a stiff 65 kg/m3 foam: `cushion fit` places the softened unloading in a 0.58 s Prony term (g 0.28 against the
// truth's 0.12 at 0.71 s) and holds the 32 ms term at 0 (the truth has g 0.033 at 92 ms). From there Mullins stopped at
// chi2/N 2.7 with the sweeps at 4.2x and 3.0x noise and Mullins + stiffness damping was named (2026-12-04 benchmark);
// with the term revived Mullins alone brings every test within 1.5x (measured 1.25x, chi2/N 0.80), r within 10 % of
// the truth's (docs/physics.md 9.24).
TEST(DiagnoseStart, OgdenRoxburghReachesTheNoiseOnceADeadPronyTermOfTheFitIsRevived) {
  const BenchCampaign c = bench_campaign("diagnose_or_revive", "c002", "--base-refit scale");
  ASSERT_EQ(c.truth.at("forms").at(0).get<std::string>(), "ogden_roxburgh") << "the generator's mix changed";

  const nlohmann::json d = cushion::foreign_program::diagnose_raw(c.dir, "--candidates mullins,stiffness_damping");
  const nlohmann::json fitted = nlohmann::json::parse(std::ifstream(c.dir / "diag" / "fit" / "material.json"));
  int dead = 0;  // the case this test is about: a fitted Prony term at g = 0
  for (const auto& t : fitted.at("viscoelastic").at("prony")) dead += t.at("g").get<double>() == 0.0;
  ASSERT_GE(dead, 1) << "the fit no longer leaves a Prony term at 0 on this campaign";
  ASSERT_EQ(d.at("winner"), "mullins") << d.at("verdict");
  for (const auto& t : d.at("candidates").at(0).at("compare").at("tests"))
    EXPECT_LT(t.at("error_over_noise").get<double>(), 1.5) << t.at("name");
  const double r_truth = c.truth.at("parameters").at("mullins").at("r").get<double>();
  EXPECT_NEAR(d.at("fragment").at("effects").at(0).at("r").get<double>() / r_truth, 1.0, 0.1);
  fs::remove_all(c.set);
}
