// Requirement: the 20-node serendipity brick (C3D20 / C3D20R) has correct shape functions in the
// ABAQUS/CalculiX node order, faces, volumes, .inp input/output and a hex8 -> hex20 converter.
// Checks: partition of unity (1e-14) and zero gradient sum (1e-14) at random points; Kronecker delta
// at the 20 nodes (1e-15); gradients = central differences of the values (1e-9); exact interpolation
// of the serendipity polynomials (1, x, y, z, x^2, ..., xyz, x^2 y, ..., x^2 y z, ...; 1e-14); mid-edge
// nodes at the middle of the ABAQUS edges 1-2, 2-3, 3-4, 4-1, 5-6, 6-7, 7-8, 8-5, 1-5, 2-6, 3-7, 4-8;
// face tables = the CalculiX C3D20 face table (ifaceq) as node sets, outward normals, mid nodes on
// their face edges; volumes (affine map 1e-13; curved edge: exact parabola area); .inp C3D20 and
// C3D20R with comma and 16-entry continuation lines, wrong node count rejected, writer round trip.
#include <gtest/gtest.h>

#include <random>
#include <set>
#include <sstream>

#include "io/input_error.hpp"
#include "mesh/inp_reader.hpp"
#include "mesh/mesh.hpp"
#include "mesh/quadratic.hpp"
#include "mesh/shape.hpp"
#include "mesh/structured_hex.hpp"

namespace cm = cushion::mesh;
using cm::ElementType;
using cm::Vec3;

namespace {

constexpr ElementType kHex20Types[] = {ElementType::hex20, ElementType::hex20r};

// A single straight-sided hex20 on [0,1]^3 (node a at (xi_a + 1) / 2).
cm::Mesh unit_hex20(ElementType type = ElementType::hex20) {
  cm::Mesh mesh;
  cm::Element element{type, {}, 1};
  const auto xi = cm::node_coordinates(type);
  for (int a = 0; a < 20; ++a) {
    mesh.nodes.push_back(0.5 * (xi[a] + Vec3::Ones()));
    mesh.node_labels.push_back(a + 1);
    element.nodes[a] = a;
  }
  mesh.elements.push_back(element);
  return mesh;
}

std::vector<Vec3> random_points(int count) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec3> points;
  for (int i = 0; i < count; ++i) points.emplace_back(u(rng), u(rng), u(rng));
  return points;
}

}  // namespace

TEST(Hex20Mesh, CountsNamesAndNodeOrder) {
  for (ElementType type : kHex20Types) {
    EXPECT_EQ(cm::nodes_per_element(type), 20);
    EXPECT_EQ(cm::faces_per_element(type), 6);
    EXPECT_EQ(cm::corners_per_face(type), 4);
    EXPECT_EQ(cm::corners_per_element(type), 8);
    EXPECT_TRUE(cm::is_hexahedron(type));
  }
  EXPECT_EQ(cm::to_string(ElementType::hex20), "C3D20");
  EXPECT_EQ(cm::to_string(ElementType::hex20r), "C3D20R");
  // ABAQUS/CalculiX (1-based): node 9 on 1-2, 10 on 2-3, 11 on 3-4, 12 on 4-1, 13 on 5-6, 14 on 6-7,
  // 15 on 7-8, 16 on 8-5, 17 on 1-5, 18 on 2-6, 19 on 3-7, 20 on 4-8.
  const int abaqus[12][2] = {{1, 2}, {2, 3}, {3, 4}, {4, 1}, {5, 6}, {6, 7},
                             {7, 8}, {8, 5}, {1, 5}, {2, 6}, {3, 7}, {4, 8}};
  const auto xi = cm::node_coordinates(ElementType::hex20);
  ASSERT_EQ(xi.size(), 20u);
  for (int m = 0; m < 12; ++m)
    EXPECT_EQ(xi[8 + m], 0.5 * (xi[abaqus[m][0] - 1] + xi[abaqus[m][1] - 1])) << "node " << 9 + m;
  // Corners as C3D8: 1-4 at zeta = -1 counter-clockwise from +zeta, 5-8 above them.
  EXPECT_EQ(xi[0], Vec3(-1, -1, -1));
  EXPECT_EQ(xi[2], Vec3(1, 1, -1));
  EXPECT_EQ(xi[6], Vec3(1, 1, 1));
}

TEST(Hex20Mesh, PartitionOfUnityAndKroneckerDelta) {
  for (ElementType type : kHex20Types) {
    for (const Vec3& p : random_points(50)) {
      EXPECT_NEAR(cm::shape_values(type, p).sum(), 1.0, 1e-14);
      EXPECT_LE(cm::shape_gradients(type, p).colwise().sum().cwiseAbs().maxCoeff(), 1e-14);
    }
    const auto xi = cm::node_coordinates(type);
    for (int b = 0; b < 20; ++b) {
      const Eigen::VectorXd N = cm::shape_values(type, xi[b]);
      for (int a = 0; a < 20; ++a) EXPECT_NEAR(N(a), a == b ? 1.0 : 0.0, 1e-15) << a << " at node " << b;
    }
  }
}

TEST(Hex20Mesh, GradientsMatchFiniteDifferences) {
  const double h = 1e-6;
  for (const Vec3& p : random_points(20)) {
    const Eigen::MatrixXd dN = cm::shape_gradients(ElementType::hex20, p);
    for (int i = 0; i < 3; ++i) {
      const Vec3 step = h * Vec3::Unit(i);
      const Eigen::VectorXd fd =
          (cm::shape_values(ElementType::hex20, p + step) - cm::shape_values(ElementType::hex20, p - step)) / (2 * h);
      EXPECT_LE((dN.col(i) - fd).cwiseAbs().maxCoeff(), 1e-9);
    }
  }
}

// The 20-node serendipity space: the complete quadratic (10 monomials), x^2 y type cubics (6), xyz, and
// x^2 yz type quartics (3).
TEST(Hex20Mesh, InterpolatesTheSerendipityPolynomialsExactly) {
  const int powers[20][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {2, 0, 0}, {0, 2, 0}, {0, 0, 2},
                             {1, 1, 0}, {0, 1, 1}, {1, 0, 1}, {1, 1, 1}, {2, 1, 0}, {2, 0, 1}, {1, 2, 0},
                             {0, 2, 1}, {1, 0, 2}, {0, 1, 2}, {2, 1, 1}, {1, 2, 1}, {1, 1, 2}};
  const auto xi = cm::node_coordinates(ElementType::hex20);
  auto monomial = [](const int* k, const Vec3& x) { return std::pow(x(0), k[0]) * std::pow(x(1), k[1]) * std::pow(x(2), k[2]); };
  for (const auto& k : powers)
    for (const Vec3& p : random_points(10)) {
      const Eigen::VectorXd N = cm::shape_values(ElementType::hex20, p);
      double interpolated = 0.0;
      for (int a = 0; a < 20; ++a) interpolated += N(a) * monomial(k, xi[a]);
      EXPECT_NEAR(interpolated, monomial(k, p), 1e-14) << k[0] << k[1] << k[2];
    }
}

// Face node sets = CalculiX's C3D20 face table ifaceq (1-based): S1 4,3,2,1,11,10,9,12;
// S2 5,6,7,8,13,14,15,16; S3 1,2,6,5,9,18,13,17; S4 2,3,7,6,10,19,14,18; S5 3,4,8,7,11,20,15,19;
// S6 4,1,5,8,12,17,16,20. Corners as C3D8; mid node k + 4 at the middle of corners k, k + 1.
TEST(Hex20Mesh, FacesMatchCalculixTableWithOutwardNormals) {
  const std::vector<std::set<int>> ccx = {{4, 3, 2, 1, 11, 10, 9, 12},   {5, 6, 7, 8, 13, 14, 15, 16},
                                          {1, 2, 6, 5, 9, 18, 13, 17},   {2, 3, 7, 6, 10, 19, 14, 18},
                                          {3, 4, 8, 7, 11, 20, 15, 19},  {4, 1, 5, 8, 12, 17, 16, 20}};
  const cm::Mesh mesh = unit_hex20();
  const Vec3 centre(0.5, 0.5, 0.5);
  for (int f = 0; f < 6; ++f) {
    const auto local = cm::face_nodes(ElementType::hex20, f);
    ASSERT_EQ(local.size(), 8u);
    std::set<int> got;
    for (int a : local) got.insert(a + 1);
    EXPECT_EQ(got, ccx[f]) << "S" << f + 1;
    const auto hex8 = cm::face_nodes(ElementType::hex8, f);
    EXPECT_EQ(std::vector<int>(local.begin(), local.begin() + 4), hex8) << "S" << f + 1;
    auto X = [&](int k) { return mesh.nodes[local[k]]; };
    for (int k = 0; k < 4; ++k) EXPECT_EQ(X(4 + k), 0.5 * (X(k) + X((k + 1) % 4))) << "S" << f + 1;
    const Vec3 n = (X(1) - X(0)).cross(X(3) - X(0));
    EXPECT_GT(n.dot(X(0) + X(2) - 2 * centre), 0.0) << "S" << f + 1;
    EXPECT_NEAR(cm::face_area(mesh, {0, f}), 1.0, 1e-15);
  }
}

TEST(Hex20Mesh, VolumesAndJacobianCheck) {
  Eigen::Matrix3d A;
  A << 2.0, 0.3, 0.1, -0.2, 1.5, 0.4, 0.0, 0.2, 0.7;
  for (ElementType type : kHex20Types) {
    cm::Mesh mesh = unit_hex20(type);
    EXPECT_NEAR(cm::element_volume(mesh, 0), 1.0, 1e-14);
    for (Vec3& x : mesh.nodes) x = A * x + Vec3(5, -3, 1);
    EXPECT_NEAR(cm::element_volume(mesh, 0), A.determinant(), 1e-13);
    EXPECT_NO_THROW(cm::check_elements(mesh, "affine"));
  }
  // Mid node 9 (edge 1-2, y = z = 0) moved by v = -d e_y: X = X0 + N_9 v, so (determinant lemma and
  // divergence theorem) V = 1 + v . int N_9 n dA = 1 + d int_{y=0} N_9 dA, with N_9 = (1 - xi^2)(1 - zeta)/2
  // on that face: V = 1 + d/3 exactly.
  cm::Mesh bulged = unit_hex20();
  const double d = 0.2;
  bulged.nodes[8].y() -= d;
  EXPECT_NEAR(cm::element_volume(bulged, 0), 1.0 + d / 3.0, 1e-14);
  // Inverted (top and bottom swapped) is named by check_elements.
  cm::Mesh inverted = unit_hex20();
  for (Vec3& x : inverted.nodes) x.z() = 1.0 - x.z();
  try {
    cm::check_elements(inverted, "deck");
    FAIL() << "inverted hex20 accepted";
  } catch (const cushion::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("deck: element 1 (C3D20)"), std::string::npos) << e.what();
  }
}

// 2 x 2 x 2 block: 27 corner nodes + 3 * 2 * 3^2 = 54 mid-edge nodes, shared between neighbours;
// 24 exterior faces, each with 8 nodes on the boundary; node sets gain the mid nodes of their edges.
TEST(Hex20Mesh, ConverterSharesMidEdgeNodes) {
  cm::BlockSpec spec;
  spec.n = {2, 2, 2};
  spec.high = Vec3(2, 2, 2);
  cm::Mesh block = cm::structured_block(spec);
  block.node_sets["bottom"] = {};
  for (int a = 0; a < static_cast<int>(block.num_nodes()); ++a)
    if (block.nodes[a].z() == 0.0) block.node_sets["bottom"].push_back(a);
  const cm::Mesh quad = cm::to_hex20(block, ElementType::hex20r);
  EXPECT_EQ(quad.num_nodes(), 81u);
  EXPECT_EQ(quad.node_sets.at("bottom").size(), 21u);  // 9 corners + 12 mid-edge nodes
  for (const auto& element : quad.elements) EXPECT_EQ(element.type, ElementType::hex20r);
  double volume = 0.0;
  for (int e = 0; e < 8; ++e) volume += cm::element_volume(quad, e);
  EXPECT_NEAR(volume, 8.0, 1e-13);
  const auto faces = cm::boundary_faces(quad);
  EXPECT_EQ(faces.size(), 24u);
  double area = 0.0;
  for (const auto& f : faces) area += cm::face_area(quad, f);
  EXPECT_NEAR(area, 24.0, 1e-13);
  EXPECT_THROW(cm::to_hex20(quad), std::invalid_argument);          // already quadratic
  EXPECT_THROW(cm::to_hex20(block, ElementType::tet10), std::invalid_argument);
}

namespace {

// One C3D20 and one C3D20R element sharing the face x = 1 of the unit cubes [0,1] and [1,2] in x.
std::string two_element_deck() {
  cm::BlockSpec spec;
  spec.n = {2, 1, 1};
  spec.high = Vec3(2, 1, 1);
  cm::Mesh mesh = cm::to_hex20(cm::structured_block(spec));
  std::ostringstream deck;
  deck.precision(17);
  deck << "*NODE\n";
  for (std::size_t i = 0; i < mesh.num_nodes(); ++i)
    deck << i + 1 << ", " << mesh.nodes[i].x() << ", " << mesh.nodes[i].y() << ", " << mesh.nodes[i].z() << "\n";
  // Element 1: C3D20 with a trailing comma after 15 nodes; element 2: C3D20R, 16 entries, no comma.
  const char* types[2] = {"C3D20", "c3d20r"};
  for (int e = 0; e < 2; ++e) {
    deck << "*ELEMENT, TYPE=" << types[e] << ", ELSET=E" << e + 1 << "\n" << e + 1;
    for (int a = 0; a < 20; ++a) deck << (a == 15 ? (e == 0 ? ",\n" : "\n") : ", ") << mesh.elements[e].nodes[a] + 1;
    deck << "\n";
  }
  deck << "*SURFACE, NAME=RIGHT\nE2, S4\n";
  return deck.str();
}

}  // namespace

TEST(Hex20Mesh, InpReaderAndWriter) {
  const cm::Mesh mesh = cm::parse_inp(two_element_deck(), "two.inp");
  ASSERT_EQ(mesh.num_elements(), 2u);
  EXPECT_EQ(mesh.elements[0].type, ElementType::hex20);
  EXPECT_EQ(mesh.elements[1].type, ElementType::hex20r);
  EXPECT_EQ(mesh.num_nodes(), 32u);  // 12 corners + 20 mid-edge nodes
  EXPECT_NEAR(cm::element_volume(mesh, 0) + cm::element_volume(mesh, 1), 2.0, 1e-14);
  EXPECT_EQ(mesh.surfaces.at("RIGHT")[0].face, 3);
  EXPECT_EQ(cm::boundary_faces(mesh).size(), 10u);  // the shared 8-node face is interior

  std::ostringstream written;
  cm::write_inp(mesh, written);
  EXPECT_NE(written.str().find("*ELEMENT, TYPE=C3D20R\n"), std::string::npos);
  const cm::Mesh again = cm::parse_inp(written.str(), "written.inp");
  ASSERT_EQ(again.num_elements(), 2u);
  for (int e = 0; e < 2; ++e) {
    EXPECT_EQ(again.elements[e].type, mesh.elements[e].type);
    EXPECT_EQ(again.elements[e].nodes, mesh.elements[e].nodes);
  }
  EXPECT_EQ(again.nodes, mesh.nodes);
}

TEST(Hex20Mesh, InpRejectsAShortElement) {
  std::string deck = two_element_deck();
  const auto at = deck.find("*SURFACE");
  deck.insert(at, "*ELEMENT, TYPE=C3D20\n3, 1, 2, 3, 4, 5, 6, 7, 8\n");
  try {
    cm::parse_inp(deck, "short.inp");
    FAIL() << "8-node C3D20 accepted";
  } catch (const cushion::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("C3D20 needs a label and 20 nodes, got 9 fields"), std::string::npos)
        << e.what();
  }
}
