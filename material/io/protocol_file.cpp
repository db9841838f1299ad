#include "material/io/protocol_file.hpp"

#include <algorithm>
#include <cmath>

#include "io/json_reader.hpp"

namespace cushion::material {

namespace {

// Physical bounds (protocol_file.hpp): a value past them would overflow the driver later (1e308 was accepted).
bool strain_range(double x) { return std::abs(x) <= 10.0; }              // |control| <= 10
bool amplitude_range(double x) { return x >= 0.0 && x <= 10.0; }
bool time_range(double x) { return x > 0.0 && x <= 1e9; }                // 0 < duration_s <= 1e9 s
bool frequency_range(double x) { return x > 0.0 && x <= 1e6; }          // 0 < frequency_Hz <= 1e6
bool cycles_range(double x) { return x > 0.0 && x <= 1e8; }
constexpr long long max_steps = 100000000;

Segment read_segment(const io::JsonNode& node) {
  node.expect_object({"ramp", "hold", "sine"});
  if (node.has("ramp") + node.has("hold") + node.has("sine") != 1)
    node.fail("must hold exactly one of \"ramp\", \"hold\", \"sine\"");
  Segment s;
  if (auto ramp = node.find("ramp")) {
    ramp->expect_object({"target", "duration_s", "steps"});
    s.kind = Segment::Kind::ramp;
    s.target = ramp->at("target").number_where(strain_range, "in [-10, 10]");
    s.duration = ramp->at("duration_s").number_where(time_range, "> 0 and <= 1e9 s");
    if (auto steps = ramp->find("steps")) s.steps = static_cast<int>(steps->integer(1, max_steps));
  } else if (auto hold = node.find("hold")) {
    hold->expect_object({"duration_s", "steps"});
    s.kind = Segment::Kind::hold;
    s.duration = hold->at("duration_s").number_where(time_range, "> 0 and <= 1e9 s");
    if (auto steps = hold->find("steps")) s.steps = static_cast<int>(steps->integer(1, max_steps));
  } else {
    const io::JsonNode sine = node.at("sine");
    sine.expect_object({"amplitude", "frequency_Hz", "cycles", "steps_per_cycle"});
    s.kind = Segment::Kind::sine;
    s.amplitude = sine.at("amplitude").number_where(amplitude_range, "in [0, 10]");
    s.frequency = sine.at("frequency_Hz").number_where(frequency_range, "> 0 and <= 1e6 Hz");
    s.cycles = sine.at("cycles").number_where(cycles_range, "> 0 and <= 1e8");
    if (auto per_cycle = sine.find("steps_per_cycle")) {
      const double steps = static_cast<double>(per_cycle->integer(1, max_steps)) * s.cycles;
      if (steps > static_cast<double>(max_steps)) per_cycle->fail("too many increments in the segment");
      s.steps = std::max(1, static_cast<int>(std::ceil(steps - 1e-9)));
    }
  }
  return s;
}

}  // namespace

Protocol parse_protocol_json(const std::string& text, const std::string& source) {
  const nlohmann::json json = io::parse_json(text, source);
  const io::JsonNode root(json, source);
  root.expect_object({"description", "platen", "segments"});
  Protocol protocol;
  if (auto description = root.find("description")) protocol.description = description->string();
  if (auto platen = root.find("platen")) protocol.platen = platen->boolean();
  const io::JsonNode segments = root.at("segments");
  const std::size_t n = segments.expect_array(1, 100000);
  for (std::size_t i = 0; i < n; ++i) protocol.segments.push_back(read_segment(segments[i]));
  return protocol;
}

Protocol read_protocol_file(const std::filesystem::path& file) {
  return parse_protocol_json(io::read_text_file(file.string()), file.string());
}

}  // namespace cushion::material
