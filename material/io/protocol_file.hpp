#pragma once
/// Protocol files for `cushion point` (README "Protocol file"): the segments of a point history, in order.
/// {
///   "description": "free text",                                                   (optional)
///   "platen": false,                                                              (optional, default false)
///   "segments": [
///     {"ramp": {"target": -0.75, "duration_s": 30, "steps": 300}},                (steps optional)
///     {"hold": {"duration_s": 2, "steps": 10}},                                   (steps optional)
///     {"sine": {"amplitude": 0.01, "frequency_Hz": 1, "cycles": 5, "steps_per_cycle": 64}}
///   ]
/// }
/// target and amplitude are the control (nominal strain l - 1, tension positive; gamma in simple shear).
/// Physical bounds (a value past them would overflow the driver; issue 16: a 1e308 target was
/// accepted): |target| <= 10, 0 <= amplitude <= 10, 0 < duration_s <= 1e9 s, 0 < frequency_Hz <= 1e6,
/// 0 < cycles <= 1e8; steps and steps_per_cycle 1..1e8.
/// Problems raise InputError "<file>: segments[2].sine.frequency_Hz: must be > 0, found 0".
#include <filesystem>
#include <string>
#include <vector>

#include "material/point_driver.hpp"

namespace cushion::material {

struct Protocol {
  std::vector<Segment> segments;
  bool platen = false;   ///< drive axis 1 by a platen that only pushes (AxisControl::platen)
  std::string description;
};

Protocol parse_protocol_json(const std::string& text, const std::string& source);
Protocol read_protocol_file(const std::filesystem::path& file);

}  // namespace cushion::material
