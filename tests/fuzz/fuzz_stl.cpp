// libFuzzer harness: STL surfaces, ASCII or binary (mesh/stl.hpp read_stl from a per-process temporary
// file), then the closedness check and the enclosed volume the TetGen path uses.
#include "mesh/stl.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = cushion::fuzz::write_file("fuzz.stl", cushion::fuzz::text(data, size));
  cushion::fuzz::expect_input_error_only([&] {
    const cushion::mesh::TriangleSurface surface = cushion::mesh::read_stl(path.string());
    cushion::mesh::check_closed(surface, "fuzz.stl");
    (void)cushion::mesh::enclosed_volume(surface);
  });
  return 0;
}
