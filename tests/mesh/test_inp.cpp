// ABAQUS .inp reader/writer: a deck with every supported keyword, round trip, malformed decks.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "io/input_error.hpp"
#include "mesh/inp_reader.hpp"
#include "mesh/structured_hex.hpp"

namespace cm = cushion::mesh;
using cm::Vec3;

namespace {

// Two C3D8 (labels 11, 12) side by side on [0,2]x[0,1]x[0,1] plus one C3D4 (21) and one C3D10 (31)
// on separate nodes; labels deliberately not contiguous.
const char* kDeck = R"(*HEADING
cushion test deck
** comment line
*NODE, NSET=NALL
1, 0, 0, 0
2, 1, 0, 0
3, 1, 1, 0
4, 0, 1, 0
5, 0, 0, 1
6, 1, 0, 1
7, 1, 1, 1
8, 0, 1, 1
9, 2, 0, 0
10, 2, 1, 0
11, 2, 0, 1
12, 2, 1, 1
*Node
101, 10., 0., 0.
102, 11., 0., 0.
103, 10., 1., 0.
104, 10., 0., 1.
105, 10.5, 0, 0
106, 10.5, 0.5, 0
107, 10, 0.5, 0
108, 10, 0, 0.5
109, 10.5, 0, 0.5
110, 10, 0.5, 0.5
*ELEMENT, TYPE=C3D8, ELSET=FOAM
11, 1, 2, 3, 4, 5, 6, 7, 8
12, 2, 9, 10, 3,
 6, 11, 12, 7
*Element, type=C3D4, elset=TETS
21, 101, 102, 103, 104
*ELEMENT, TYPE=C3D10, ELSET=TETS
31, 101, 102, 103, 104, 105, 106, 107,
108, 109, 110
*NSET, NSET=BOTTOM
1, 2, 3, 4,
9, 10
*NSET, NSET=ODD, GENERATE
1, 11, 2
*NSET, NSET=BOTH
BOTTOM, 5
*NSET, NSET=HEXNODES, ELSET=FOAM
*ELSET, ELSET=ALLEL
FOAM, tets
*ELSET, ELSET=GEN, GENERATE
11, 12
*SURFACE, TYPE=ELEMENT, NAME=TOP
FOAM, S2
*SURFACE, NAME=MIXED
21, S1
31, s3
*SURFACE, NAME=FREE
FOAM
*MATERIAL, NAME=FOAM
*HYPERFOAM, N=2
0.1, 2.0, 0.05, -1.0, 0., 0.
*STEP
*STATIC
*END STEP
)";

std::string error_of(const std::string& deck) {
  try {
    cm::parse_inp(deck, "model.inp");
  } catch (const cushion::InputError& e) {
    return e.what();
  }
  return "(no error)";
}

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

void expect_same(const cm::Mesh& a, const cm::Mesh& b) {
  ASSERT_EQ(a.num_nodes(), b.num_nodes());
  for (std::size_t i = 0; i < a.num_nodes(); ++i) {
    EXPECT_EQ(a.nodes[i], b.nodes[i]);  // 17 significant digits: exact round trip
    EXPECT_EQ(a.node_labels[i], b.node_labels[i]);
  }
  ASSERT_EQ(a.num_elements(), b.num_elements());
  for (std::size_t e = 0; e < a.num_elements(); ++e) {
    EXPECT_EQ(a.elements[e].type, b.elements[e].type);
    EXPECT_EQ(a.elements[e].label, b.elements[e].label);
    EXPECT_EQ(a.elements[e].nodes, b.elements[e].nodes);
  }
  EXPECT_EQ(a.node_sets, b.node_sets);
  EXPECT_EQ(a.element_sets, b.element_sets);
  ASSERT_EQ(a.surfaces.size(), b.surfaces.size());
  for (const auto& [name, faces] : a.surfaces) {
    const auto& other = b.surfaces.at(name);
    ASSERT_EQ(faces.size(), other.size()) << name;
    for (std::size_t k = 0; k < faces.size(); ++k) {
      EXPECT_EQ(faces[k].element, other[k].element);
      EXPECT_EQ(faces[k].face, other[k].face);
    }
  }
}

}  // namespace

TEST(InpReader, ReadsEveryKeyword) {
  std::vector<std::string> notes;
  const cm::Mesh mesh = cm::parse_inp(kDeck, "model.inp", &notes);
  ASSERT_EQ(mesh.num_nodes(), 22u);
  EXPECT_EQ(mesh.node_labels[12], 101);
  EXPECT_EQ(mesh.nodes[13], Vec3(11, 0, 0));
  ASSERT_EQ(mesh.num_elements(), 4u);
  EXPECT_EQ(mesh.elements[1].label, 12);
  // continuation line: element 12 = nodes 2, 9, 10, 3, 6, 11, 12, 7 -> indices
  EXPECT_EQ((std::vector<int>(mesh.elements[1].nodes.begin(), mesh.elements[1].nodes.begin() + 8)),
            (std::vector<int>{1, 8, 9, 2, 5, 10, 11, 6}));
  EXPECT_EQ(mesh.elements[3].type, cm::ElementType::tet10);
  EXPECT_EQ(mesh.elements[3].nodes[9], 21);
  EXPECT_EQ(mesh.node_sets.at("NALL").size(), 12u);
  EXPECT_EQ(mesh.node_sets.at("BOTTOM"), (std::vector<int>{0, 1, 2, 3, 8, 9}));
  EXPECT_EQ(mesh.node_sets.at("ODD"), (std::vector<int>{0, 2, 4, 6, 8, 10}));
  EXPECT_EQ(mesh.node_sets.at("BOTH"), (std::vector<int>{0, 1, 2, 3, 4, 8, 9}));
  EXPECT_EQ(mesh.node_sets.at("HEXNODES").size(), 12u);
  EXPECT_EQ(mesh.element_sets.at("FOAM"), (std::vector<int>{0, 1}));
  EXPECT_EQ(mesh.element_sets.at("TETS"), (std::vector<int>{2, 3}));
  EXPECT_EQ(mesh.element_sets.at("ALLEL"), (std::vector<int>{0, 1, 2, 3}));  // "tets": any case
  EXPECT_EQ(mesh.element_sets.at("GEN"), (std::vector<int>{0, 1}));
  const auto& top = mesh.surfaces.at("TOP");
  ASSERT_EQ(top.size(), 2u);
  EXPECT_EQ(top[1].element, 1);
  EXPECT_EQ(top[1].face, 1);
  EXPECT_EQ(mesh.surfaces.at("MIXED")[1].face, 2);
  EXPECT_EQ(mesh.surfaces.at("FREE").size(), 10u);  // 2 hexes side by side: 12 - 2 shared faces
  // Notes: *HEADING, *MATERIAL, *HYPERFOAM, *STEP, *STATIC, *END STEP skipped, with file:line.
  ASSERT_EQ(notes.size(), 6u);
  const std::string read_only = " (mesh import reads only *NODE, *ELEMENT, *NSET, *ELSET, *SURFACE, *INCLUDE)";
  EXPECT_EQ(notes[0], "model.inp:1: keyword *HEADING ignored" + read_only);
  EXPECT_EQ(notes[5], "model.inp:61: keyword *END STEP ignored" + read_only);
}

TEST(InpReader, RepeatedIgnoredKeywordIsReportedOnceWithItsCount) {
  const std::string deck = std::string(kDeck) + "*STEP\n*BOUNDARY\n1, 1, 3\n*END STEP\n*BOUNDARY\n2, 1, 3\n";
  std::vector<std::string> notes;
  cm::parse_inp(deck, "model.inp", &notes);
  ASSERT_EQ(notes.size(), 7u);  // the 6 keywords of kDeck once each, then *BOUNDARY
  EXPECT_EQ(notes[3], "model.inp:59: keyword *STEP ignored (2 times, the first here; mesh import reads only "
                      "*NODE, *ELEMENT, *NSET, *ELSET, *SURFACE, *INCLUDE)");
  EXPECT_EQ(notes[6].rfind("model.inp:63: keyword *BOUNDARY ignored (2 times, the first here; ", 0), 0u) << notes[6];
}

// A deck with a meshed indenter (the tets of kDeck stand for it): only the foam's element set is kept.
TEST(InpReader, ElementSetPartKeepsItsElementsNodesAndSets) {
  const cm::Mesh all = cm::parse_inp(kDeck, "model.inp");
  std::vector<std::string> notes;
  const cm::Mesh foam = cm::element_set_part(all, "foam", &notes);  // case-insensitive, as ABAQUS
  ASSERT_EQ(foam.num_elements(), 2u);
  ASSERT_EQ(foam.num_nodes(), 12u);
  EXPECT_EQ(foam.node_labels.back(), 12);
  EXPECT_EQ(foam.nodes[8], Vec3(2, 0, 0));
  EXPECT_EQ(foam.elements[1].label, 12);
  EXPECT_EQ(foam.elements[1].nodes, all.elements[1].nodes);  // nodes 1..12 keep their indices
  EXPECT_EQ(foam.node_sets.at("BOTTOM"), all.node_sets.at("BOTTOM"));
  EXPECT_EQ(foam.element_sets.at("ALLEL"), (std::vector<int>{0, 1}));
  EXPECT_EQ(foam.element_sets.count("TETS"), 0u);
  EXPECT_EQ(foam.surfaces.at("FREE").size(), 10u);
  EXPECT_EQ(foam.surfaces.count("MIXED"), 0u);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_EQ(notes[0], "element set 'foam' kept (2 of 4 elements, 12 of 22 nodes); sets and surfaces outside it "
                      "dropped: TETS, MIXED");
  EXPECT_NO_THROW(cm::check_elements(foam, "foam"));

  // The other part: two element types, nodes renumbered from 0, sets of the foam dropped.
  const cm::Mesh tets = cm::element_set_part(all, "TETS");
  ASSERT_EQ(tets.num_nodes(), 10u);
  EXPECT_EQ(tets.node_labels.front(), 101);
  EXPECT_EQ(tets.elements[0].type, cm::ElementType::tet4);
  EXPECT_EQ(tets.elements[1].type, cm::ElementType::tet10);
  EXPECT_EQ(tets.elements[1].nodes[9], 9);
  EXPECT_EQ(tets.surfaces.at("MIXED").size(), 2u);
  EXPECT_TRUE(tets.node_sets.empty());
  EXPECT_NO_THROW(cm::check_elements(tets, "tets"));

  try {
    cm::element_set_part(all, "INDENTER");
    FAIL() << "an unknown element set was accepted";
  } catch (const cushion::InputError& e) {
    EXPECT_EQ(std::string(e.what()), "no element set 'INDENTER' (element sets: ALLEL, FOAM, GEN, TETS)");
  }
}

TEST(InpReader, RoundTripThroughWriter) {
  const cm::Mesh mesh = cm::parse_inp(kDeck, "model.inp");
  std::ostringstream written;
  cm::write_inp(mesh, written);
  expect_same(mesh, cm::parse_inp(written.str(), "written.inp"));

  cm::BlockSpec spec;  // graded coordinates with non-terminating decimals
  spec.n = {3, 2, 2};
  spec.high = Vec3(1.0 / 3.0, 0.7, 2.0);
  spec.grading[0] = {cm::AxisGrading::Kind::geometric, 2.7, 0.0};
  spec.type = cm::ElementType::tet4;
  const cm::Mesh block = cm::structured_block(spec);
  std::ostringstream again;
  cm::write_inp(block, again);
  expect_same(block, cm::parse_inp(again.str(), "block.inp"));
}

TEST(InpReader, IncludeFile) {
  const auto dir = std::filesystem::temp_directory_path() / ("cushion_inp_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  { std::ofstream(dir / "nodes.inp") << "*NODE\n1,0,0,0\n2,1,0,0\n3,0,1,0\n4,0,0,1\n"; }
  { std::ofstream(dir / "main.inp") << "*INCLUDE, INPUT=nodes.inp\n*ELEMENT, TYPE=C3D4\n1, 1,2,3,5\n"; }
  const std::string message = [&] {
    try {
      cm::read_inp((dir / "main.inp").string());
    } catch (const cushion::InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  }();
  EXPECT_NE(message.find("main.inp:3: *ELEMENT: undefined node label 5"), std::string::npos) << message;
  { std::ofstream(dir / "main.inp") << "*INCLUDE, INPUT=nodes.inp\n*ELEMENT, TYPE=C3D4\n1, 1,2,3,4\n"; }
  EXPECT_EQ(cm::read_inp((dir / "main.inp").string()).num_nodes(), 4u);
  std::filesystem::remove_all(dir);
}

// Each malformed deck names the file, line and keyword (kDeck line numbers: *HEADING = 1, *NODE = 4,
// *Node = 17, first *ELEMENT = 28, *NSET BOTTOM = 37, *SURFACE TOP = 49; comment lines count).
TEST(InpReader, MalformedDecksNameTheLine) {
  EXPECT_EQ(error_of(replace(kDeck, "2, 1, 0, 0\n", "2, 1, 0x, 0\n")),
            "model.inp:6: *NODE: bad number '0x'");
  EXPECT_EQ(error_of(replace(kDeck, "TYPE=C3D10,", "TYPE=C3D15,")),
            "model.inp:34: *ELEMENT: unknown TYPE=C3D15 (supported: C3D8, C3D8R, C3D4, C3D10, C3D20, C3D20R)");
  EXPECT_EQ(error_of(replace(kDeck, "21, 101, 102, 103, 104", "21, 101, 102, 103, 999")),
            "model.inp:33: *ELEMENT: undefined node label 999");
  EXPECT_EQ(error_of(replace(kDeck, "1, 11, 2\n", "11, 1, 2\n")),
            "model.inp:41: *NSET: bad GENERATE range 11, 1, 2 (need first <= last, increment > 0 "
            "dividing last - first)");
  EXPECT_EQ(error_of(replace(kDeck, "1, 11, 2\n", "1, 11, 0\n")).substr(0, 31),
            "model.inp:41: *NSET: bad GENERA");
  EXPECT_EQ(error_of(replace(kDeck, "102, 11., 0., 0.", "101, 11., 0., 0.")),
            "model.inp:19: *NODE: duplicate node label 101");
  EXPECT_EQ(error_of(replace(kDeck, "21, 101", "11, 101")),
            "model.inp:33: *ELEMENT: duplicate element label 11");
  EXPECT_EQ(error_of(replace(kDeck, "*NSET, NSET=HEXNODES, ELSET=FOAM", "*NSET, NSET=EMPTY")),
            "model.inp:44: *NSET: node set 'EMPTY' is empty");
  EXPECT_EQ(error_of(replace(kDeck, "FOAM, tets", "FOAM, NOSUCH")),
            "model.inp:46: *ELSET: unknown set 'NOSUCH'");
  EXPECT_EQ(error_of(replace(kDeck, "31, s3", "31, S5")),
            "model.inp:53: *SURFACE: bad face 'S5' for C3D10 element 31 (S1..S4)");
  EXPECT_EQ(error_of(replace(kDeck, "*NSET, NSET=BOTH", "*NSET, NAME=BOTH")),
            "model.inp:42: *NSET: missing NSET=");
  EXPECT_EQ(error_of(replace(kDeck, "12, 2, 9, 10, 3,\n", "12, 2, 9, 10, 3\n")),
            "model.inp:30: *ELEMENT: C3D8 needs a label and 8 nodes, got 5 fields");
  // Inverted element: bottom and top swapped.
  EXPECT_EQ(error_of(replace(kDeck, "11, 1, 2, 3, 4, 5, 6, 7, 8", "11, 5, 6, 7, 8, 1, 2, 3, 4"))
                .substr(0, 44),
            "model.inp: element 11 (C3D8): non-positive J");
  EXPECT_EQ(error_of("1, 2, 3\n"), "model.inp:1: data line before the first keyword");
}

// Fuzzing findings (issue 16): a keyword line that is only '*' crashed (front() of no fields); GENERATE
// over the whole int range overflowed and rejected a valid deck.
TEST(InpReader, FuzzFindingsAreInputErrors) {
  EXPECT_EQ(error_of("*\n"), "model.inp:1: empty keyword");
  EXPECT_EQ(error_of("*,\n"), "model.inp:1: empty keyword");
  EXPECT_EQ(error_of(replace(kDeck, "*HEADING\n", "*,\n")), "model.inp:1: empty keyword");
}

// Found while writing the fuzz harness (issue 16): *INCLUDE of a device (/dev/zero) was read for ever.
TEST(InpReader, IncludeOfANonRegularFileIsAnInputError) {
  EXPECT_EQ(error_of("*NODE\n1,0,0,0\n*INCLUDE, INPUT=/dev/zero\n"),
            "model.inp:3: *INCLUDE: '/dev/zero' is not a regular file");
  EXPECT_EQ(error_of("*INCLUDE, INPUT=/\n"), "model.inp:1: *INCLUDE: '/' is not a regular file");
}

TEST(InpReader, GenerateAtTheEndsOfTheIntRange) {
  const std::string deck = R"(*NODE
-2147483647, 0, 0, 0
0, 2, 0, 0
2147483645, 3, 0, 0
2147483647, 1, 0, 0
*NSET, NSET=ENDS, GENERATE
-2147483647, 2147483647, 2147483647
*NSET, NSET=TOP, GENERATE
2147483645, 2147483647, 2
*NSET, NSET=LAST, GENERATE
2147483647, 2147483647
)";
  const cm::Mesh mesh = cm::parse_inp(deck, "ends.inp");
  EXPECT_EQ(mesh.node_sets.at("ENDS").size(), 3u);  // -2147483647, 0, 2147483647
  EXPECT_EQ(mesh.node_sets.at("TOP").size(), 2u);
  EXPECT_EQ(mesh.node_sets.at("LAST").size(), 1u);
}
