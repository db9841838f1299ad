// TetGen meshes of a box and of closed STL surfaces; tet10 conversion; STL reading and checks.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <unistd.h>
#include <set>

#include "io/input_error.hpp"
#include "mesh/quadratic.hpp"
#include "mesh/stl.hpp"
#include "mesh/tetgen_mesher.hpp"

namespace cm = cushion::mesh;
using cm::Vec3;

namespace {

std::string temp_path(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("cushion_test_mesh_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

double total_volume(const cm::Mesh& mesh, double* smallest = nullptr) {
  double v = 0.0, vmin = INFINITY;
  for (int e = 0; e < static_cast<int>(mesh.num_elements()); ++e) {
    const double ve = cm::element_volume(mesh, e);
    v += ve;
    vmin = std::min(vmin, ve);
  }
  if (smallest) *smallest = vmin;
  return v;
}

// Unit cube [0,1]^3 scaled to `size` mm, 12 triangles with outward orientation.
cm::TriangleSurface cube_surface(double size) {
  cm::TriangleSurface s;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) s.vertices.emplace_back(size * i, size * j, size * k);
  // corner index i + 2 j + 4 k; each side as two outward triangles
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    s.triangles.push_back({q[0], q[1], q[2]});
    s.triangles.push_back({q[0], q[2], q[3]});
  }
  return s;
}

// Icosphere: icosahedron subdivided `levels` times, vertices projected on the sphere.
cm::TriangleSurface sphere_surface(double radius, int levels) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  cm::TriangleSurface s;
  for (const Vec3& v : {Vec3(-1, t, 0), Vec3(1, t, 0), Vec3(-1, -t, 0), Vec3(1, -t, 0),
                        Vec3(0, -1, t), Vec3(0, 1, t), Vec3(0, -1, -t), Vec3(0, 1, -t),
                        Vec3(t, 0, -1), Vec3(t, 0, 1), Vec3(-t, 0, -1), Vec3(-t, 0, 1)})
    s.vertices.push_back(radius * v.normalized());
  s.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                 {3, 8, 9},  {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int, int>, int> mid;
    const auto midpoint = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto [it, inserted] = mid.try_emplace({key.first, key.second}, static_cast<int>(s.vertices.size()));
      if (inserted) s.vertices.push_back(radius * (s.vertices[a] + s.vertices[b]).normalized());
      return it->second;
    };
    std::vector<std::array<int, 3>> finer;
    for (const auto& tri : s.triangles) {
      const int ab = midpoint(tri[0], tri[1]), bc = midpoint(tri[1], tri[2]), ca = midpoint(tri[2], tri[0]);
      finer.push_back({tri[0], ab, ca});
      finer.push_back({tri[1], bc, ab});
      finer.push_back({tri[2], ca, bc});
      finer.push_back({ab, bc, ca});
    }
    s.triangles = finer;
  }
  return s;
}

}  // namespace

TEST(Tetgen, SwitchString) {
  cm::TetgenOptions o;
  o.max_radius_edge = 1.4;
  o.min_dihedral = 10;
  o.max_volume = 2.5;
  EXPECT_EQ(cm::tetgen_switches(o), "pq1.4/10a2.5O0Q");
  o.verbose = true;
  o.max_radius_edge = 0;
  o.max_volume = 0;
  o.optimise = true;
  EXPECT_EQ(cm::tetgen_switches(o), "p");
  o.max_radius_edge = 0.5;
  EXPECT_THROW(cm::tetgen_box(Vec3::Zero(), Vec3::Ones(), o), cushion::InputError);
}

// Box 40 x 30 x 20 mm: total volume = 24000 mm^3 to 1e-10 relative, every tet positive, every tet
// below the volume bound, radius-edge ratio <= 1.5 (+1e-9), side sets exactly on their planes.
// (With optimise = true TetGen's smoothing breaks both bounds: 12.7 mm^3 and 1.516 for a = 10.)
TEST(Tetgen, BoxVolumeQualityAndSets) {
  cm::TetgenOptions o;
  o.max_radius_edge = 1.5;
  o.max_volume = 10.0;
  const cm::Mesh mesh = cm::tetgen_box(Vec3(0, 0, 0), Vec3(40, 30, 20), o);
  ASSERT_GT(mesh.num_elements(), 2400u);  // at least 24000 / 10 tets
  double smallest = 0.0;
  EXPECT_NEAR(total_volume(mesh, &smallest), 24000.0, 1e-10 * 24000.0);
  EXPECT_GT(smallest, 0.0);
  for (int e = 0; e < static_cast<int>(mesh.num_elements()); ++e)
    EXPECT_LE(cm::element_volume(mesh, e), 10.0 * (1 + 1e-12));
  EXPECT_LE(cm::max_radius_edge_ratio(mesh), 1.5 + 1e-9);
  EXPECT_NO_THROW(cm::check_elements(mesh));
  for (int n : mesh.node_sets.at("zmax")) EXPECT_NEAR(mesh.nodes[n].z(), 20.0, 1e-12);
  double area = 0.0;
  for (const cm::Face& f : mesh.surfaces.at("xmin")) {
    const auto& el = mesh.elements[f.element];
    const auto l = cm::face_nodes(el.type, f.face);
    const Vec3 n = (mesh.nodes[el.nodes[l[1]]] - mesh.nodes[el.nodes[l[0]]])
                       .cross(mesh.nodes[el.nodes[l[2]]] - mesh.nodes[el.nodes[l[0]]]);
    EXPECT_LT(n.x(), 0.0);  // outward on x = 0
    area += 0.5 * n.norm();
  }
  EXPECT_NEAR(area, 30.0 * 20.0, 1e-10 * 600.0);
  EXPECT_EQ(cm::boundary_faces(mesh).size(), [&] {
    std::size_t n = 0;
    for (const auto& [name, faces] : mesh.surfaces) n += faces.size();
    return n;
  }());
}

// Tet10: one mid node per distinct tet4 edge (counted independently from the element edges), at
// the edge midpoint (1e-12 mm) and shared by every element around the edge; volume unchanged.
TEST(Tetgen, QuadraticMidNodesShared) {
  cm::TetgenOptions o;
  o.max_volume = 20.0;
  const cm::Mesh linear = cm::tetgen_box(Vec3(0, 0, 0), Vec3(10, 10, 10), o);
  const cm::Mesh quad = cm::to_tet10(linear);
  const int edges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  std::map<std::pair<int, int>, int> mid_of_edge;
  for (std::size_t e = 0; e < quad.num_elements(); ++e) {
    ASSERT_EQ(quad.elements[e].type, cm::ElementType::tet10);
    for (int m = 0; m < 6; ++m) {
      const int a = quad.elements[e].nodes[edges[m][0]], b = quad.elements[e].nodes[edges[m][1]];
      const int mid = quad.elements[e].nodes[4 + m];
      EXPECT_NEAR((quad.nodes[mid] - 0.5 * (quad.nodes[a] + quad.nodes[b])).norm(), 0.0, 1e-12);
      const auto [it, inserted] = mid_of_edge.try_emplace(std::minmax(a, b), mid);
      EXPECT_EQ(it->second, mid) << "edge not shared";
    }
  }
  EXPECT_EQ(quad.num_nodes(), linear.num_nodes() + mid_of_edge.size());
  EXPECT_NEAR(total_volume(quad), 1000.0, 1e-10 * 1000.0);
  EXPECT_EQ(cm::boundary_faces(quad).size(), cm::boundary_faces(linear).size());
  // zmin face: corners and mid nodes of the boundary triangles, all at z = 0
  std::set<int> expected;
  for (const cm::Face& f : quad.surfaces.at("zmin"))
    for (int l : cm::face_nodes(quad.elements[f.element].type, f.face))
      expected.insert(quad.elements[f.element].nodes[l]);
  const auto& zmin = quad.node_sets.at("zmin");
  EXPECT_EQ(std::set<int>(zmin.begin(), zmin.end()), expected);
  cm::TetgenOptions q = o;
  q.quadratic = true;
  EXPECT_EQ(cm::tetgen_box(Vec3(0, 0, 0), Vec3(10, 10, 10), q).elements[0].type, cm::ElementType::tet10);
}

// A closed cube STL (ASCII and binary) reads back to 8 merged vertices and meshes to its volume
// 8000 mm^3 (1e-10 relative); a sphere STL meshes to the volume of its polyhedron.
TEST(Tetgen, ClosedStlMeshes) {
  for (bool binary : {false, true}) {
    const std::string path = temp_path(binary ? "cube_bin.stl" : "cube_ascii.stl");
    cm::write_stl(cube_surface(20.0), path, binary);
    const cm::TriangleSurface s = cm::read_stl(path);
    EXPECT_EQ(s.vertices.size(), 8u);
    EXPECT_EQ(s.triangles.size(), 12u);
    EXPECT_NO_THROW(cm::check_closed(s, path));
    EXPECT_NEAR(cm::enclosed_volume(s), 8000.0, 1e-9);
    cm::TetgenOptions o;
    o.max_volume = 100.0;
    const cm::Mesh mesh = cm::tetgen_surface(s, o, path);
    double smallest = 0.0;
    EXPECT_NEAR(total_volume(mesh, &smallest), 8000.0, 1e-10 * 8000.0);
    EXPECT_GT(smallest, 0.0);
    EXPECT_FALSE(mesh.surfaces.at("boundary").empty());
  }
  const cm::TriangleSurface sphere = sphere_surface(10.0, 2);  // 320 triangles
  const std::string path = temp_path("sphere.stl");
  cm::write_stl(sphere, path, false);
  const cm::TriangleSurface read = cm::read_stl(path);
  EXPECT_EQ(read.vertices.size(), sphere.vertices.size());
  const double polyhedron = cm::enclosed_volume(read);
  EXPECT_NEAR(polyhedron, 4.0 / 3.0 * M_PI * 1000.0, 0.05 * 4188.8);  // inscribed polyhedron
  cm::TetgenOptions o;
  o.max_volume = 20.0;
  o.min_dihedral = 10.0;
  const cm::Mesh mesh = cm::tetgen_surface(read, o, path);
  EXPECT_NEAR(total_volume(mesh), polyhedron, 1e-10 * polyhedron);
  EXPECT_NO_THROW(cm::check_elements(mesh));
}

TEST(Tetgen, OpenStlRejected) {
  cm::TriangleSurface open = cube_surface(1.0);
  open.triangles.pop_back();  // a hole: 3 open edges
  const std::string path = temp_path("open.stl");
  cm::write_stl(open, path, false);
  try {
    cm::tetgen_surface(cm::read_stl(path), cm::TetgenOptions{}, path);
    FAIL() << "open surface accepted";
  } catch (const cushion::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path + ": surface not closed/manifold: 3 open edge(s)"),
              std::string::npos) << e.what();
  }
  cm::TriangleSurface flipped = cube_surface(1.0);
  std::swap(flipped.triangles[0][1], flipped.triangles[0][2]);
  EXPECT_THROW(cm::check_closed(flipped, "flipped"), cushion::InputError);
  const std::string bad = temp_path("bad.stl");
  { std::ofstream(bad) << "solid x\n facet normal 0 0 1\n outer loop\n vertex 0 0 zero\n"; }
  try {
    cm::read_stl(bad);
    FAIL();
  } catch (const cushion::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(bad + ":4: bad vertex"), std::string::npos) << e.what();
  }
}
