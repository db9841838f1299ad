#include "calibration/protocol.hpp"

namespace cushion::calibration {

PriorLoading read_prior_loading(const io::JsonNode& t, PriorLoading p) {
  if (auto c = t.find("preflex_cycles")) p.preflex_cycles = static_cast<int>(c->integer(0, 100));
  if (auto e = t.find("preflex_strain")) {
    if (p.preflex_cycles == 0) e->fail("given without preflex_cycles > 0 (a preflex strain with no preflex)");
    p.preflex_strain = e->number_where([](double x) { return x > 0.0 && x < 0.95; }, "in (0, 0.95) (nominal compression)");
  }
  if (auto r = t.find("rest_between_tests_s")) p.rest_s = r->number_where([](double x) { return x >= 0.0; }, ">= 0");
  return p;
}

bool read_peak_to_peak(const io::JsonNode& t) {
  const auto a = t.find("amplitude_convention"), b = t.find("amplitude_is");
  if (a && b) b->fail("give either amplitude_convention or its older name amplitude_is, not both");
  if (const auto& c = a ? a : b) return c->choice({"peak_to_peak", "peak"}) == "peak_to_peak";
  return true;
}

}  // namespace cushion::calibration
