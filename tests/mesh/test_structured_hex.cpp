// Structured block generator: counts, volumes, grading, named sets and surfaces.
#include <gtest/gtest.h>

#include <cmath>

#include "io/input_error.hpp"
#include "mesh/structured_hex.hpp"

namespace cm = cushion::mesh;
using cm::AxisGrading;
using cm::ElementType;
using cm::Vec3;

namespace {

double total_volume(const cm::Mesh& mesh) {
  double v = 0.0;
  for (int e = 0; e < static_cast<int>(mesh.num_elements()); ++e) {
    const double ve = cm::element_volume(mesh, e);
    EXPECT_GT(ve, 0.0) << "element " << e;
    v += ve;
  }
  return v;
}

cm::BlockSpec seat_block() {
  cm::BlockSpec spec;
  spec.low = Vec3(-50, -40, 0);
  spec.high = Vec3(50, 40, 60);
  spec.n = {6, 5, 4};
  return spec;
}

}  // namespace

// Sum of element volumes equals the box volume 100 x 80 x 60 mm^3 to 1e-10 relative, for uniform,
// geometric and focus grading, hex8 and the 6-tet split.
TEST(StructuredBlock, CountsAndVolume) {
  const double box = 100.0 * 80.0 * 60.0;
  for (ElementType type : {ElementType::hex8, ElementType::tet4}) {
    cm::BlockSpec spec = seat_block();
    spec.type = type;
    for (int variant = 0; variant < 3; ++variant) {
      if (variant == 1) spec.grading[2] = AxisGrading{AxisGrading::Kind::geometric, 0.2, 0.0};
      if (variant == 2) {
        spec.grading[0] = AxisGrading{AxisGrading::Kind::focus, 5.0, 0.0};
        spec.grading[1] = AxisGrading{AxisGrading::Kind::focus, 3.0, -40.0};
      }
      const cm::Mesh mesh = cm::structured_block(spec);
      EXPECT_EQ(mesh.num_nodes(), 7u * 6u * 5u);
      EXPECT_EQ(mesh.num_elements(), (type == ElementType::hex8 ? 1u : 6u) * 6u * 5u * 4u);
      EXPECT_NEAR(total_volume(mesh), box, 1e-10 * box) << "variant " << variant;
      EXPECT_NO_THROW(cm::check_elements(mesh));
      EXPECT_EQ(mesh.node_labels.front(), 1);
      EXPECT_EQ(mesh.elements.back().label, static_cast<int>(mesh.num_elements()));
      EXPECT_EQ(mesh.element_sets.at("all").size(), mesh.num_elements());
    }
  }
}

// Geometric grading: consecutive size ratio constant q = r^(1/(n-1)) and h_last / h_first = r
// (tolerance 1e-12 relative).
TEST(StructuredBlock, GeometricGradingRatios) {
  const double r = 4.0;
  const int n = 5;
  const auto x = cm::graded_coordinates(0.0, 10.0, n, {AxisGrading::Kind::geometric, r, 0.0});
  ASSERT_EQ(x.size(), 6u);
  EXPECT_DOUBLE_EQ(x.front(), 0.0);
  EXPECT_DOUBLE_EQ(x.back(), 10.0);
  const double q = std::pow(r, 1.0 / (n - 1));
  for (int i = 1; i < n; ++i) EXPECT_NEAR((x[i + 1] - x[i]) / (x[i] - x[i - 1]), q, 1e-12 * q);
  EXPECT_NEAR((x[5] - x[4]) / (x[1] - x[0]), r, 1e-12 * r);
  // h0 (1 + q + q^2 + q^3 + q^4) = 10
  EXPECT_NEAR(x[1], 10.0 * (q - 1) / (std::pow(q, n) - 1), 1e-12);
}

// Focus grading: the finest elements touch the focus plane, sizes grow monotonically away from it,
// coarsest / finest = ratio on each side; focus at an end (symmetry plane of a quarter model).
TEST(StructuredBlock, FocusGradingRefinesAtPlane) {
  const auto x = cm::graded_coordinates(-50.0, 50.0, 10, {AxisGrading::Kind::focus, 6.0, 0.0});
  ASSERT_EQ(x.size(), 11u);
  EXPECT_NEAR(x[5], 0.0, 1e-12);  // 5 elements each side for a centred focus
  for (int i = 0; i < 4; ++i) {
    EXPECT_GT(x[i + 1] - x[i], x[i + 2] - x[i + 1]);              // shrinking towards 0
    EXPECT_LT(x[6 + i] - x[5 + i], x[7 + i] - x[6 + i]);          // growing away from 0
  }
  EXPECT_NEAR((x[1] - x[0]) / (x[5] - x[4]), 6.0, 1e-12 * 6.0);
  EXPECT_NEAR((x[10] - x[9]) / (x[6] - x[5]), 6.0, 1e-12 * 6.0);

  const auto y = cm::graded_coordinates(0.0, 40.0, 8, {AxisGrading::Kind::focus, 5.0, 0.0});
  EXPECT_NEAR((y[8] - y[7]) / (y[1] - y[0]), 5.0, 1e-12 * 5.0);
  const auto z = cm::graded_coordinates(0.0, 40.0, 8, {AxisGrading::Kind::focus, 5.0, 40.0});
  EXPECT_NEAR((z[1] - z[0]) / (z[8] - z[7]), 5.0, 1e-12 * 5.0);

  EXPECT_THROW(cm::graded_coordinates(0, 1, 4, {AxisGrading::Kind::focus, 2.0, 3.0}),
               cushion::InputError);
  EXPECT_THROW(cm::graded_coordinates(0, 1, 4, {AxisGrading::Kind::geometric, -1.0, 0.0}),
               cushion::InputError);
  cm::BlockSpec bad;
  bad.n = {2, 0, 2};
  EXPECT_THROW(cm::structured_block(bad), cushion::InputError);
}

// Named sets: each side holds (n_a + 1)(n_b + 1) nodes, all on the plane; its surface has n_a n_b
// quads (2 n_a n_b triangles), each with its outward normal along the side's axis.
TEST(StructuredBlock, SideSetsAndSurfaces) {
  for (ElementType type : {ElementType::hex8, ElementType::tet4}) {
    cm::BlockSpec spec = seat_block();
    spec.type = type;
    spec.grading[2] = AxisGrading{AxisGrading::Kind::geometric, 3.0, 0.0};
    const cm::Mesh mesh = cm::structured_block(spec);
    const char* names[3][2] = {{"xmin", "xmax"}, {"ymin", "ymax"}, {"zmin", "zmax"}};
    for (int d = 0; d < 3; ++d)
      for (int side = 0; side < 2; ++side) {
        const int a = (d + 1) % 3, b = (d + 2) % 3;
        const auto& nodes = mesh.node_sets.at(names[d][side]);
        EXPECT_EQ(nodes.size(), static_cast<std::size_t>((spec.n[a] + 1) * (spec.n[b] + 1)));
        const double plane = side == 0 ? spec.low[d] : spec.high[d];
        for (int n : nodes) EXPECT_EQ(mesh.nodes[n][d], plane);
        const auto& faces = mesh.surfaces.at(names[d][side]);
        EXPECT_EQ(faces.size(),
                  static_cast<std::size_t>((type == ElementType::hex8 ? 1 : 2) * spec.n[a] * spec.n[b]));
        double area = 0.0;
        for (const cm::Face& face : faces) {
          const cm::Element& el = mesh.elements[face.element];
          const auto l = cm::face_nodes(el.type, face.face);
          const Vec3& p0 = mesh.nodes[el.nodes[l[0]]];
          Vec3 n = (mesh.nodes[el.nodes[l[1]]] - p0).cross(mesh.nodes[el.nodes[l[2]]] - p0);
          if (type == ElementType::hex8) n *= 2.0;  // rectangle: twice the triangle
          EXPECT_GT(n[d] * (side == 0 ? -1.0 : 1.0), 0.0);
          area += 0.5 * n.norm();
        }
        const double expected = (spec.high[a] - spec.low[a]) * (spec.high[b] - spec.low[b]);
        EXPECT_NEAR(area, expected, 1e-10 * expected);
      }
  }
}
