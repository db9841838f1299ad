// Element conventions of mesh/mesh.hpp: face tables, outward normals, volumes, validity checks.
#include <gtest/gtest.h>

#include <set>

#include "io/input_error.hpp"
#include "mesh/mesh.hpp"
#include "mesh/shape.hpp"
#include "mesh/structured_hex.hpp"

namespace cm = cushion::mesh;
using cm::ElementType;
using cm::Vec3;

namespace {

// One element on the unit cube [0,1]^3 (hex8) or the unit corner tet (tet4/tet10, straight sides).
cm::Mesh single(ElementType type) {
  cm::Mesh mesh;
  std::vector<Vec3> corners;
  for (const Vec3& xi : cm::corner_coordinates(type))
    corners.push_back(type == ElementType::hex8 ? Vec3(0.5 * (xi.array() + 1.0)) : xi);
  mesh.nodes = corners;
  if (type == ElementType::tet10) {
    const int edges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
    for (const auto& e : edges) mesh.nodes.push_back(0.5 * (corners[e[0]] + corners[e[1]]));
  }
  cm::Element element{type, {}, 7};
  for (int a = 0; a < cm::nodes_per_element(type); ++a) element.nodes[a] = a;
  mesh.elements.push_back(element);
  for (int a = 0; a < cm::nodes_per_element(type); ++a) mesh.node_labels.push_back(a + 1);
  return mesh;
}

Vec3 centroid(const cm::Mesh& mesh, const std::vector<int>& nodes) {
  Vec3 c = Vec3::Zero();
  for (int n : nodes) c += mesh.nodes[n];
  return c / static_cast<double>(nodes.size());
}

}  // namespace

TEST(MeshCore, CountsAndNames) {
  EXPECT_EQ(cm::nodes_per_element(ElementType::hex8), 8);
  EXPECT_EQ(cm::nodes_per_element(ElementType::tet4), 4);
  EXPECT_EQ(cm::nodes_per_element(ElementType::tet10), 10);
  EXPECT_EQ(cm::faces_per_element(ElementType::hex8), 6);
  EXPECT_EQ(cm::faces_per_element(ElementType::tet10), 4);
  EXPECT_EQ(cm::to_string(ElementType::tet10), "C3D10");
  EXPECT_THROW(cm::face_nodes(ElementType::tet4, 4), std::out_of_range);
}

// The node sets of each face equal the ABAQUS face tables (1-based): C3D8 S1 = 1-2-3-4,
// S2 = 5-8-7-6, S3 = 1-5-6-2, S4 = 2-6-7-3, S5 = 3-7-8-4, S6 = 4-8-5-1; tets S1 = 1-2-3,
// S2 = 1-4-2, S3 = 2-4-3, S4 = 3-4-1.
TEST(MeshCore, FaceNodeSetsMatchAbaqusTables) {
  const std::vector<std::set<int>> hex = {{1, 2, 3, 4}, {5, 8, 7, 6}, {1, 5, 6, 2},
                                          {2, 6, 7, 3}, {3, 7, 8, 4}, {4, 8, 5, 1}};
  const std::vector<std::set<int>> tet = {{1, 2, 3}, {1, 4, 2}, {2, 4, 3}, {3, 4, 1}};
  for (int f = 0; f < 6; ++f) {
    std::set<int> got;
    for (int a : cm::face_nodes(ElementType::hex8, f)) got.insert(a + 1);
    EXPECT_EQ(got, hex[f]) << "S" << f + 1;
  }
  for (int f = 0; f < 4; ++f) {
    std::set<int> got;
    for (int a : cm::face_nodes(ElementType::tet4, f)) got.insert(a + 1);
    EXPECT_EQ(got, tet[f]) << "S" << f + 1;
  }
}

// Right-hand-rule normal of each face points away from the element centroid; the hex faces of the
// unit cube have unit outward normals along the expected axes. Exact arithmetic (tolerance 1e-15).
TEST(MeshCore, FaceNormalsPointOutward) {
  for (ElementType type : {ElementType::hex8, ElementType::tet4, ElementType::tet10}) {
    const cm::Mesh mesh = single(type);
    std::vector<int> all(cm::nodes_per_element(type));
    for (int a = 0; a < static_cast<int>(all.size()); ++a) all[a] = a;
    const Vec3 c = centroid(mesh, all);
    for (int f = 0; f < cm::faces_per_element(type); ++f) {
      const auto local = cm::face_nodes(type, f);
      const Vec3 &a = mesh.nodes[local[0]], &b = mesh.nodes[local[1]], &d = mesh.nodes[local[2]];
      const Vec3 n = (b - a).cross(d - a);
      std::vector<int> corners(local.begin(), local.begin() + (type == ElementType::hex8 ? 4 : 3));
      EXPECT_GT(n.dot(centroid(mesh, corners) - c), 0.0) << cm::to_string(type) << " S" << f + 1;
      if (type == ElementType::hex8) {
        // Planar quad: the other corner triple gives the same normal direction.
        const Vec3 n2 = (mesh.nodes[local[0]] - mesh.nodes[local[3]])
                            .cross(mesh.nodes[local[2]] - mesh.nodes[local[3]]);
        EXPECT_NEAR((n.normalized() - n2.normalized()).norm(), 0.0, 1e-15);
      }
      if (type == ElementType::tet10) {  // face mid nodes sit on edges (c0,c1), (c1,c2), (c2,c0)
        for (int k = 0; k < 3; ++k)
          EXPECT_NEAR((mesh.nodes[local[3 + k]] -
                       0.5 * (mesh.nodes[local[k]] + mesh.nodes[local[(k + 1) % 3]])).norm(),
                      0.0, 1e-15);
      }
    }
  }
  const cm::Mesh cube = single(ElementType::hex8);
  const Vec3 expected[6] = {-Vec3::UnitZ(), Vec3::UnitZ(), -Vec3::UnitY(),
                            Vec3::UnitX(), Vec3::UnitY(), -Vec3::UnitX()};
  for (int f = 0; f < 6; ++f) {
    const auto l = cm::face_nodes(ElementType::hex8, f);
    const Vec3 n = (cube.nodes[l[1]] - cube.nodes[l[0]]).cross(cube.nodes[l[3]] - cube.nodes[l[0]]);
    EXPECT_NEAR((n - expected[f]).norm(), 0.0, 1e-15) << "S" << f + 1;
  }
}

// Volumes: unit cube = 1 and unit tet = 1/6 exactly; an affine map scales by det(A); a trilinear
// hex with corner 7 moved by d along x has volume 1 + d/4 (integral of y z over the unit cube);
// a tet10 whose mid node slides along its straight edge keeps the volume 1/6 (tolerance 1e-14).
TEST(MeshCore, ElementVolumesAgainstAnalytic) {
  EXPECT_NEAR(cm::element_volume(single(ElementType::hex8), 0), 1.0, 1e-14);
  EXPECT_NEAR(cm::element_volume(single(ElementType::tet4), 0), 1.0 / 6.0, 1e-15);
  EXPECT_NEAR(cm::element_volume(single(ElementType::tet10), 0), 1.0 / 6.0, 1e-15);

  Eigen::Matrix3d A;
  A << 2.0, 0.3, 0.1, -0.2, 1.5, 0.4, 0.0, 0.2, 0.7;
  for (ElementType type : {ElementType::hex8, ElementType::tet10}) {
    cm::Mesh mesh = single(type);
    const double v0 = cm::element_volume(mesh, 0);
    for (Vec3& x : mesh.nodes) x = A * x + Vec3(5, -3, 1);
    EXPECT_NEAR(cm::element_volume(mesh, 0), A.determinant() * v0, 1e-13);
  }
  cm::Mesh hex = single(ElementType::hex8);
  const double d = 0.3;
  hex.nodes[6].x() += d;
  EXPECT_NEAR(cm::element_volume(hex, 0), 1.0 + d / 4.0, 1e-14);

  cm::Mesh tet = single(ElementType::tet10);
  tet.nodes[4] = Vec3(0.3, 0, 0);  // node 5 on edge 1-2, off-centre: curved map, same region
  EXPECT_NEAR(cm::element_volume(tet, 0), 1.0 / 6.0, 1e-14);
}

TEST(MeshCore, CheckElementsNamesTheBadElement) {
  cm::Mesh mesh = single(ElementType::hex8);
  EXPECT_NO_THROW(cm::check_elements(mesh, "cube"));
  auto& n = mesh.elements[0].nodes;
  std::swap_ranges(n.begin(), n.begin() + 4, n.begin() + 4);  // top and bottom swapped: inverted
  try {
    cm::check_elements(mesh, "cube");
    FAIL() << "inverted hex accepted";
  } catch (const cushion::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cube: element 7 (C3D8)"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("Jacobian"), std::string::npos) << e.what();
  }
  cm::Mesh tet = single(ElementType::tet4);
  tet.nodes[3] = Vec3(0.5, 0.5, 0.0);  // flat tet
  EXPECT_THROW(cm::check_elements(tet), cushion::InputError);
  EXPECT_LT(cm::min_corner_jacobian(mesh, 0), 0.0);
}

// 2 x 3 x 4 hex block: exterior faces = 2 (2*3 + 3*4 + 2*4) = 52; every interior face is shared.
TEST(MeshCore, BoundaryFacesOfABlock) {
  cm::BlockSpec spec;
  spec.n = {2, 3, 4};
  EXPECT_EQ(cm::boundary_faces(cm::structured_block(spec)).size(), 52u);
  spec.type = ElementType::tet4;  // each boundary quad split in 2 triangles
  EXPECT_EQ(cm::boundary_faces(cm::structured_block(spec)).size(), 104u);
}
