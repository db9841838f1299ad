// Requirement: an STL indenter cut by the symmetry planes of a quarter model (closed by triangles in
// x = 0 and y = 0) shall give the force of the same analytic indenter: the triangles in the symmetry
// planes are dropped with a warning (kept, foam nodes on those planes touch them with gap 0 and carry
// no load, so the force is low). Triangles in a plane where nodes are held without a symmetry
// condition are kept and warned about.
// Checks: quarter sphere R = 50 mm (2 degree facets) pressed 15 mm into a 100 x 100 x 40 mm quarter
// block (5 x 5 x 4 hex8, graded to the axis): force within 0.5 % of the analytic sphere's at every
// 5 mm (faceting: the facets lie up to 0.008 mm inside the sphere); the warnings name the number of
// triangles and the planes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <sstream>

#include "io/csv.hpp"
#include "tests/solver/test_run_support.hpp"

namespace cushion::solver {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Quarter sphere (x >= 0, y >= 0), radius r, centre (0, 0, zc), n polar x n/2 azimuthal facets,
// closed by half discs in y = 0 and x = 0; ASCII STL with outward normals.
std::string quarter_sphere_stl(double r, double zc, int n) {
  auto point = [&](int i, int j) {  // polar angle from -z: i pi / n; azimuth from +x: j (pi / 2) / (n / 2)
    const double t = kPi * i / n, p = kPi * j / n;
    return Vec3(r * std::sin(t) * std::cos(p), r * std::sin(t) * std::sin(p), zc - r * std::cos(t));
  };
  std::vector<std::array<Vec3, 3>> triangles;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n / 2; ++j) {
      if (i > 0) triangles.push_back({point(i, j), point(i + 1, j), point(i, j + 1)});
      if (i < n - 1) triangles.push_back({point(i + 1, j), point(i + 1, j + 1), point(i, j + 1)});
    }
  const Vec3 centre(0, 0, zc);
  for (int j : {0, n / 2})  // walls y = 0 and x = 0
    for (int i = 0; i < n; ++i) triangles.push_back({centre, point(i, j), point(i + 1, j)});
  std::ostringstream out;
  out.precision(15);
  out << "solid quarter\n";
  const Vec3 inside(0.4 * r, 0.4 * r, zc);
  for (auto& t : triangles) {
    Vec3 normal = (t[1] - t[0]).cross(t[2] - t[0]);
    if (normal.dot((t[0] + t[1] + t[2]) / 3 - inside) < 0) std::swap(t[1], t[2]), normal = -normal;
    out << "facet normal " << normal.x() << " " << normal.y() << " " << normal.z() << "\nouter loop\n";
    for (const Vec3& v : t) out << "vertex " << v.x() << " " << v.y() << " " << v.z() << "\n";
    out << "endloop\nendfacet\n";
  }
  return out.str() + "endsolid quarter\n";
}

// The quarter block pressed 15 mm by `indenter`; `sym_x` holds x = 0 by `sym_x_condition`.
std::string quarter_case(const std::string& indenter, const std::string& sym_x_condition) {
  return R"({"mesh": {"generate": {"type": "hex8", "box_mm": [0, 100, 0, 100, 0, 40], "elements": [5, 5, 4],
      "grading": {"x": {"ratio": 2, "focus_mm": 0}, "y": {"ratio": 2, "focus_mm": 0}}}},
    "material": {"file": "foam.json"},
    "sets": {"base": "z == 0", "top": "z == 40", "sym_x": "x == 0", "sym_y": "y == 0"},
    "steps": [{"name": "press", "type": "static", "time_period_s": 1,
      "increment": {"initial_s": 0.1, "max_s": 0.1},
      "boundary": [{"set": "base", "type": "fixed"}, {"set": "sym_x", )" +
         sym_x_condition + R"(}, {"set": "sym_y", "type": "symmetry_y"}],
      "contact": [{"name": "ball", "set": "top", "indenter": )" +
         indenter + R"(, "motion_mm": [0, 0, -15], "tolerance_mm": 0.01, "force_factor": 4}]}]})";
}

struct Indentation {
  std::vector<double> depth, force;  ///< [mm], [N] (full model), one row per increment
  std::string progress;
  double force_at(double d) const { return test::interpolate(depth, force, d); }  ///< [N] at depth d [mm]
};

Indentation run(const std::filesystem::path& dir, const std::string& name, const std::string& text) {
  const std::filesystem::path file = test::write_text(dir / (name + ".json"), text);
  std::ostringstream progress;
  RunOptions options;
  options.output_dir = dir / name;
  options.threads = 2;
  options.progress = &progress;
  run_analysis(load_case(file), options);
  const CsvTable t = read_csv(dir / name / "contact_ball.csv");
  Indentation out;
  for (double u : t.col("ball.U3_mm")) out.depth.push_back(-u);
  for (double f : t.col("ball.F3_N")) out.force.push_back(-f);
  out.progress = progress.str();
  return out;
}

TEST(ContactStlSymmetry, QuarterStlMatchesAnalyticSphereWithSymmetryTrianglesDropped) {
  const auto dir = test::scratch_dir();
  test::write_text(dir / "foam.json", test::foam_json(0.0, false));
  test::write_text(dir / "quarter.stl", quarter_sphere_stl(50, 90, 90));
  const std::string symmetry = R"("type": "symmetry_x")";
  const Indentation sphere =
      run(dir, "sphere", quarter_case(R"({"type": "sphere", "centre_mm": [0, 0, 90], "radius_mm": 50})", symmetry));
  const Indentation stl = run(dir, "stl", quarter_case(R"({"type": "stl", "file": "quarter.stl"})", symmetry));
  for (double d : {5.0, 10.0, 15.0}) {
    std::printf("depth %4.1f mm: STL %.4f N, sphere %.4f N (%+.3f %%)\n", d, stl.force_at(d), sphere.force_at(d),
                100 * (stl.force_at(d) / sphere.force_at(d) - 1));
    EXPECT_NEAR(stl.force_at(d), sphere.force_at(d), 5e-3 * sphere.force_at(d)) << "at " << d << " mm";
  }
  // 90 + 90 triangles close the quarter sphere in x = 0 and y = 0.
  EXPECT_NE(stl.progress.find("180 of 8190 triangles of " + (dir / "quarter.stl").string() +
                              " lie in the symmetry planes x = 0 mm, y = 0 mm and were dropped"),
            std::string::npos)
      << stl.progress;
}

TEST(ContactStlSymmetry, TrianglesInAHeldPlaneWithoutSymmetryAreWarned) {
  const auto dir = test::scratch_dir();
  test::write_text(dir / "foam.json", test::foam_json(0.0, false));
  test::write_text(dir / "quarter.stl", quarter_sphere_stl(50, 90, 90));
  // x = 0 held by a zero displacement instead of a symmetry condition: the plane is not known to be
  // a symmetry plane, so its triangles stay, with a warning.
  const Indentation stl = run(dir, "stl", quarter_case(R"({"type": "stl", "file": "quarter.stl"})",
                                               R"("dof": "x", "value_mm": 0)"));
  EXPECT_NE(stl.progress.find("90 of 8190 triangles of " + (dir / "quarter.stl").string() +
                              " lie in the symmetry planes y = 0 mm and were dropped"),
            std::string::npos)
      << stl.progress;
  EXPECT_NE(stl.progress.find("90 triangles of " + (dir / "quarter.stl").string() +
                              " lie in the plane x = 0 mm where nodes are held"),
            std::string::npos)
      << stl.progress;
}

}  // namespace
}  // namespace cushion::solver
