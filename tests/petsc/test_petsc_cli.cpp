// Requirement: `cushion run` with "linear_solver": "petsc" gives the force history of the CHOLMOD run
// (|RF3 - RF3_cholmod| <= 1e-6 max |RF3_cholmod| at every increment, same times) on a short
// cube_compression run; an unknown PETSc option is one input-error line, exit 2, nothing written; a
// Krylov method that does not converge stops the run with exit 1 and complete frames.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_runner.hpp"
#include "io/csv.hpp"

namespace {

namespace fs = std::filesystem;
using cli_test::run_cushion;

/// The shipped cube_compression case, load step only and shortened to 10 s (20 mm, the same rate), with
/// the given solver settings, written to `dir`/case.json.
fs::path short_cube_case(const fs::path& dir, const nlohmann::json& solver) {
  const fs::path shipped = fs::path(CUSHION_SOURCE_DIR) / "cases" / "cube_compression";
  std::ifstream in(shipped / "case.json");
  nlohmann::json c = nlohmann::json::parse(in);
  c["material"]["file"] = fs::weakly_canonical(shipped / c["material"]["file"].get<std::string>()).string();
  nlohmann::json load = c["steps"][0];
  load["time_period_s"] = 10;
  for (auto& b : load["boundary"])
    if (b.contains("value_mm")) b["value_mm"] = -20;
  c["steps"] = nlohmann::json::array({load});
  c["solver"] = solver;
  fs::create_directories(dir);
  const fs::path file = dir / "case.json";
  std::ofstream(file) << c.dump(2);
  return file;
}

/// Rows (time [s], RF3 [N]) of history.csv (columns time_s, top.U3_mm, top.RF3_N).
std::vector<std::pair<double, double>> force_history(const fs::path& csv) {
  std::ifstream in(csv);
  std::vector<std::pair<double, double>> rows;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || !std::isdigit(static_cast<unsigned char>(line[0]))) continue;
    std::stringstream s(line);
    std::string t, u, rf;
    std::getline(s, t, ','), std::getline(s, u, ','), std::getline(s, rf, ',');
    rows.emplace_back(std::stod(t), std::stod(rf));
  }
  return rows;
}

TEST(PetscRun, ForceHistoryMatchesCholmod) {
  const fs::path dir = cli_test::scratch_dir("cushion_petsc_");
  const fs::path petsc = short_cube_case(dir / "p", {{"linear_solver", "petsc"}});
  const fs::path cholmod = short_cube_case(dir / "c", {{"linear_solver", "cholmod"}});
  const auto run_p = run_cushion("run " + cli_test::quoted(petsc) + " -o " + cli_test::quoted(dir / "out_p") + " --quiet");
  const auto run_c = run_cushion("run " + cli_test::quoted(cholmod) + " -o " + cli_test::quoted(dir / "out_c") + " --quiet");
  ASSERT_EQ(run_p.exit_code, 0) << run_p.output;
  ASSERT_EQ(run_c.exit_code, 0) << run_c.output;
  EXPECT_NE(run_p.output.find("linear solver: petsc cg + gamg"), std::string::npos) << run_p.output;
  const auto p = force_history(dir / "out_p" / "history.csv"), c = force_history(dir / "out_c" / "history.csv");
  ASSERT_EQ(p.size(), c.size());
  ASSERT_GT(c.size(), 5u);
  double scale = 0.0;
  for (const auto& [t, rf] : c) scale = std::max(scale, std::abs(rf));
  for (std::size_t i = 0; i < c.size(); ++i) {
    EXPECT_EQ(p[i].first, c[i].first) << "row " << i;
    EXPECT_LE(std::abs(p[i].second - c[i].second), 1e-6 * scale) << "row " << i << " t = " << c[i].first;
  }
  // The iterations of every solve are in the log.
  std::ifstream log(dir / "out_p" / "solver.log");
  const std::string text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("ksp cg: "), std::string::npos);
  EXPECT_NE(text.find("preconditioner reused"), std::string::npos);
}

TEST(PetscRun, UnknownOptionIsOneInputErrorAndWritesNothing) {
  const fs::path dir = cli_test::scratch_dir("cushion_petsc_");
  const fs::path file = short_cube_case(dir, {{"linear_solver", "petsc"}, {"petsc_options", "-ksp_type cg -ksp_tpye gmres"}});
  const auto run = run_cushion("run " + cli_test::quoted(file) + " -o " + cli_test::quoted(dir / "out"));
  cli_test::expect_input_error(run, {"case.json", "solver.petsc_options", "-ksp_tpye"});
  EXPECT_FALSE(fs::exists(dir / "out")) << cli_test::listed(dir / "out");
}

TEST(PetscRun, OptionsWithoutPetscSolverAreAnInputError) {
  const fs::path dir = cli_test::scratch_dir("cushion_petsc_");
  const fs::path file = short_cube_case(dir, {{"linear_solver", "cholmod"}, {"petsc_options", "-ksp_type cg"}});
  const auto run = run_cushion("run " + cli_test::quoted(file) + " -o " + cli_test::quoted(dir / "out"));
  cli_test::expect_input_error(run, {"case.json", "petsc_options", "linear_solver"});
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST(PetscRun, KrylovMethodThatDoesNotConvergeStopsWithCompleteFrames) {
  const fs::path dir = cli_test::scratch_dir("cushion_petsc_");
  const fs::path file = short_cube_case(dir, {{"linear_solver", "petsc"}, {"petsc_options", "-ksp_max_it 1"}});
  const auto run = run_cushion("run " + cli_test::quoted(file) + " -o " + cli_test::quoted(dir / "out") + " --quiet");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_EQ(cli_test::line_count(run.output), 1u) << run.output;
  EXPECT_NE(run.output.find("cushion: error: step 'load'"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("linear solve failed"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("DIVERGED_ITS"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("frames written so far are complete"), std::string::npos) << run.output;
  EXPECT_TRUE(fs::exists(dir / "out" / "results.pvd"));
  EXPECT_TRUE(fs::exists(dir / "out" / "results_0000.vtu"));  // the undeformed state at t = 0
}

/// The SIT-BAR sweep case on a 6 x 6 x 4 mesh, 1 to 20 Hz in 4 Hz steps, with the given solver settings.
fs::path small_sweep_case(const fs::path& dir, const nlohmann::json& solver) {
  const fs::path shipped = fs::path(CUSHION_SOURCE_DIR) / "cases" / "sitbar_sweep";
  std::ifstream in(shipped / "case.json");
  nlohmann::json c = nlohmann::json::parse(in);
  c["material"]["file"] = fs::weakly_canonical(shipped / c["material"]["file"].get<std::string>()).string();
  c["mesh"]["generate"]["elements"] = {6, 6, 4};
  for (auto& s : c["steps"])
    if (s["type"] == "steady_state") s["steady_state"]["frequencies"] = {{"start_Hz", 1}, {"end_Hz", 20}, {"step_Hz", 4}};
  c["solver"] = solver;
  fs::create_directories(dir);
  std::ofstream(dir / "case.json") << c.dump(2);
  return dir / "case.json";
}

/// (|E*| [kPa], phase [deg]) per row of a sweep CSV.
std::vector<std::pair<double, double>> modulus_and_phase(const fs::path& csv) {
  std::ifstream in(csv);
  std::vector<std::string> header;
  std::vector<std::pair<double, double>> rows;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells;
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');) cells.push_back(cell);
    if (header.empty()) {
      header = cells;
      continue;
    }
    auto at = [&](const std::string& name) {
      const auto it = std::find(header.begin(), header.end(), name);
      return it == header.end() ? NAN : std::stod(cells[static_cast<std::size_t>(it - header.begin())]);
    };
    rows.emplace_back(at("dynamic_modulus_kPa"), at("phase_deg"));
  }
  return rows;
}

// Requirement (issue 14, sweeps on the PETSc engine): with "linear_solver": "petsc" the iterative sweep's
// real preconditioner P = Re D_ff is PETSc's CG + GAMG instead of a CHOLMOD factor, and the sweep gives the
// CHOLMOD-preconditioned one's |E*| and phase to 1e-6 (both solve to a true relative residual of 1e-10).
TEST(PetscRun, SweepPreconditionedByPetscGivesTheCholmodPreconditionedSweep) {
  const fs::path dir = cli_test::scratch_dir("cushion_petsc_");
  const fs::path petsc = small_sweep_case(dir / "p", {{"linear_solver", "petsc"}, {"petsc_options", "-ksp_rtol 1e-12"}});
  const fs::path direct = small_sweep_case(dir / "c", {{"linear_solver", "auto"}});
  const auto run_p = run_cushion("run " + cli_test::quoted(petsc) + " -o " + cli_test::quoted(dir / "out_p") + " --quiet");
  const auto run_c = run_cushion("run " + cli_test::quoted(direct) + " -o " + cli_test::quoted(dir / "out_c") + " --quiet");
  ASSERT_EQ(run_p.exit_code, 0) << run_p.output;
  ASSERT_EQ(run_c.exit_code, 0) << run_c.output;
  for (const char* sweep : {"sweep_rayleigh_sweep.csv", "sweep_no_rayleigh_sweep.csv"}) {
    const auto p = modulus_and_phase(dir / "out_p" / sweep), c = modulus_and_phase(dir / "out_c" / sweep);
    ASSERT_EQ(p.size(), 5u) << sweep;
    ASSERT_EQ(c.size(), 5u) << sweep;
    for (std::size_t i = 0; i < c.size(); ++i) {
      ASSERT_TRUE(std::isfinite(c[i].first) && std::isfinite(c[i].second)) << sweep << " row " << i;
      EXPECT_NEAR(p[i].first, c[i].first, 1e-6 * std::abs(c[i].first)) << sweep << " row " << i;
      EXPECT_NEAR(p[i].second, c[i].second, 1e-6 * std::abs(c[i].second) + 1e-9) << sweep << " row " << i;
    }
  }
  // The sweeps were preconditioned by PETSc, on one thread, and GMRES converged (no complex LU fallback).
  std::ifstream log(dir / "out_p" / "solver.log");
  const std::string text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
  for (const char* step : {"step 'sweep_rayleigh' done", "step 'sweep_no_rayleigh' done"}) {
    const std::size_t at = text.find(step);
    ASSERT_NE(at, std::string::npos) << step;
    const std::string line = text.substr(at, text.find('\n', at) - at);
    EXPECT_NE(line.find("on 1 threads"), std::string::npos) << line;
    EXPECT_NE(line.find("GMRES + PETSc preconditioner"), std::string::npos) << line;
    EXPECT_NE(line.find(" 0 complex factorisations"), std::string::npos) << line;
  }
}

}  // namespace

// Requirement: where PETSc's node-block SOR fails the multigrid (all-zero rows in a coarse operator: the graded
// 20 x 20 x 8 indentation mesh of tools/calculix/make_indentation.py fails its first solve) the solver rebuilds
// it with SOR on a shifted diagonal, says so in the log, and the indenter force equals CHOLMOD's within 1e-6 of
// the largest force over the first 4 mm (2 increments).
TEST(PetscRun, FailedNodeBlockSorIsReplacedByShiftedSor) {
  const fs::path dir = cli_test::scratch_dir("cushion_petsc_");
  const std::string make = "python3 " + cli_test::quoted(fs::path(CUSHION_SOURCE_DIR) / "tools" / "calculix" / "make_indentation.py") +
                           " " + cli_test::quoted(dir / "problem") + " --n 20 --nz 8";
  const auto made = cli_test::run_command(make);
  ASSERT_EQ(made.exit_code, 0) << made.output;
  nlohmann::json c = nlohmann::json::parse(std::ifstream(dir / "problem" / "case.json"));
  auto& step = c["steps"][0];
  const double full_time = step["time_period_s"].get<double>();
  step["time_period_s"] = full_time / 15.0;  // 2 of the 30 increments: 4 of the 60 mm
  step["contact"][0]["motion_mm"][2] = step["contact"][0]["motion_mm"][2].get<double>() / 15.0;
  step["output"]["frames_every_s"] = full_time / 15.0;
  std::map<std::string, fs::path> out;
  for (const char* solver : {"petsc", "cholmod"}) {
    c["solver"] = {{"linear_solver", solver}};
    const fs::path file = (dir / "problem" / solver).replace_extension(".json");
    std::ofstream(file) << c.dump(1);
    out[solver] = dir / (std::string("out_") + solver);
    const auto run = run_cushion("run " + cli_test::quoted(file) + " -o " + cli_test::quoted(out[solver]) + " --quiet");
    ASSERT_EQ(run.exit_code, 0) << run.output;
  }
  std::ifstream log(out["petsc"] / "solver.log");
  const std::string text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("SOR smoothing failed (SUBPC_ERROR): SOR on a shifted diagonal from here on"), std::string::npos)
      << "the node-block SOR no longer fails here: find another mesh that exercises the fallback";
  const cushion::CsvTable p = cushion::read_csv(out["petsc"] / "contact_sphere.csv");
  const cushion::CsvTable ch = cushion::read_csv(out["cholmod"] / "contact_sphere.csv");
  const std::vector<double>&fp = p.col("sphere.F3_N"), &fc = ch.col("sphere.F3_N"), &t = ch.col("time_s");
  ASSERT_EQ(fp.size(), fc.size());
  ASSERT_GE(fc.size(), 3u);
  double scale = 0.0;
  for (double f : fc) scale = std::max(scale, std::abs(f));
  ASSERT_GT(scale, 0.0);
  for (std::size_t i = 0; i < fc.size(); ++i) EXPECT_LE(std::abs(fp[i] - fc[i]), 1e-6 * scale) << "t = " << t[i];
}
