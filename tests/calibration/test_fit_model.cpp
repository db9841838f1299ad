// The solver-model helpers of `cushion fit` (fit_model, fit_prony_conversion, abaqus_cards, plot):
// checked against closed forms of the uniaxial hyperfoam and the Prony series, and against the
// time-domain virtual lab.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "calibration/abaqus_cards.hpp"
#include "calibration/fit_model.hpp"
#include "calibration/fit_prony_conversion.hpp"
#include "calibration/plot.hpp"
#include "material/hyperfoam.hpp"

namespace cal = cushion::calibration;
namespace mat = cushion::material;

namespace {

// Truth of the shipped synthetic campaign (cases/materials/paper_table3.json) in MPa.
std::vector<mat::HyperfoamTerm> truth_terms(double nu = 0.0) {
  return {{0.010, 10.0, nu}, {0.0001, -2.0, nu}, {0.0005, 3.0, nu}};
}
const std::vector<double> table3_E = {0.0239, 0.0197, 0.00899, 0.0124, 0.00814};
const std::vector<double> table3_tau = {0.01, 0.1, 1.0, 10.0, 100.0};
constexpr double table3_E_inf = 0.00305;

/// Nominal compression stress of the closed form and its derivative by central differences.
double closed_form_stress(const std::vector<mat::HyperfoamTerm>& t, double eps, cal::Lateral lateral) {
  return cal::hyperfoam_uniaxial_stress(t, t.front().nu, lateral, {eps}).front();
}

}  // namespace

TEST(FitModel, PreloadTangentMatchesClosedFormUniaxialHyperfoam) {
  for (cal::Lateral lateral : {cal::Lateral::free, cal::Lateral::constrained}) {
    for (double nu : {0.0, 0.2}) {
      const auto terms = truth_terms(nu);
      const mat::Hyperfoam base(terms);
      const double eps = 0.25, h = 1e-5;
      const cal::PreloadTangent p = cal::preload_tangent(base, eps, lateral);
      const double sigma = closed_form_stress(terms, eps, lateral);
      const double K = (closed_form_stress(terms, eps + h, lateral) - closed_form_stress(terms, eps - h, lateral)) / (2 * h);
      EXPECT_NEAR(p.stress, sigma, 1e-9 * std::abs(sigma) + 1e-12);
      EXPECT_NEAR(p.K_hf, K, 1e-6 * K);  // central difference O(h^2)
      EXPECT_NEAR(p.K_v, p.K_hf - p.S11, 1e-12);
      EXPECT_NEAR(p.S11, -sigma / (1.0 - eps), 1e-9 * std::abs(sigma));
    }
  }
}

TEST(FitModel, DynamicModuliAreThePronyFactorOnTheMaterialTangent) {
  const auto terms = truth_terms();
  const cal::PronyConversion c = cal::convert_prony(table3_E_inf, table3_E, table3_tau, terms, 0.25);
  const cal::ViscoHyperfoam m{terms, c.tangent};
  const auto model = cal::build_model(m);
  const mat::Hyperfoam base(terms);
  const std::vector<double> f = {0.5, 1.0, 7.0, 20.0};
  const cal::DynamicModuli d = cal::model_dynamic_moduli(*model, base, 0.25, f);
  // (b) tangent normalisation: E*(w) = K_hf + sum E_i i w tau / (1 + i w tau) exactly (fit_model.hpp).
  const cal::DynamicModuli prony = cal::prony_moduli(c.preload.K_hf, table3_E, table3_tau, f);
  for (std::size_t i = 0; i < f.size(); ++i) {
    EXPECT_NEAR(d.storage[i], prony.storage[i], 1e-10 * prony.storage[i]);
    EXPECT_NEAR(d.loss[i], prony.loss[i], 1e-10 * prony.loss[i]);
  }
  // (a) paper normalisation: a_i = E_i / E_inf, the viscous part scaled by K_v / E_inf.
  EXPECT_NEAR(c.a_paper[0], table3_E[0] / table3_E_inf, 1e-12);
  EXPECT_NEAR(c.a_tangent[0], table3_E[0] / c.preload.K_v, 1e-12);
  const auto model_a = cal::build_model({terms, c.paper});
  const cal::DynamicModuli da = cal::model_dynamic_moduli(*model_a, base, 0.25, f);
  const double scale = c.preload.K_v / table3_E_inf;
  for (std::size_t i = 0; i < f.size(); ++i) EXPECT_NEAR(da.loss[i], scale * prony.loss[i], 1e-10 * scale * prony.loss[i]);
}

TEST(FitModel, FrequencyDomainModulusAgreesWithTheTimeDomainLab) {
  // Independent check: the virtual lab runs the point driver in time and measures with a sine fit.
  const auto terms = truth_terms();
  const cal::PronyConversion c = cal::convert_prony(table3_E_inf, table3_E, table3_tau, terms, 0.25);
  const auto model = cal::build_model({terms, c.tangent});
  cal::DynamicProtocol p;
  p.preload_strain = 0.25;
  p.acceleration_amplitude = 0.25;
  p.frequencies_Hz = {5.0, 12.0, 20.0};  // displacement amplitude <= 0.13 mm: linear regime
  p.cycles = 8;
  p.fit_cycles = 4;
  p.steps_per_cycle = 64;
  const cal::DynamicRecord lab = cal::run_dynamic(*model, cal::LabSpecimen{}, p, cal::LabNoise{}, 0);
  // The sines start right after the preload ramp: the frequency-domain model follows the same schedule.
  const cal::DynamicSchedule schedule{30.0, 80.0, p.cycles, p.fit_cycles};
  const cal::DynamicModuli d =
      cal::model_dynamic_moduli(*model, mat::Hyperfoam(terms), 0.25, p.frequencies_Hz, cal::Lateral::free, &schedule);
  for (std::size_t i = 0; i < p.frequencies_Hz.size(); ++i) {
    const double magnitude = std::hypot(d.storage[i], d.loss[i]) * 1e3;
    const double phase = std::atan2(d.loss[i], d.storage[i]) * 180.0 / std::numbers::pi;
    EXPECT_NEAR(lab.dynamic_modulus_kPa[i], magnitude, 0.005 * magnitude) << p.frequencies_Hz[i] << " Hz";
    EXPECT_NEAR(lab.phase_deg[i], phase, 0.3) << p.frequencies_Hz[i] << " Hz";
  }
}

TEST(FitModel, LongTermRatiosRoundTrip) {
  const std::vector<double> a = {0.5, 2.0, 0.1};
  const auto prony = cal::prony_from_long_term_ratios(a, {0.1, 1.0, 10.0});
  double sum_g = 0.0;
  for (const auto& t : prony) sum_g += t.g;
  EXPECT_LT(sum_g, 1.0);
  const auto back = cal::long_term_ratios(prony);
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(back[i], a[i], 1e-14);
}

TEST(AbaqusCards, HyperfoamAndPronyDataLines) {
  const cal::ViscoHyperfoam m{truth_terms(), cal::prony_from_long_term_ratios({1.0, 1.0}, {0.1, 10.0})};
  const std::string text = cal::abaqus_cards(m, "FOAM", 6.5e-11, "test");
  EXPECT_NE(text.find("*HYPERFOAM, N=3, MODULI=LONG TERM\n0.01, 10, 0.0001, -2, 0.0005, 3, 0, 0\n0\n"), std::string::npos)
      << text;
  EXPECT_NE(text.find("*VISCOELASTIC, TIME=PRONY\n"), std::string::npos);
  EXPECT_NE(text.find("0.3333333333, 0.3333333333, 0.1\n"), std::string::npos) << text;  // g = 1/(1+2), k = g
  EXPECT_NE(text.find("*DENSITY\n6.5e-11\n"), std::string::npos);
  EXPECT_NE(text.find("MPa"), std::string::npos);
}

TEST(Plot, WritesCsvAndScriptAndDrawsWhenGnuplotIsPresent) {
  const auto dir = std::filesystem::temp_directory_path() / "cushion_test_plot";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  cal::Plot p{"line", "a line", "x [-]", "y [-]", "", "x", "y", {}};
  p.series.push_back({"data", {0.0, 1.0, 2.0}, {0.0, 1.0, 4.0}, true});
  p.series.push_back({"model", {0.0, 2.0}, {0.0, 4.0}});
  std::vector<cal::PlotFiles> files{cal::write_plot(p, dir)};
  std::ifstream csv(files[0].csv);
  std::string header, row;
  std::getline(csv, header);
  std::getline(csv, row);
  EXPECT_EQ(header, "series,x,y");
  EXPECT_TRUE(std::filesystem::exists(files[0].script));
  const std::string gnuplot = cal::find_gnuplot();
  cal::draw_plots(files, dir, gnuplot);
  EXPECT_EQ(files[0].drawn, !gnuplot.empty()) << files[0].message;
  cal::draw_plots(files, dir, "");
  EXPECT_FALSE(files[0].drawn);
  EXPECT_NE(files[0].message.find("gnuplot not found"), std::string::npos);
}

TEST(Plot, ScriptResetsStateAndHasARightAxisOnlyWhenASeriesUsesIt) {
  cal::Plot p{"line", "a: line", "x [-]", "y [-]", "phase [deg]", "x", "y", {}};
  p.series.push_back({"data", {1.0, 2.0}, {1.0, 4.0}, true});
  const std::string plain = cal::plot_script(p, "line.csv", "line.png");
  EXPECT_NE(plain.find("\nreset\n"), std::string::npos) << plain;
  EXPECT_EQ(plain.find("y2"), std::string::npos) << plain;  // y2label given but no series on it
  p.series.push_back({"phase", {1.0, 2.0}, {10.0, 12.0}, false, true});
  const std::string right = cal::plot_script(p, "line.csv", "line.png");
  EXPECT_NE(right.find("set y2tics"), std::string::npos) << right;
  EXPECT_NE(right.find("axes x1y2"), std::string::npos) << right;
  p.two_panels = true;  // the y2 series go to a lower panel with their own y axis
  const std::string panels = cal::plot_script(p, "line.csv", "line.png");
  EXPECT_EQ(panels.find("y2"), std::string::npos) << panels;
  EXPECT_NE(panels.find("set multiplot layout 2,1"), std::string::npos) << panels;
  EXPECT_NE(panels.find("set ylabel 'phase [deg]'"), std::string::npos) << panels;
}

TEST(Plot, RangeFromTheDataAndLabelledIntegerTics) {
  cal::Plot p{"spectrum", "s", "f [Hz]", "E [kPa]", "", "f", "E", {}};
  p.series.push_back({"test", {1.0, 20.0}, {40.0, 70.0}, true});
  p.log_x = true;
  const std::string log = cal::plot_script(p, "s.csv", "s.png");
  EXPECT_NE(log.find("set logscale x"), std::string::npos);
  EXPECT_NE(log.find("set xrange [0.9259259259:21.6]"), std::string::npos) << log;  // 8 % beyond the data
  p.log_x = false;
  p.xtics = {{1.0, "1: baseline"}, {2.0, "2: +friction"}};
  p.levels = {{1.0, "noise"}};
  const std::string tics = cal::plot_script(p, "s.csv", "s.png");
  EXPECT_NE(tics.find("set xtics ('1: baseline' 1, '2: +friction' 2)"), std::string::npos) << tics;
  EXPECT_NE(tics.find("set xrange [0.5:2.5]"), std::string::npos) << tics;
  EXPECT_NE(tics.find("set arrow from graph 0, first 1 to graph 1, first 1 nohead"), std::string::npos) << tics;
}
