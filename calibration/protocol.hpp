#pragma once
/// Protocol keys shared by campaigns (campaign.hpp) and the virtual lab's truth files (lab.hpp): what was
/// done to a specimen before a test and how a dynamic test's amplitude is read. Every key is optional and
/// has the documented default (README "Protocol keys"); a bad value is an InputError naming the key.
#include "io/json_reader.hpp"

namespace cushion::calibration {

/// Loading before a test: preflex cycles (load to preflex_strain and back at the test's crosshead speed),
/// then an unloaded rest.
struct PriorLoading {
  int preflex_cycles = 0;        ///< load/unload cycles before the test (key preflex_cycles, 0..100)
  double preflex_strain = 0.75;  ///< nominal compression of each preflex cycle [-] (key preflex_strain, (0, 0.95))
  double rest_s = 300.0;         ///< unloaded rest after the preflex [s] (key rest_between_tests_s, >= 0)
};

/// Reads preflex_cycles, preflex_strain (only with preflex_cycles > 0) and rest_between_tests_s of a test
/// object; absent keys keep `defaults`.
PriorLoading read_prior_loading(const io::JsonNode& test, PriorLoading defaults = {});

/// The amplitude convention of a dynamic test: key "amplitude_convention" (or its older name "amplitude_is"),
/// "peak_to_peak" (default, the paper's words: returns true) or "peak".
bool read_peak_to_peak(const io::JsonNode& test);

}  // namespace cushion::calibration
