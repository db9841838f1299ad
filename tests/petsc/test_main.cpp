// The main of test_petsc: PETSc (and MPI) started once for the whole executable, when tests run (not when
// ctest lists them), and finished after the last test: MPI cannot be started twice in one process.
#include <gtest/gtest.h>

#include <optional>

#include "solver/petsc/petsc_session.hpp"

namespace {

class PetscEnvironment : public ::testing::Environment {
 public:
  void SetUp() override { session_.emplace(); }
  void TearDown() override { session_.reset(); }

 private:
  std::optional<cushion::solver::petsc::Session> session_;
};

}  // namespace

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ::testing::AddGlobalTestEnvironment(new PetscEnvironment);  // owned by GoogleTest
  return RUN_ALL_TESTS();
}
