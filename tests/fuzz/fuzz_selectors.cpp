// libFuzzer harness: selector text (mesh/selectors.hpp parse_selector), then validate and select the
// nodes of a small block and the faces they span.
#include "mesh/selectors.hpp"
#include "mesh/structured_hex.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const cushion::mesh::Mesh block = [] {
    cushion::mesh::BlockSpec spec;
    spec.high = cushion::mesh::Vec3(10.0, 10.0, 10.0);
    spec.n = {2, 2, 2};
    return cushion::mesh::structured_block(spec);
  }();
  const std::string text = cushion::fuzz::text(data, size);
  cushion::fuzz::expect_input_error_only([&] {
    const cushion::mesh::Selector selector = cushion::mesh::parse_selector(text, "fuzz");
    const std::vector<int> nodes = cushion::mesh::select_nodes(block, selector);
    (void)cushion::mesh::surface_from_node_set(block, nodes);
  });
  return 0;
}
