// The named definitions steps refer to (case_spec.hpp): "sets" (selector text) and "amplitudes".
#include "io/text_support.hpp"
#include "mesh/selectors.hpp"
#include "solver/case/case_parts.hpp"

namespace cushion::solver::case_parse {

namespace {

/// {"type": "sine", "frequency_Hz": f, "start_s"?: t0, "time"?: ...} (case_spec.hpp).
Amplitude parse_sine_amplitude(const Obj& o) {
  Amplitude a;
  a.kind = Amplitude::Kind::sine;
  a.frequency = o.positive("frequency_Hz");
  if (o.has("start_s")) a.start = o.number("start_s");
  if (a.start < 0.0) o.fail("start_s", "must be >= 0, found " + io::format_double(a.start));
  a.total_time = o.choice_or("time", {"step", "total"}, "step") == "total";
  return a;
}

Amplitude parse_tabular_amplitude(const Obj& o) {
  if (o.has("type")) o.choice("type", {"tabular"});  // "sine" is dispatched by the caller
  Amplitude a;
  a.time = o.numbers("time_s", 1, 1000000);
  a.value = o.numbers("value", 1, 1000000);
  if (a.value.size() != a.time.size())
    o.fail("value", "must have as many entries as time_s (" + std::to_string(a.time.size()) + "), found " +
                        std::to_string(a.value.size()));
  for (std::size_t i = 0; i < a.time.size(); ++i) {
    if (a.time[i] < 0.0) o.fail("time_s", "must be >= 0, found " + io::format_double(a.time[i]));
    if (i > 0 && !(a.time[i] > a.time[i - 1]))
      o.fail("time_s", "must be strictly increasing (entry " + std::to_string(i) + ")");
  }
  a.total_time = o.choice_or("time", {"step", "total"}, "step") == "total";
  return a;
}

}  // namespace

std::map<std::string, std::string> parse_sets(const Obj& top) {
  std::map<std::string, std::string> out;
  const nlohmann::json& sets = top.raw("sets");
  if (!sets.is_object()) top.fail("sets", "must be an object {\"name\": \"selector\", ...}");
  for (const auto& [name, value] : sets.items()) {
    const std::string selector = io::JsonNode(value, top.ctx().source, "sets." + name).string();
    mesh::parse_selector(selector, top.ctx().source + ": sets." + name);  // syntax check now
    out[name] = selector;
  }
  return out;
}

std::map<std::string, Amplitude> parse_amplitudes(const Obj& top) {
  std::map<std::string, Amplitude> out;
  const nlohmann::json& amplitudes = top.raw("amplitudes");
  if (!amplitudes.is_object()) top.fail("amplitudes", "must be an object {\"name\": {...}, ...}");
  const Context& ctx = top.ctx();
  for (const auto& [name, value] : amplitudes.items()) {
    const std::string path = "amplitudes." + name;
    const bool sine = value.is_object() && value.contains("type") &&
                      io::JsonNode(value, ctx.source, path).at("type").choice({"tabular", "sine"}) == "sine";
    out[name] = sine ? parse_sine_amplitude(Obj(value, ctx, path, {"type", "frequency_Hz", "start_s", "time"}))
                     : parse_tabular_amplitude(Obj(value, ctx, path, {"type", "time_s", "value", "time"}));
  }
  return out;
}

}  // namespace cushion::solver::case_parse
