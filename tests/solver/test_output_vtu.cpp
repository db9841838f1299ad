// Result output: frames written as .vtu + .pvd and read back with VTK's own XML reader and parser;
// field names, values and times agree to 1e-12; cell node orders agree with VTK's cell definitions.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>

#include "solver/output/cell_measures.hpp"
#include "solver/output/vtu_reader.hpp"
#include "solver/output/vtu_writer.hpp"

namespace fs = std::filesystem;
using namespace cushion;
using namespace cushion::solver;

namespace {

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("cushion_h6_out_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  return dir;
}

/// Two unit hexahedra side by side along x (C3D8 order: bottom face 0-3 counter-clockwise, top 4-7).
mesh::Mesh two_hexes() {
  mesh::Mesh m;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 3; ++i) m.nodes.emplace_back(i, j, k);
  auto id = [](int i, int j, int k) { return i + 3 * j + 6 * k; };
  for (int e = 0; e < 2; ++e) {
    mesh::Element el;
    el.type = mesh::ElementType::hex8;
    const int c[8] = {id(e, 0, 0), id(e + 1, 0, 0), id(e + 1, 1, 0), id(e, 1, 0),
                      id(e, 0, 1), id(e + 1, 0, 1), id(e + 1, 1, 1), id(e, 1, 1)};
    std::copy(c, c + 8, el.nodes.begin());
    el.label = e + 1;
    m.elements.push_back(el);
  }
  m.node_labels.resize(m.nodes.size());
  return m;
}

/// One straight-sided C3D10: corners 0-3, mid-edge nodes 1-2, 2-3, 3-1, 1-4, 2-4, 3-4 (1-based).
mesh::Mesh one_tet10() {
  mesh::Mesh m;
  m.nodes = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 3, 0), Vec3(0, 0, 5)};
  const int edges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  for (const auto& e : edges) m.nodes.push_back(0.5 * (m.nodes[e[0]] + m.nodes[e[1]]));
  mesh::Element el;
  el.type = mesh::ElementType::tet10;
  for (int a = 0; a < 10; ++a) el.nodes[a] = a;
  m.elements.push_back(el);
  m.node_labels.resize(m.nodes.size());
  return m;
}

FrameData frame_for(const mesh::Mesh& m, double t) {
  FrameData f;
  f.time = t;
  for (const Vec3& x : m.nodes) {
    f.displacement.push_back(Vec3(0.1 * t * x.x() + 1.0 / 3.0, -0.2 * x.y() * x.z(), std::sin(x.x() + t)));
    f.reaction_force.push_back(Vec3(x.z() == 1 ? -7.25 * t : 0.0, 0.0, 1e-7 * x.x()));
  }
  for (std::size_t e = 0; e < m.num_elements(); ++e) {
    Mat3 s;
    s << 1.0 + t, 0.2, 0.3, 0.2, -2.0 * e, 0.4, 0.3, 0.4, 0.5 / 3.0;  // MPa
    f.cauchy_stress.push_back(s);
    Mat3 F = Mat3::Identity();
    F(2, 2) = 1.0 - 0.25 * t;
    F(0, 1) = 0.1 * e;
    f.deformation_gradient.push_back(F);
    f.viscous_stress_norm.push_back(0.001 * (e + 1) * t);
  }
  NamedField gap{"gap_mm", 1, {}};
  for (std::size_t n = 0; n < m.num_nodes(); ++n) gap.values.push_back(0.5 * n - t);
  f.point_fields.push_back(gap);
  f.cell_fields.push_back({"contact_status", 2, std::vector<double>(2 * m.num_elements(), t)});
  return f;
}

void expect_near_all(const std::vector<double>& a, const std::vector<double>& b, double tol, const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], b[i], tol * (1.0 + std::abs(b[i]))) << what << "[" << i << "]";
}

}  // namespace

TEST(VtuOutput, FramesRoundTripThroughVtkReaders) {
  const mesh::Mesh m = two_hexes();
  const fs::path dir = scratch("roundtrip");
  ResultSeries series(dir, "cube");
  const std::vector<double> times = {0.0, 0.5, 1.0 / 3.0 + 1.0};
  for (double t : times) series.write_frame(m, frame_for(m, t));

  // The .pvd lists every frame with its exact time, and no temporary file is left behind.
  const auto entries = read_pvd(series.pvd_file());
  ASSERT_EQ(entries.size(), times.size());
  for (const auto& entry : fs::directory_iterator(dir)) EXPECT_NE(entry.path().extension(), ".tmp") << entry.path();

  for (std::size_t k = 0; k < times.size(); ++k) {
    EXPECT_EQ(entries[k].time, times[k]);  // shortest round-trip decimal: exact
    const VtuContents v = read_vtu(dir / entries[k].file);
    const FrameData f = frame_for(m, times[k]);
    ASSERT_TRUE(v.time.has_value());
    EXPECT_EQ(*v.time, times[k]);
    ASSERT_EQ(v.points.size(), m.num_nodes());
    for (std::size_t n = 0; n < m.num_nodes(); ++n) EXPECT_EQ(v.points[n], m.nodes[n]);
    ASSERT_EQ(v.cells.size(), 2u);
    EXPECT_EQ(v.cell_types[0], 12);  // VTK_HEXAHEDRON
    for (int a = 0; a < 8; ++a) EXPECT_EQ(v.cells[1][a], m.elements[1].nodes[a]);

    std::vector<double> u, rf, sigma, strain, stretches, J, mises, p, visc;
    for (std::size_t n = 0; n < m.num_nodes(); ++n)
      for (int c = 0; c < 3; ++c) {
        u.push_back(f.displacement[n](c));
        rf.push_back(f.reaction_force[n](c));
      }
    for (std::size_t e = 0; e < 2; ++e) {
      const Mat3& s = f.cauchy_stress[e];
      const Mat3& F = f.deformation_gradient[e];
      // Independent expectations: components XX YY ZZ XY YZ XZ in kPa; stretches of F = I + shear
      // + axial from B = F F^T by hand for the diagonal case.
      const double kpa = 1000.0;
      for (double x : {s(0, 0), s(1, 1), s(2, 2), s(0, 1), s(1, 2), s(0, 2)}) sigma.push_back(kpa * x);
      const Mat3 E = log_strain(F);
      for (double x : {E(0, 0), E(1, 1), E(2, 2), E(0, 1), E(1, 2), E(0, 2)}) strain.push_back(x);
      const Vec3 l = principal_stretches(F);
      for (int c = 0; c < 3; ++c) stretches.push_back(l(c));
      J.push_back(F(2, 2));  // det of [[1, g, 0], [0, 1, 0], [0, 0, a]] = a
      const Mat3 dev = s - s.trace() / 3.0 * Mat3::Identity();
      mises.push_back(kpa * std::sqrt(1.5 * (dev * dev.transpose()).trace()));
      p.push_back(-kpa * s.trace() / 3.0);
      visc.push_back(kpa * f.viscous_stress_norm[e]);
    }
    expect_near_all(v.point_data.at("displacement_mm").values, u, 1e-12, "displacement_mm");
    expect_near_all(v.point_data.at("reaction_force_N").values, rf, 1e-12, "reaction_force_N");
    expect_near_all(v.point_data.at("gap_mm").values, f.point_fields[0].values, 1e-12, "gap_mm");
    expect_near_all(v.cell_data.at("cauchy_stress_kPa").values, sigma, 1e-12, "cauchy_stress_kPa");
    EXPECT_EQ(v.cell_data.at("cauchy_stress_kPa").components, 6);
    expect_near_all(v.cell_data.at("log_strain").values, strain, 1e-12, "log_strain");
    expect_near_all(v.cell_data.at("principal_stretches").values, stretches, 1e-12, "principal_stretches");
    expect_near_all(v.cell_data.at("J").values, J, 1e-12, "J");
    expect_near_all(v.cell_data.at("von_mises_kPa").values, mises, 1e-12, "von_mises_kPa");
    expect_near_all(v.cell_data.at("pressure_kPa").values, p, 1e-12, "pressure_kPa");
    expect_near_all(v.cell_data.at("viscous_stress_norm_kPa").values, visc, 1e-12, "viscous_stress_norm_kPa");
    EXPECT_EQ(v.cell_data.at("contact_status").components, 2);
    expect_near_all(v.cell_data.at("contact_status").values, f.cell_fields[0].values, 1e-12, "contact_status");
  }

  // A new series in the same folder starts clean (no stale frames from the earlier run).
  ResultSeries again(dir, "cube");
  again.write_frame(m, frame_for(m, 2.0));
  EXPECT_EQ(read_pvd(again.pvd_file()).size(), 1u);
  EXPECT_FALSE(fs::exists(dir / "cube_0002.vtu"));
  fs::remove_all(dir);
}

TEST(VtuOutput, CellNodeOrdersAgreeWithVtk) {
  // tet10: every VTK quadratic edge (end, end, mid) has its mid node at the midpoint of its ends,
  // which holds only if C3D10 and VTK_QUADRATIC_TETRA number the mid-edge nodes alike.
  const fs::path dir = scratch("order");
  const mesh::Mesh tet = one_tet10();
  FrameData f;
  f.displacement.assign(tet.num_nodes(), Vec3::Zero());
  write_vtu(dir / "tet10.vtu", tet, f);
  const VtuContents v = read_vtu(dir / "tet10.vtu");
  ASSERT_EQ(v.cell_types[0], 24);  // VTK_QUADRATIC_TETRA
  ASSERT_EQ(v.vtk_edges[0].size(), 6u);
  for (const auto& e : v.vtk_edges[0]) {
    ASSERT_EQ(e.size(), 3u);
    EXPECT_LT((v.points[e[2]] - 0.5 * (v.points[e[0]] + v.points[e[1]])).norm(), 1e-12);
  }
  for (int a = 0; a < 10; ++a) EXPECT_LT((v.points[v.cells[0][a]] - tet.nodes[a]).norm(), 1e-12);

  // hex8 on unit cubes: each of VTK's 12 edges joins nodes one unit apart along one axis.
  const mesh::Mesh hex = two_hexes();
  f.displacement.assign(hex.num_nodes(), Vec3::Zero());
  write_vtu(dir / "hex8.vtu", hex, f);
  const VtuContents h = read_vtu(dir / "hex8.vtu");
  for (const auto& cell : h.vtk_edges) {
    ASSERT_EQ(cell.size(), 12u);
    for (const auto& e : cell) EXPECT_NEAR((h.points[e[0]] - h.points[e[1]]).norm(), 1.0, 1e-12);
  }

  // tet4: the VTK tetra of the corner nodes has 6 edges that are the 6 corner pairs.
  mesh::Mesh tet4 = tet;
  tet4.nodes.resize(4);
  tet4.elements[0].type = mesh::ElementType::tet4;
  f.displacement.assign(4, Vec3::Zero());
  write_vtu(dir / "tet4.vtu", tet4, f);
  const VtuContents t4 = read_vtu(dir / "tet4.vtu");
  EXPECT_EQ(t4.cell_types[0], 10);  // VTK_TETRA
  EXPECT_EQ(t4.vtk_edges[0].size(), 6u);
  fs::remove_all(dir);
}

TEST(VtuOutput, SizeMismatchIsAProgrammingError) {
  const mesh::Mesh m = two_hexes();
  FrameData f = frame_for(m, 0.0);
  f.cauchy_stress.pop_back();
  EXPECT_THROW(write_vtu(scratch("mismatch") / "x.vtu", m, f), std::invalid_argument);
}

TEST(CellMeasures, AnalyticValues) {
  // Uniaxial stress s: von Mises |s|, pressure -s/3. Hydrostatic -p I: von Mises 0, pressure p.
  Mat3 uni = Mat3::Zero();
  uni(0, 0) = -3.5;
  EXPECT_NEAR(von_mises(uni), 3.5, 1e-14);
  EXPECT_NEAR(pressure(uni), 3.5 / 3.0, 1e-14);
  EXPECT_NEAR(von_mises(-2.0 * Mat3::Identity()), 0.0, 1e-14);
  EXPECT_NEAR(pressure(-2.0 * Mat3::Identity()), 2.0, 1e-14);
  // Pure shear tau: von Mises sqrt(3) tau.
  Mat3 shear = Mat3::Zero();
  shear(0, 1) = shear(1, 0) = 2.0;
  EXPECT_NEAR(von_mises(shear), 2.0 * std::sqrt(3.0), 1e-14);

  // F = R diag(l) (rotation then stretch, left polar V = R diag(l) R^T ... here F = V R with V = R diag R^T):
  // stretches are l sorted descending, ln V = R diag(ln l) R^T, J = prod l.
  const Mat3 R = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const Vec3 l(0.25, 1.3, 0.9);
  const Mat3 V = R * l.asDiagonal() * R.transpose();
  const Mat3 Q = Eigen::AngleAxisd(-0.4, Vec3::UnitZ()).toRotationMatrix();
  const Mat3 F = V * Q;
  const Vec3 got = principal_stretches(F);
  EXPECT_NEAR(got(0), 1.3, 1e-13);
  EXPECT_NEAR(got(1), 0.9, 1e-13);
  EXPECT_NEAR(got(2), 0.25, 1e-13);
  const Mat3 expected = R * Vec3(std::log(0.25), std::log(1.3), std::log(0.9)).asDiagonal() * R.transpose();
  EXPECT_LT((log_strain(F) - expected).norm(), 1e-13);
}
