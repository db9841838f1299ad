// Requirement: `cushion run` on an ABAQUS/CalculiX deck that also meshes the indenter shall import only
// the element set named by mesh.elset (the indenter would otherwise be imported as foam), report every keyword the mesh import skips once on stderr with its file and
// line (repeated keywords counted), and reject an unknown element set with one line naming the key and
// the deck's element sets, writing nothing.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "cli_runner.hpp"

namespace fs = std::filesystem;

namespace {

using cli_test::CommandRun;
using cli_test::quoted;
using cli_test::run_cushion;

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// A 10 mm C3D8 foam cube (ELSET=FOAM) and a C3D4 indenter above it (ELSET=INDENTER, NSET=NIND), two
// element blocks of different types, with the material and step keywords of a CalculiX deck.
const char* kDeck = R"(*HEADING
foam cube and a meshed indenter
*NODE, NSET=NFOAM
1, 0, 0, 0
2, 10, 0, 0
3, 10, 10, 0
4, 0, 10, 0
5, 0, 0, 10
6, 10, 0, 10
7, 10, 10, 10
8, 0, 10, 10
*NODE, NSET=NIND
11, 0, 0, 20
12, 10, 0, 20
13, 0, 10, 20
14, 0, 0, 30
*ELEMENT, TYPE=C3D8, ELSET=FOAM
1, 1, 2, 3, 4, 5, 6, 7, 8
*ELEMENT, TYPE=C3D4, ELSET=INDENTER
2, 11, 12, 13, 14
*MATERIAL, NAME=FOAM
*HYPERFOAM, N=1
0.01, 10, 0
*SOLID SECTION, ELSET=FOAM, MATERIAL=FOAM
*SOLID SECTION, ELSET=INDENTER, MATERIAL=FOAM
*STEP, NLGEOM
*STATIC
*BOUNDARY
1, 1, 3
*BOUNDARY
2, 3, 3
*END STEP
)";

fs::path write_case(const fs::path& dir, const std::string& mesh) {
  std::ofstream(dir / "model.inp") << kDeck;
  const std::string material = std::string(CUSHION_SOURCE_DIR) + "/cases/materials/paper_table3.json";
  std::ofstream(dir / "case.json") << R"({"mesh": )" << mesh << R"(, "material": {"file": ")" << material << R"("},
    "sets": {"bottom": "z == 0", "top": "z == 10"},
    "steps": [{"name": "press", "type": "static", "time_period_s": 1, "increment": {"initial_s": 0.5},
               "boundary": [{"set": "bottom", "type": "fixed"}, {"set": "top", "dof": "z", "value_mm": -1}]}]})";
  return dir / "case.json";
}

CommandRun run(const fs::path& dir, const std::string& mesh) {
  return run_cushion("run " + quoted(write_case(dir, mesh)) + " -o " + quoted(dir / "out") + " --quiet");
}

}  // namespace

TEST(CliInp, ElementSetImportsOnlyTheFoamAndSkippedKeywordsAreWarnedWithTheirLines) {
  const fs::path dir = cli_test::scratch_dir("cushion_test_cli_inp_");
  const CommandRun r = run(dir, R"({"inp": "model.inp", "elset": "FOAM"})");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string at = "cushion: warning: " + (dir / "model.inp").string() + ":";
  const std::string reads_only = "mesh import reads only *NODE, *ELEMENT, *NSET, *ELSET, *SURFACE, *INCLUDE)\n";
  for (const std::string& line :
       {at + "1: keyword *HEADING ignored (" + reads_only, at + "21: keyword *MATERIAL ignored (" + reads_only,
        at + "22: keyword *HYPERFOAM ignored (" + reads_only,
        at + "24: keyword *SOLID SECTION ignored (2 times, the first here; " + reads_only,
        at + "28: keyword *BOUNDARY ignored (2 times, the first here; " + reads_only,
        std::string("cushion: warning: element set 'FOAM' kept (1 of 2 elements, 8 of 12 nodes); sets and surfaces outside "
        "it dropped: NIND, INDENTER\n")})
    EXPECT_EQ(count(r.output, line), 1u) << line << "\n" << r.output;
  EXPECT_EQ(count(r.output, "cushion: warning: "), 9u) << r.output;  // + *STEP, *STATIC, *END STEP
  EXPECT_NE(r.output.find("model: 8 nodes, 1 elements"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(dir / "out" / "results.pvd"));

  // Without the element set the indenter's tet is imported as foam too.
  fs::remove_all(dir / "out");
  const CommandRun all = run(dir, R"({"inp": "model.inp"})");
  EXPECT_NE(all.output.find("model: 12 nodes, 2 elements"), std::string::npos) << all.output;
  EXPECT_EQ(count(all.output, "cushion: warning: "), 8u) << all.output;  // the keywords, no dropped sets
}

TEST(CliInp, UnknownOrMisplacedElementSetIsOneInputErrorAndNothingIsWritten) {
  const fs::path dir = cli_test::scratch_dir("cushion_test_cli_inp_");
  const struct {
    std::string mesh, message;
  } cases[] = {
      {R"({"inp": "model.inp", "elset": "FOAMS"})",
       "mesh.elset: no element set 'FOAMS' (element sets: FOAM, INDENTER) in "},
      {R"({"inp": "model.inp", "elset": ""})", "mesh.elset: must name an element set of the .inp file"},
      {R"({"inp": "model.inp", "elsett": "FOAM"})", "did you mean 'elset'"},
      {R"({"generate": {"type": "hex8", "box_mm": [0, 10, 0, 10, 0, 10], "elements": [1, 1, 1]}, "elset": "FOAM"})",
       "mesh.elset: is an option of \"inp\" meshes only"},
  };
  for (const auto& c : cases) {
    const CommandRun r = run(dir, c.mesh);
    EXPECT_EQ(r.exit_code, 2) << c.mesh << "\n" << r.output;
    EXPECT_EQ(r.output.rfind("cushion: input error: " + (dir / "case.json").string() + ": ", 0), 0u) << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << c.message << "\n" << r.output;
    EXPECT_EQ(count(r.output, "\n"), 1u) << r.output;  // no warnings before an input error
    EXPECT_FALSE(fs::exists(dir / "out")) << c.mesh;
  }
}
