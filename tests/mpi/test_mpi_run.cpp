// Requirement (issue 14): `mpirun -np 2 cushion run` gives the results of the one-process run to 1e-6
// (every CSV the run writes, each value within 1e-6 of its column's largest magnitude, same rows; the
// last frame's stress and displacement fields likewise) on a contact case with two frequency sweeps and on
// a case with visco, steady-state and implicit dynamic steps; only process 0 writes and prints. A launch
// that cannot run distributed, an unknown PETSc option and a Krylov solve that does not converge are one
// clear message (exit 2 / exit 1 with complete frames), not a hang or one message per process.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "solver/output/vtu_reader.hpp"

namespace {

namespace fs = std::filesystem;
using cli_test::quoted;

/// `mpirun -q -np N cushion ARGUMENTS` (oversubscribed: more processes than cores are allowed; -q: without
/// OpenMPI's own banner after a process exits with an error; yield when idle: a process waiting for the
/// other gives up its core instead of polling, which on a loaded machine slowed a 10 s test to 20 min).
cli_test::CommandRun run_mpi(int processes, const std::string& arguments) {
  return cli_test::run_command(std::string(CUSHION_MPIEXEC) + " -q --oversubscribe --allow-run-as-root --mca mpi_yield_when_idle 1 -np " +
                               std::to_string(processes) + " " + quoted(CUSHION_BINARY) + " " + arguments);
}

/// A shipped case with its material path made absolute, changed by `edit`, written to dir/case.json.
template <class Edit>
fs::path shipped_case(const fs::path& dir, const std::string& name, Edit edit) {
  const fs::path folder = fs::path(CUSHION_SOURCE_DIR) / "cases" / name;
  std::ifstream in(folder / "case.json");
  nlohmann::json c = nlohmann::json::parse(in);
  c["material"]["file"] = fs::weakly_canonical(folder / c["material"]["file"].get<std::string>()).string();
  c["solver"] = {{"linear_solver", "petsc"}, {"petsc_options", "-ksp_rtol 1e-12"}};
  edit(c);
  fs::create_directories(dir);
  std::ofstream(dir / "case.json") << c.dump(2);
  return dir / "case.json";
}

/// The SIT-BAR sweep case on a 6 x 6 x 4 mesh, 5 frequencies per sweep: contact, visco, two sweeps.
fs::path small_sitbar_sweep(const fs::path& dir) {
  return shipped_case(dir, "sitbar_sweep", [](nlohmann::json& c) {
    c["mesh"]["generate"]["elements"] = {6, 6, 4};
    for (auto& s : c["steps"])
      if (s["type"] == "steady_state") s["steady_state"]["frequencies"] = {{"start_Hz", 1}, {"end_Hz", 20}, {"step_Hz", 4}};
  });
}

/// Numeric rows of a CSV (comment lines and the header skipped) and its header.
std::pair<std::string, std::vector<std::vector<double>>> read_table(const fs::path& file) {
  std::ifstream in(file);
  std::string header;
  std::vector<std::vector<double>> rows;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    if (header.empty()) {
      header = line;
      continue;
    }
    std::vector<double> row;
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return {header, rows};
}

/// Every CSV of `one` is in `two` with the same header and rows, each value within `tolerance` x the
/// largest magnitude of its column.
void expect_same_tables(const fs::path& one, const fs::path& two, double tolerance) {
  int tables = 0;
  for (const auto& entry : fs::directory_iterator(one)) {
    if (entry.path().extension() != ".csv") continue;
    ++tables;
    const fs::path other = two / entry.path().filename();
    ASSERT_TRUE(fs::exists(other)) << other;
    const auto [h1, a] = read_table(entry.path());
    const auto [h2, b] = read_table(other);
    EXPECT_EQ(h1, h2) << other;
    ASSERT_EQ(a.size(), b.size()) << other;
    ASSERT_FALSE(a.empty()) << other;
    // An energy balance (a dynamic step's *_energy.csv, all columns mJ) is a difference of the energies:
    // it is measured against the largest energy of the table.
    const bool energies = entry.path().filename().string().find("_energy.csv") != std::string::npos;
    double table_scale = 0.0;
    for (const auto& r : a)
      for (std::size_t j = 1; j < r.size(); ++j) table_scale = std::max(table_scale, std::abs(r[j]));
    for (std::size_t j = 0; j < a[0].size(); ++j) {
      double scale = energies && j > 0 ? table_scale : 0.0;
      for (const auto& r : a) scale = std::max(scale, std::abs(r[j]));
      for (std::size_t i = 0; i < a.size(); ++i)
        EXPECT_LE(std::abs(a[i][j] - b[i][j]), tolerance * scale)
            << entry.path().filename() << " row " << i << " column " << j << ": " << a[i][j] << " vs " << b[i][j];
    }
  }
  EXPECT_GE(tables, 2) << one;
}

/// The last frame's fields of the two runs agree within `tolerance` x each field's largest magnitude.
void expect_same_last_frame(const fs::path& one, const fs::path& two, double tolerance) {
  const auto frames = cushion::solver::read_pvd(one / "results.pvd");
  ASSERT_FALSE(frames.empty());
  ASSERT_EQ(cushion::solver::read_pvd(two / "results.pvd").size(), frames.size());
  const auto a = cushion::solver::read_vtu(one / frames.back().file);
  const auto b = cushion::solver::read_vtu(two / frames.back().file);
  for (const auto* data : {&a.point_data, &a.cell_data}) {
    const auto& other = data == &a.point_data ? b.point_data : b.cell_data;
    for (const auto& [name, field] : *data) {
      ASSERT_TRUE(other.count(name)) << name;
      const auto& x = field.values;
      const auto& y = other.at(name).values;
      ASSERT_EQ(x.size(), y.size()) << name;
      double scale = 0.0;
      for (double v : x)
        if (!std::isnan(v)) scale = std::max(scale, std::abs(v));
      for (std::size_t i = 0; i < x.size(); ++i) {
        if (std::isnan(x[i]) && std::isnan(y[i])) continue;  // undefined in both (e.g. a gap away from the set)
        EXPECT_LE(std::abs(x[i] - y[i]), tolerance * scale) << name << " " << i;
      }
    }
  }
}

TEST(MpiRun, TwoProcessesGiveTheOneProcessContactRunAndSweeps) {
  const fs::path dir = cli_test::scratch_dir("cushion_mpi_");
  const fs::path file = small_sitbar_sweep(dir);
  const auto one = run_mpi(1, "run " + quoted(file) + " -o " + quoted(dir / "one") + " --quiet");
  const auto two = run_mpi(2, "run " + quoted(file) + " -o " + quoted(dir / "two"));
  ASSERT_EQ(one.exit_code, 0) << one.output;
  ASSERT_EQ(two.exit_code, 0) << two.output;
  // One summary and one set of progress lines (process 0's); the log says the run was distributed.
  EXPECT_EQ(std::count(two.output.begin(), two.output.end(), '\n') > 0, true);
  EXPECT_EQ(two.output.find("summary:"), two.output.rfind("summary:")) << two.output;
  std::ifstream log(dir / "two" / "solver.log");
  const std::string text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("distributed over 2 processes"), std::string::npos);
  expect_same_tables(dir / "one", dir / "two", 1e-6);
  expect_same_last_frame(dir / "one", dir / "two", 1e-6);
  EXPECT_EQ(cli_test::listing(dir / "one").size(), cli_test::listing(dir / "two").size());
}

TEST(MpiRun, TwoProcessesGiveTheOneProcessViscoSweepAndDynamicRun) {
  const fs::path dir = cli_test::scratch_dir("cushion_mpi_");
  const fs::path file = shipped_case(dir, "dynamic_sine", [](nlohmann::json&) {});
  const auto one = run_mpi(1, "run " + quoted(file) + " -o " + quoted(dir / "one") + " --quiet");
  const auto two = run_mpi(2, "run " + quoted(file) + " -o " + quoted(dir / "two") + " --quiet");
  ASSERT_EQ(one.exit_code, 0) << one.output;
  ASSERT_EQ(two.exit_code, 0) << two.output;
  expect_same_tables(dir / "one", dir / "two", 1e-6);
  expect_same_last_frame(dir / "one", dir / "two", 1e-6);
}

TEST(MpiRun, WhatCannotRunDistributedIsOneMessage) {
  const fs::path dir = cli_test::scratch_dir("cushion_mpi_");
  const fs::path direct = shipped_case(dir / "direct", "dynamic_sine", [](nlohmann::json& c) {
    c["solver"] = {{"linear_solver", "cholmod"}};
  });
  cli_test::expect_input_error(run_mpi(2, "run " + quoted(direct) + " -o " + quoted(dir / "out")),
                               {"case.json", "solver.linear_solver", "2 MPI processes", "petsc"});
  EXPECT_FALSE(fs::exists(dir / "out"));
  const fs::path misspelt = shipped_case(dir / "misspelt", "dynamic_sine", [](nlohmann::json& c) {
    c["solver"]["petsc_options"] = "-ksp_tpye gmres";
  });
  cli_test::expect_input_error(run_mpi(2, "run " + quoted(misspelt) + " -o " + quoted(dir / "out")),
                               {"case.json", "solver.petsc_options", "-ksp_tpye"});
  EXPECT_FALSE(fs::exists(dir / "out"));
  cli_test::expect_input_error(run_mpi(2, "lab --help"), {"mpirun", "only `cushion run`"});
  // A folder that is not an earlier output: refused by process 0 (the others are ended by mpirun).
  const fs::path taken = dir / "taken";
  fs::create_directories(taken);
  std::ofstream(taken / "notes.txt") << "mine\n";
  const fs::path good = shipped_case(dir / "good", "dynamic_sine", [](nlohmann::json&) {});
  cli_test::expect_input_error(run_mpi(2, "run " + quoted(good) + " -o " + quoted(taken)), {"taken"});
  EXPECT_EQ(cli_test::listing(taken).size(), 1u);
}

TEST(MpiRun, KrylovFailureStopsEveryProcessWithCompleteFrames) {
  const fs::path dir = cli_test::scratch_dir("cushion_mpi_");
  const fs::path file = small_sitbar_sweep(dir);
  nlohmann::json c = nlohmann::json::parse(std::ifstream(file));
  c["solver"]["petsc_options"] = "-ksp_max_it 2 -cushion_pc_reuse_max_it 0";
  std::ofstream(file) << c.dump(2);
  const auto run = run_mpi(2, "run " + quoted(file) + " -o " + quoted(dir / "out") + " --quiet");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_NE(run.output.find("frames written so far are complete"), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find("cushion: error"), run.output.rfind("cushion: error")) << "one message: " << run.output;
  for (const auto& frame : cushion::solver::read_pvd(dir / "out" / "results.pvd"))
    EXPECT_NO_THROW(cushion::solver::read_vtu(dir / "out" / frame.file)) << frame.file;
}

}  // namespace
