// Requirement: `cushion run DECK.inp` shall run contact decks as CalculiX does: a *RIGID BODY (meshed
// elements with a reference node) whose element-face master surface is pressed by the reference node's
// prescribed displacement onto the slave surface of a *CONTACT PAIR, with the *SURFACE BEHAVIOR law
// (PRESSURE-OVERCLOSURE=LINEAR: pressure = K x overclosure, checked against the closed form of a
// homogeneously compressed block); frames at *TIME POINTS; *ELASTIC as the neo-Hooke solid with the same
// small-strain moduli (checked against linear elasticity); and refuse what it cannot run (a free or rotating
// rigid body, a deformable master surface, forces on a rigid body, bad interaction data) with one line
// naming file and line, exit 2, nothing written.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "cli_runner.hpp"
#include "io/csv.hpp"

namespace fs = std::filesystem;

namespace {

using cli_test::CommandRun;
using cli_test::quoted;
using cli_test::run_cushion;

constexpr double kMu = 0.01, kAlpha = 10.0, kSlope = 0.002;  // MPa, -, MPa/mm

/// A 10 mm hyperfoam cube (nu = 0, so it compresses homogeneously and uniaxially) under a rigid plate
/// (one C3D8, 20 x 20 x 2 mm, face S1 towards the foam) driven down by `travel` mm through its reference
/// node 17 (rotation node 18). `model` is inserted before the *STEP, `step` inside it.
std::string plate_deck(double travel, const std::string& model = "", const std::string& step = "",
                       const std::string& ref_boundary = "17, 1, 2\n18, 1, 3\n") {
  return "*NODE, NSET=ALL\n1, 0, 0, 0\n2, 10, 0, 0\n3, 10, 10, 0\n4, 0, 10, 0\n"
         "5, 0, 0, 10\n6, 10, 0, 10\n7, 10, 10, 10\n8, 0, 10, 10\n"
         "9, -5, -5, 10\n10, 15, -5, 10\n11, 15, 15, 10\n12, -5, 15, 10\n"
         "13, -5, -5, 12\n14, 15, -5, 12\n15, 15, 15, 12\n16, -5, 15, 12\n"
         "17, 5, 5, 12\n18, 5, 5, 12\n"
         "*ELEMENT, TYPE=C3D8, ELSET=FOAM\n1, 1, 2, 3, 4, 5, 6, 7, 8\n"
         "*ELEMENT, TYPE=C3D8, ELSET=PLATE\n2, 9, 10, 11, 12, 13, 14, 15, 16\n"
         "*NSET, NSET=BOTTOM\n1, 2, 3, 4\n"
         "*MATERIAL, NAME=FOAM\n*HYPERFOAM, N=1\n" + std::to_string(kMu) + ", " + std::to_string(kAlpha) + ", 0\n"
         "*MATERIAL, NAME=STEEL\n*ELASTIC\n210000, 0.3\n"
         "*SOLID SECTION, ELSET=FOAM, MATERIAL=FOAM\n*SOLID SECTION, ELSET=PLATE, MATERIAL=STEEL\n"
         "*RIGID BODY, ELSET=PLATE, REF NODE=17, ROT NODE=18\n"
         "*SURFACE, NAME=STOP, TYPE=ELEMENT\nFOAM, S2\n*SURFACE, NAME=SPLATE, TYPE=ELEMENT\nPLATE, S1\n"
         "*SURFACE INTERACTION, NAME=SOFT\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n" +
         std::to_string(kSlope) + ", 1e-9, 1e-3\n"
         "*CONTACT PAIR, INTERACTION=SOFT, TYPE=NODE TO SURFACE\nSTOP, SPLATE\n"
         "*BOUNDARY\nBOTTOM, 3, 3\n1, 1, 2\n2, 2, 2\n4, 1, 1\n" + ref_boundary + model +
         "*TIME POINTS, NAME=TP\n0.25, 0.5\n0.75\n"
         "*STEP, NLGEOM, INC=100\n*STATIC\n0.1, 1.0\n*BOUNDARY\n17, 3, 3, " + std::to_string(-travel) + "\n" + step +
         "*NODE PRINT, NSET=ALL, TIME POINTS=TP\nU\n*END STEP\n";
}

/// Compressive nominal stress [MPa] of the nu = 0 hyperfoam at stretch l < 1: -2 mu/alpha (l^(alpha-1) - 1/l).
double pressure(double l) { return -2.0 * kMu / kAlpha * (std::pow(l, kAlpha - 1.0) - 1.0 / l); }

using cli_test::line_of;
using cli_test::write_text;

}  // namespace

TEST(DeckContact, RigidPlateOnLinearPressureOverclosureMatchesClosedForm) {
  const fs::path dir = cli_test::scratch_dir("cushion_test_deck_contact_");
  const double travel = 3.0;
  const CommandRun r = run_cushion("run " + quoted(write_text(dir, plate_deck(travel))) + " -o " + quoted(dir / "out"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const cushion::CsvTable t = cushion::read_csv(dir / "out" / "contact_SPLATE.csv");
  // Frames at the start, the *TIME POINTS 0.25, 0.5, 0.75 and the step end (the contact table has every increment).
  const cushion::CsvTable p = cushion::read_csv(dir / "out" / "node_print_ALL.csv");
  std::vector<double> times;
  for (double time : p.col("time_s"))
    if (times.empty() || time != times.back()) times.push_back(time);
  ASSERT_EQ(times.size(), 5u);
  for (std::size_t k = 0; k < 5; ++k) EXPECT_NEAR(times[k], 0.25 * k, 1e-12);
  // Closed form: the plate at d, the foam top compressed by c: 100 mm^2 pressure(1 - c/10) = 100 mm^2 K (d - c).
  for (std::size_t row = 0; row < t.rows(); ++row) {
    const double d = -t.col("SPLATE.U3_mm")[row];
    double c = 0.0;
    for (int it = 0; it < 100; ++it) {  // Newton on g(c) = pressure(1 - c/10) - K (d - c)
      const double h = 1e-7, g = pressure(1.0 - c / 10.0) - kSlope * (d - c);
      const double dg = (pressure(1.0 - (c + h) / 10.0) - pressure(1.0 - (c - h) / 10.0)) / (2 * h) + kSlope;
      c -= g / dg;
    }
    const double force = 100.0 * kSlope * (d - c);
    EXPECT_NEAR(-t.col("SPLATE.F3_N")[row], force, 1e-6 * std::max(force, 1e-3)) << "d = " << d;
    EXPECT_NEAR(t.col("SPLATE.max_penetration_mm")[row], d - c, 1e-6) << "d = " << d;
    if (row + 1 == t.rows()) {
      EXPECT_NEAR(d, travel, 1e-12);
      EXPECT_GT(d - c, 0.5);  // a real overclosure: the law, not a constraint, decides the force
    }
  }
}

TEST(DeckContact, PressedPlateThenFrequencyAndSteadyStateSteps) {
  // The pressed plate is the base state of a *FREQUENCY and a *STEADY STATE DYNAMICS step (the rigid body's
  // conditions, carried into them, hold the plate); both write their tables, the frames stay complete.
  std::string deck = plate_deck(1.0) +
                     "*STEP\n*FREQUENCY\n3\n*END STEP\n"
                     "*STEP\n*STEADY STATE DYNAMICS, DIRECT\n10, 20, 3\n*CLOAD\n7, 3, 0.01\n*NODE PRINT, NSET=ALL\nU\n*END STEP\n";
  const std::string hyperfoam = std::to_string(kMu) + ", " + std::to_string(kAlpha) + ", 0\n";
  deck.insert(deck.find(hyperfoam) + hyperfoam.size(), "*DENSITY\n6.5e-11\n");
  const fs::path dir = cli_test::scratch_dir("cushion_test_deck_contact_");
  const CommandRun r = run_cushion("run " + quoted(write_text(dir, deck)) + " -o " + quoted(dir / "out") + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(cushion::read_csv(dir / "out" / "Step-2_frequencies.csv").rows(), 3u);
  const cushion::CsvTable u = cushion::read_csv(dir / "out" / "Step-3_node_print_ALL.csv");
  EXPECT_EQ(u.rows(), 3u * 8u);  // 3 frequencies x the 8 foam nodes (the plate's nodes left the mesh)
  for (std::size_t row = 0; row < u.rows(); ++row) EXPECT_TRUE(std::isfinite(u.col("U3_re_mm")[row]));
}

TEST(DeckContact, ElasticIsLinearElasticityAtSmallStrain) {
  // One C3D8 cube pulled by 1e-5 strain with *ELASTIC E = 1000, nu = 0.3: RF = E eps A, lateral -nu eps a.
  const fs::path dir = cli_test::scratch_dir("cushion_test_deck_contact_");
  const std::string deck =
      "*NODE, NSET=ALL\n1, 0, 0, 0\n2, 10, 0, 0\n3, 10, 10, 0\n4, 0, 10, 0\n"
      "5, 0, 0, 10\n6, 10, 0, 10\n7, 10, 10, 10\n8, 0, 10, 10\n"
      "*ELEMENT, TYPE=C3D8, ELSET=CUBE\n1, 1, 2, 3, 4, 5, 6, 7, 8\n"
      "*NSET, NSET=BOTTOM\n1, 2, 3, 4\n*NSET, NSET=TOP\n5, 6, 7, 8\n"
      "*MATERIAL, NAME=STEEL\n*ELASTIC\n1000, 0.3\n*SOLID SECTION, ELSET=CUBE, MATERIAL=STEEL\n"
      "*BOUNDARY\nBOTTOM, 3, 3\n1, 1, 2\n2, 2, 2\n4, 1, 1\n"
      "*STEP, NLGEOM\n*STATIC\n1, 1\n*BOUNDARY\nTOP, 3, 3, 1e-4\n*NODE PRINT, NSET=ALL\nU, RF\n*END STEP\n";
  const CommandRun r = run_cushion("run " + quoted(write_text(dir, deck)) + " -o " + quoted(dir / "out"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("model.inp:" + std::to_string(line_of(deck, "*ELASTIC")) +
                          ": *ELASTIC read as the compressible neo-Hooke solid"),
            std::string::npos)
      << r.output;
  const cushion::CsvTable t = cushion::read_csv(dir / "out" / "node_print_ALL.csv");
  double rf = 0.0, ux7 = 0.0;
  for (std::size_t row = 0; row < t.rows(); ++row) {
    if (t.col("time_s")[row] != 1.0) continue;
    if (t.col("node")[row] >= 5) rf += t.col("RF3_N")[row];
    if (t.col("node")[row] == 7) ux7 = t.col("U1_mm")[row];
  }
  const double eps = 1e-5;
  EXPECT_NEAR(rf, 1000.0 * eps * 100.0, 1e-4 * 1000.0 * eps * 100.0);  // O(eps) geometric nonlinearity
  EXPECT_NEAR(ux7, -0.3 * eps * 10.0, 1e-4 * 0.3 * eps * 10.0);
}

TEST(DeckContact, WhatCannotRunIsOneLineWithFileAndLine) {
  const fs::path dir = cli_test::scratch_dir("cushion_test_deck_contact_");
  const std::string ok = plate_deck(1.0);
  const struct {
    std::string deck, line_start, message;
  } cases[] = {
      // Rotation node free: the body could rotate.
      {plate_deck(1.0, "", "", "17, 1, 2\n18, 1, 2\n"), "*RIGID BODY",
       "*RIGID BODY: in step Step-1 the three translations of REF NODE 17 must be prescribed"},
      // Reference node not driven along x.
      {plate_deck(1.0, "", "", "17, 2, 2\n18, 1, 3\n"), "*RIGID BODY", "no free or rotating rigid bodies"},
      // A rotation prescribed.
      {plate_deck(1.0, "", "*BOUNDARY\n18, 1, 1, 0.1\n"), "18, 1, 1, 0.1", "a rotation of rigid body PLATE is prescribed"},
      // A force on the reference node.
      {plate_deck(1.0, "", "*CLOAD\n17, 3, -1.0\n"), "17, 3, -1.0", "*CLOAD: a force on a rigid body's node"},
      // A master surface on the foam.
      {[&] {
         std::string d = ok;
         d.replace(d.find("STOP, SPLATE"), 12, "SPLATE, STOP");
         return d;
       }(),
       "SPLATE, STOP", "the master surface STOP must lie on the elements of one *RIGID BODY"},
      // The reference node is a node of the foam.
      {[&] {
         std::string d = ok;
         for (const auto& [from, to] : {std::pair<std::string, std::string>{"REF NODE=17", "REF NODE=8"},
                                        {"17, 1, 2", "8, 1, 2"}, {"17, 3, 3,", "8, 3, 3,"}})
           d.replace(d.find(from), from.size(), to);
         return d;
       }(),
       "*RIGID BODY", "its reference or rotation node 8 belongs to the deformable element 1"},
      {[&] {
         std::string d = ok;
         d.replace(d.find("STOP, SPLATE"), 12, "STOP, NOWHERE");
         return d;
       }(),
       "STOP, NOWHERE", "unknown surface 'NOWHERE'"},
      {[&] {
         std::string d = ok;
         d.replace(d.find(std::to_string(kSlope) + ", 1e-9"), std::to_string(kSlope).size(), "0");
         return d;
       }(),
       "0, 1e-9", "the slope K must be > 0"},
      {[&] {
         std::string d = ok;
         d.replace(d.find("PRESSURE-OVERCLOSURE=LINEAR"), 27, "PRESSURE-OVERCLOSURE=EXPONENTIAL");
         return d;
       }(),
       "*SURFACE BEHAVIOR", "PRESSURE-OVERCLOSURE must be HARD or LINEAR"},
      {[&] {
         std::string d = ok;
         d.replace(d.find("*NODE PRINT, NSET=ALL, TIME POINTS=TP"), 37, "*NODE PRINT, NSET=ALL, TIME POINTS=XX");
         return d;
       }(),
       "*NODE PRINT", "unknown *TIME POINTS 'XX'"},
  };
  for (const auto& c : cases) {
    const CommandRun r = run_cushion("run " + quoted(write_text(dir, c.deck)) + " -o " + quoted(dir / "out"));
    ASSERT_GT(line_of(c.deck, c.line_start), 0) << c.line_start;
    cli_test::expect_input_error(
        r, {(dir / "model.inp").string() + ":" + std::to_string(line_of(c.deck, c.line_start)) + ": ", c.message});
    EXPECT_FALSE(fs::exists(dir / "out")) << c.message;
  }
}
