// libFuzzer harness: case JSON (solver/case/case_file.hpp parse_case_json). The case is named
// <per-process folder>/case.json, beside a valid material.json and mesh.inp it may refer to. When the
// parse succeeds, the mesh is built only if it is small (a generated block of at most 512 cells or
// the 1-element mesh.inp; STL/TetGen meshes are not built) so the selector sets and set-name checks
// run too.
#include "solver/case/case_file.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const bool files = [] {
    cushion::fuzz::write_file("material.json",
                              "{\"hyperfoam\": {\"terms\": [{\"mu_kPa\": 10, \"alpha\": 8, \"nu\": 0}]}}");
    cushion::fuzz::write_file("mesh.inp",
                              "*NODE\n1,0,0,0\n2,1,0,0\n3,0,1,0\n4,0,0,1\n*ELEMENT,TYPE=C3D4,ELSET=E\n1,1,2,3,4\n"
                              "*NSET,NSET=TOP\n4\n");
    cushion::fuzz::write_file("part.stl", "solid s\nendsolid s\n");
    return true;
  }();
  (void)files;
  const std::string text = cushion::fuzz::text(data, size);
  cushion::fuzz::expect_input_error_only([&] {
    const cushion::solver::CaseSpec spec = cushion::solver::parse_case_json(text, cushion::fuzz::work_dir() / "case.json");
    using Source = cushion::solver::MeshSpec::Source;
    const auto& n = spec.mesh.generate.elements;
    const bool small = spec.mesh.source == Source::inp ||
                       (spec.mesh.source == Source::generate && double(n[0]) * n[1] * n[2] <= 512.0);
    if (small) (void)cushion::solver::build_case_mesh(spec);
  });
  return 0;
}
