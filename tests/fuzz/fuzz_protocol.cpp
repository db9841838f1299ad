// libFuzzer harness: protocol JSON for `cushion point` (material/io/protocol_file.hpp parse_protocol_json).
#include "material/io/protocol_file.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text = cushion::fuzz::text(data, size);
  cushion::fuzz::expect_input_error_only([&] { cushion::material::parse_protocol_json(text, "fuzz.json"); });
  return 0;
}
