// libFuzzer harness: ABAQUS .inp decks (mesh/inp_reader.hpp parse_inp). The bytes are also written to
// the file the deck is named after, so *INCLUDE of itself (or of mesh.inp beside it) is reachable.
#include "mesh/inp_reader.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const auto include = cushion::fuzz::write_file(
      "mesh.inp", "*NODE\n1,0,0,0\n2,1,0,0\n3,0,1,0\n4,0,0,1\n*ELEMENT,TYPE=C3D4,ELSET=E\n1,1,2,3,4\n");
  (void)include;
  const std::string text = cushion::fuzz::text(data, size);
  const auto path = cushion::fuzz::write_file("fuzz.inp", text);
  cushion::fuzz::expect_input_error_only([&] { cushion::mesh::parse_inp(text, path.string()); });
  return 0;
}
