// Requirement: the deck translator shall read material data lines in the ABAQUS/CalculiX order across
// lines (8 values a line: mu_i, alpha_i pairs, then nu_i or D_i), convert them with the deck's units,
// replace a zero D1 as CalculiX does, and refuse temperature-dependent data and k_i != g_i naming the line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "io/input_error.hpp"
#include "solver/deck/deck_reader.hpp"

namespace cushion::solver {
namespace {

namespace fs = std::filesystem;

/// A one-element deck with the material lines `material`, written to a temporary file named after the running test
/// and `name` (ctest runs this binary's tests in parallel processes: a shared name let one test read another's deck).
fs::path deck_with(const std::string& material, const std::string& name = "deck.inp") {
  const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
  const fs::path file = fs::temp_directory_path() / ("cushion_test_deck_" + test + "_" + name);
  std::ofstream(file) << "*NODE\n1,0,0,0\n2,1,0,0\n3,0,1,0\n4,0,0,1\n*ELEMENT, TYPE=C3D4, ELSET=E\n1,1,2,3,4\n"
                         "*MATERIAL, NAME=M\n"
                      << material
                      << "*SOLID SECTION, ELSET=E, MATERIAL=M\n*BOUNDARY\n1, ENCASTRE\n2, 2, 3\n3, 3, 3\n"
                         "*STEP\n*STATIC\n*CLOAD\n4, 3, 0.001\n*END STEP\n";
  return file;
}

TEST(DeckMaterial, HyperfoamTermsAcrossTwoLinesInMegapascalsAndPascals) {
  const std::string card = "*HYPERFOAM, N=3\n0.01, 10, 0.0001, -2, 0.0005, 3, 0.1, 0.2\n0.3\n";
  const LoadedCase mm = load_deck(deck_with(card), deck_units("mm-N-MPa"));
  const auto& t = mm.material.spec.hyperfoam;
  ASSERT_EQ(t.size(), 3u);
  EXPECT_DOUBLE_EQ(t[1].mu, 0.0001);
  EXPECT_DOUBLE_EQ(t[1].alpha, -2.0);
  EXPECT_DOUBLE_EQ(t[2].mu, 0.0005);
  EXPECT_DOUBLE_EQ(t[0].nu, 0.1);
  EXPECT_DOUBLE_EQ(t[2].nu, 0.3);
  // The same numbers read as Pa are 1e-6 MPa; the lengths of an m deck are 1000 mm.
  const LoadedCase si = load_deck(deck_with(card), deck_units("m-N-Pa"));
  EXPECT_DOUBLE_EQ(si.material.spec.hyperfoam[0].mu, 0.01 * 1e-6);
  EXPECT_DOUBLE_EQ(si.mesh.nodes[1].x(), 1000.0);
}

TEST(DeckMaterial, OgdenAndNeoHookeAndCalculixDefaultD1) {
  const LoadedCase og = load_deck(deck_with("*HYPERELASTIC, OGDEN, N=2\n0.4, 2.5, 0.05, -1.5, 0.5, 2.0\n"),
                                  deck_units("mm-N-MPa"));
  ASSERT_EQ(og.material.spec.base, material::MaterialSpec::Base::ogden);
  EXPECT_DOUBLE_EQ(og.material.spec.ogden[1].alpha, -1.5);
  EXPECT_EQ(og.material.spec.ogden_D, (std::vector<double>{0.5, 2.0}));
  const LoadedCase nh = load_deck(deck_with("*HYPERELASTIC, NEO HOOKE\n1.5, 0\n*DENSITY\n1e-9\n"), deck_units("mm-N-MPa"));
  EXPECT_DOUBLE_EQ(nh.material.spec.ogden[0].mu, 3.0);  // 2 C10
  EXPECT_DOUBLE_EQ(nh.material.spec.ogden[0].alpha, 2.0);
  EXPECT_DOUBLE_EQ(nh.material.spec.ogden_D[0], 1.0 / (10.0 * 3.0));  // K0 = 20 mu0
  EXPECT_DOUBLE_EQ(nh.material.spec.density, 1e-9);
  ASSERT_EQ(nh.warnings.size(), 2u);  // and *STEP without NLGEOM
  EXPECT_NE(nh.warnings[0].find(":9: *HYPERELASTIC: D1 = 0 (incompressible) replaced"), std::string::npos) << nh.warnings[0];
  EXPECT_NE(nh.warnings[1].find(":18: *STEP without NLGEOM"), std::string::npos) << nh.warnings[1];
}

TEST(DeckMaterial, TemperatureDataAndUnequalPronyModuliAreRefusedWithTheirLine) {
  const struct {
    std::string card, message;
  } cases[] = {
      {"*HYPERFOAM, N=1\n0.01, 10, 0.1, 20\n", ":10: *HYPERFOAM: more than 3 values: temperature-dependent data"},
      {"*HYPERFOAM, N=1\n0.01, 10, 0.1\n0.02, 10, 0.1\n", ":11: *HYPERFOAM: further data lines (temperature"},
      {"*HYPERFOAM\n0.01, 10, 0\n*VISCOELASTIC, TIME=PRONY\n0.3, 0.2, 1\n", ":12: *VISCOELASTIC: k_i = 0.2 differs from g_i = 0.3"},
      {"*HYPERELASTIC, MOONEY-RIVLIN\n0.1, 0.2, 0.01\n", ":9: parameter MOONEY-RIVLIN of *HYPERELASTIC is not supported"},
      {"*HYPERFOAM, N=7\n", ":9: *HYPERFOAM: N must be 1..6"},
  };
  for (const auto& c : cases) {
    try {
      load_deck(deck_with(c.card), deck_units("mm-N-MPa"));
      ADD_FAILURE() << "accepted: " << c.card;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace cushion::solver
