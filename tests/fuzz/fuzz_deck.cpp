// libFuzzer harness: ABAQUS/CalculiX decks run by `cushion run DECK.inp` (solver/deck/deck_reader.hpp
// load_deck: mesh, materials, steps, conditions, checks). Only InputError may escape.
#include "solver/deck/deck_reader.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto path = cushion::fuzz::write_file("fuzz_deck.inp", cushion::fuzz::text(data, size));
  cushion::fuzz::expect_input_error_only(
      [&] { cushion::solver::load_deck(path, cushion::solver::deck_units("mm-N-MPa")); });
  return 0;
}
