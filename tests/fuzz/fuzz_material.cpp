// libFuzzer harness: material JSON (material/io/material_file.hpp parse_material_json, which
// validates the file and builds the model).
#include "material/io/material_file.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text = cushion::fuzz::text(data, size);
  cushion::fuzz::expect_input_error_only([&] { cushion::material::parse_material_json(text, "fuzz.json"); });
  return 0;
}
