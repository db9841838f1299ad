// Requirement: in a build without PETSc, a case choosing "linear_solver": "petsc" is one input-error line
// (exit 2, nothing written) saying so. Skipped in a build with PETSc (tests/petsc covers that one).
#include <gtest/gtest.h>

#include <fstream>

#include "cli_runner.hpp"

namespace {

namespace fs = std::filesystem;

TEST(CliRunPetsc, WithoutPetscBuiltTheChoiceIsAnInputError) {
  if (CUSHION_PETSC_BUILT) GTEST_SKIP() << "this cushion is built with PETSc";
  const fs::path dir = cli_test::scratch_dir("cushion_petsc_absent_");
  const fs::path shipped = fs::path(CUSHION_SOURCE_DIR) / "cases" / "cube_compression" / "case.json";
  std::ifstream in(shipped);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string from = "\"linear_solver\": \"auto\"", material = "\"../materials/";
  text.replace(text.find(from), from.size(), "\"linear_solver\": \"petsc\"");
  text.replace(text.find(material), material.size(), "\"" + (shipped.parent_path().parent_path() / "materials").string() + "/");
  std::ofstream(dir / "case.json") << text;
  const auto run = cli_test::run_cushion("run " + cli_test::quoted(dir / "case.json") + " -o " + cli_test::quoted(dir / "out"));
  cli_test::expect_input_error(run, {"case.json", "solver.linear_solver", "built without PETSc"});
  EXPECT_FALSE(fs::exists(dir / "out")) << cli_test::listed(dir / "out");
}

}  // namespace
