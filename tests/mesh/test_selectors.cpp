// Node selectors (text and struct forms) and node set -> surface.
#include <gtest/gtest.h>

#include "io/input_error.hpp"
#include "mesh/selectors.hpp"
#include "mesh/structured_hex.hpp"

namespace cm = cushion::mesh;
using cm::Vec3;

namespace {

cm::Mesh block() {  // 10 x 10 x 10 mm, 5 x 5 x 5 hexes, node spacing 2 mm
  cm::BlockSpec spec;
  spec.low = Vec3(0, 0, 0);
  spec.high = Vec3(10, 10, 10);
  spec.n = {5, 5, 5};
  return cm::structured_block(spec);
}

std::string error_of(const std::string& text) {
  try {
    cm::parse_selector(text, "case.json:selector");
  } catch (const cushion::InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Selectors, ParseCompactText) {
  const auto z0 = std::get<cm::PlaneSelector>(cm::parse_selector("z == 0"));
  EXPECT_EQ(z0.axis, 2);
  EXPECT_EQ(z0.op, cm::Comparison::equal);
  EXPECT_EQ(z0.value, 0.0);
  EXPECT_LT(z0.tol, 0.0);  // automatic
  const auto x = std::get<cm::PlaneSelector>(cm::parse_selector("  x <= 1e-6 tol 0.5 "));
  EXPECT_EQ(x.axis, 0);
  EXPECT_EQ(x.op, cm::Comparison::less_equal);
  EXPECT_EQ(x.value, 1e-6);
  EXPECT_EQ(x.tol, 0.5);
  EXPECT_EQ(std::get<cm::PlaneSelector>(cm::parse_selector("y>3")).op, cm::Comparison::greater);
  const auto box = std::get<cm::BoxSelector>(cm::parse_selector("box(0,0,0, 4,4,10)"));
  EXPECT_EQ(box.high, Vec3(4, 4, 10));
  const auto cyl = std::get<cm::CylinderSelector>(cm::parse_selector("cylinder(5,5,0, 0,0,1, 3)"));
  EXPECT_EQ(cyl.radius, 3.0);
  EXPECT_TRUE(std::holds_alternative<cm::AllSelector>(cm::parse_selector("ALL")));
}

TEST(Selectors, ParseErrorsNameTheBadText) {
  EXPECT_NE(error_of("z == abc").find("case.json:selector: selector 'z == abc': bad number 'abc'"),
            std::string::npos) << error_of("z == abc");
  EXPECT_NE(error_of("w == 0").find("unknown axis or selector 'w'"), std::string::npos);
  EXPECT_NE(error_of("z != 0").find("bad comparison '!='"), std::string::npos) << error_of("z != 0");
  EXPECT_NE(error_of("sphere(1,2,3)").find("expected 4 numbers, got 3"), std::string::npos);
  EXPECT_NE(error_of("box(5,0,0, 1,1,1)").find("low corner"), std::string::npos);
  EXPECT_NE(error_of("z == 0 tol -1").find("tolerance"), std::string::npos);
  EXPECT_THROW(cm::select_nodes(block(), cm::Selector{cm::PlaneSelector{3}}), cushion::InputError);
}

// Selected sets equal a brute-force count on the 6 x 6 x 6 node lattice with coordinates 2 i mm.
TEST(Selectors, SelectionMatchesLatticeCounts) {
  const cm::Mesh mesh = block();
  EXPECT_EQ(cm::select_nodes(mesh, cm::parse_selector("z == 0")).size(), 36u);
  EXPECT_EQ(cm::select_nodes(mesh, cm::parse_selector("x <= 4")).size(), 3u * 36u);   // x = 0, 2, 4
  EXPECT_EQ(cm::select_nodes(mesh, cm::parse_selector("x < 4")).size(), 2u * 36u);    // x = 0, 2
  EXPECT_EQ(cm::select_nodes(mesh, cm::parse_selector("y >= 9.5 tol 0.6")).size(), 36u);
  EXPECT_EQ(cm::select_nodes(mesh, cm::parse_selector("box(0,0,0, 4,4,10)")).size(), 9u * 6u);
  // sphere of radius 2 about the lattice node (4,4,4): itself and its 6 neighbours
  EXPECT_EQ(cm::select_nodes(mesh, cm::parse_selector("sphere(4,4,4, 2)")).size(), 7u);
  // cylinder radius 2.9 about x = y = 4 along z: (4,4), 4 neighbours at 2, 4 diagonal at 2.83
  EXPECT_EQ(cm::select_nodes(mesh, cm::parse_selector("cylinder(4,4,0, 0,0,1, 2.9)")).size(), 9u * 6u);
  EXPECT_EQ(cm::select_nodes(mesh, cm::parse_selector("all")).size(), 216u);
  for (int n : cm::select_nodes(mesh, cm::parse_selector("sphere(4,4,4, 2)")))
    EXPECT_LE((mesh.nodes[n] - Vec3(4, 4, 4)).norm(), 2.0 + 1e-9);
}

// Top face nodes -> 25 boundary quads on z = 10; a disc of nodes under an indenter -> only faces
// whose four corners are all inside (2 x 2 quads around the centre for r = 2.9 at (4,4)).
TEST(Selectors, SurfaceFromNodeSet) {
  const cm::Mesh mesh = block();
  const auto top = cm::surface_from_node_set(mesh, cm::select_nodes(mesh, cm::parse_selector("z == 10")));
  EXPECT_EQ(top.size(), 25u);
  for (const cm::Face& f : top) EXPECT_EQ(f.face, 1);  // S2 = top of each hex
  cm::Selector disc = cm::CylinderSelector{Vec3(4, 4, 0), Vec3(0, 0, 1), 2.9, 1e-6};
  std::vector<int> nodes = cm::select_nodes(mesh, disc);
  std::vector<int> on_top;
  for (int n : nodes)
    if (mesh.nodes[n].z() == 10.0) on_top.push_back(n);
  EXPECT_EQ(cm::surface_from_node_set(mesh, on_top).size(), 4u);
}
