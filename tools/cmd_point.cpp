// `cushion point`: runs a strain history at one material point and writes the stresses to a CSV file.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <iostream>
#include <memory>
#include <sstream>

#include "io/input_error.hpp"
#include "io/csv.hpp"
#include "material/io/material_file.hpp"
#include "material/io/protocol_file.hpp"
#include "material/point_driver.hpp"
#include "tools/command.hpp"

namespace cushion::tools {

namespace {

using material::Segment;

struct PointOptions {
  std::string material_file, mode = "uniaxial_free", protocol_file, output;
  std::vector<std::string> ramps, holds, sines;
  bool platen = false;
  CLI::Option *ramp = nullptr, *hold = nullptr, *sine = nullptr;
};

/// Splits "a,b,c" into numbers; `form` (e.g. "TARGET,DURATION_S[,STEPS]") names them in messages.
std::vector<double> parse_numbers(const std::string& option, const std::string& text, const std::string& form,
                                  std::size_t min_count, std::size_t max_count) {
  std::vector<double> values;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    const std::string cell = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    double x = 0.0;
    const auto [ptr, ec] = std::from_chars(cell.data(), cell.data() + cell.size(), x);
    if (cell.empty() || ec != std::errc{} || ptr != cell.data() + cell.size() || !std::isfinite(x))
      throw InputError(option + " '" + text + "': '" + cell + "' is not a finite number (expected " + form + ")");
    values.push_back(x);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (values.size() < min_count || values.size() > max_count)
    throw InputError(option + " '" + text + "': expected " + form + ", found " + std::to_string(values.size()) + " value(s)");
  return values;
}

int parse_steps(const std::string& option, const std::string& text, double value) {
  if (value < 1.0 || value != std::floor(value) || value > 1e8)
    throw InputError(option + " '" + text + "': STEPS must be a whole number >= 1");
  return static_cast<int>(value);
}

/// The segments given on the command line, in the order they were typed.
std::vector<Segment> segments_from_options(const CLI::App& sub, const PointOptions& o) {
  std::vector<Segment> segments;
  std::size_t next_ramp = 0, next_hold = 0, next_sine = 0;
  for (const CLI::Option* option : sub.parse_order()) {
    Segment s;
    if (option == o.ramp) {
      const std::string& text = o.ramps.at(next_ramp++);
      const auto v = parse_numbers("--ramp", text, "TARGET,DURATION_S[,STEPS]", 2, 3);
      s.kind = Segment::Kind::ramp;
      s.target = v[0];
      s.duration = v[1];
      if (v.size() == 3) s.steps = parse_steps("--ramp", text, v[2]);
    } else if (option == o.hold) {
      const std::string& text = o.holds.at(next_hold++);
      const auto v = parse_numbers("--hold", text, "DURATION_S[,STEPS]", 1, 2);
      s.kind = Segment::Kind::hold;
      s.duration = v[0];
      if (v.size() == 2) s.steps = parse_steps("--hold", text, v[1]);
    } else if (option == o.sine) {
      const std::string& text = o.sines.at(next_sine++);
      const auto v = parse_numbers("--sine", text, "AMPLITUDE,FREQ_HZ,CYCLES[,STEPS_PER_CYCLE]", 3, 4);
      s.kind = Segment::Kind::sine;
      s.amplitude = v[0];
      s.frequency = v[1];
      s.cycles = v[2];
      if (v.size() == 4 && s.cycles > 0.0)  // bad cycles are reported by build_history
        s.steps = std::max(1, static_cast<int>(std::min(1e8, std::ceil(parse_steps("--sine", text, v[3]) * s.cycles - 1e-9))));
    } else {
      continue;
    }
    segments.push_back(s);
  }
  return segments;
}

/// Output table: one row per sample, stresses in kPa (tension positive).
void write_result(const std::string& file, const material::PointResult& r, const std::vector<std::string>& comment) {
  const std::vector<std::string> columns = {"time_s",      "control",     "stretch_1",   "stretch_2",  "stretch_3",
                                            "F12",         "J",           "P11_kPa",     "P22_kPa",    "P33_kPa",
                                            "P12_kPa",     "sigma11_kPa", "sigma22_kPa", "sigma33_kPa", "sigma12_kPa",
                                            "in_contact"};
  std::vector<std::vector<double>> data(columns.size());
  constexpr double kPa = 1e3;  // MPa -> kPa
  for (std::size_t i = 0; i < r.time.size(); ++i) {
    const Mat3& F = r.F[i];
    const double row[] = {r.time[i],          r.control[i],       F(0, 0),           F(1, 1),
                          F(2, 2),            F(0, 1),            F.determinant(),   r.P[i](0, 0) * kPa,
                          r.P[i](1, 1) * kPa, r.P[i](2, 2) * kPa, r.P[i](0, 1) * kPa, r.sigma[i](0, 0) * kPa,
                          r.sigma[i](1, 1) * kPa, r.sigma[i](2, 2) * kPa, r.sigma[i](0, 1) * kPa,
                          r.in_contact[i] ? 1.0 : 0.0};
    for (std::size_t c = 0; c < columns.size(); ++c) data[c].push_back(row[c]);
  }
  write_csv(file, columns, data, comment);
}

void run(const CLI::App& sub, const PointOptions& o) {
  if (o.material_file.empty()) throw InputError("point: --material FILE is required");
  if (o.output.empty()) throw InputError("point: -o/--output FILE.csv is required");
  const bool command_line_segments = o.ramp->count() + o.hold->count() + o.sine->count() > 0;
  if (command_line_segments == !o.protocol_file.empty())
    throw InputError("point: give the protocol either as --ramp/--hold/--sine segments or as --protocol FILE (one of the two)");

  const material::LoadMode mode = material::load_mode_from_string(o.mode);
  const material::MaterialDefinition definition = material::read_material_file(o.material_file);
  std::vector<Segment> segments;
  bool platen = o.platen;
  if (command_line_segments) {
    segments = segments_from_options(sub, o);
  } else {
    const material::Protocol protocol = material::read_protocol_file(o.protocol_file);
    segments = protocol.segments;
    platen = platen || protocol.platen;
  }
  const material::History history =
      material::build_history(segments, platen ? material::AxisControl::platen : material::AxisControl::displacement);
  if (mode != material::LoadMode::simple_shear)
    for (std::size_t i = 0; i < history.control.size(); ++i)
      if (!(history.control[i] > -1.0)) {
        std::ostringstream s;
        s << "point: the protocol reaches control " << history.control[i] << " at t = " << history.time[i]
          << " s; nominal strain must stay > -1 (positive stretch)";
        throw InputError(s.str());
      }

  const material::PointResult result = material::run_point(*definition.model, mode, history);

  std::vector<std::string> comment = {
      "cushion point: material " + definition.spec.name + " (" + o.material_file + "): " + definition.model->describe(),
      "mode " + o.mode + (platen ? ", platen control" : ", displacement control") +
          "; stresses nominal (P) and Cauchy (sigma) in kPa, tension positive; control = nominal strain (gamma in simple_shear)"};
  write_result(o.output, result, comment);

  std::size_t peak = 0, lift_off = 0;
  for (std::size_t i = 0; i < result.time.size(); ++i) {
    if (std::abs(result.P[i](0, 0)) > std::abs(result.P[peak](0, 0))) peak = i;
    lift_off += result.in_contact[i] ? 0 : 1;
  }
  const int shear = mode == material::LoadMode::simple_shear ? 1 : 0;
  const char* component = shear ? "P12" : "P11";
  std::cout << "cushion point: " << definition.spec.name << ": " << definition.model->describe() << "\n"
            << "  mode " << o.mode << (platen ? " (platen)" : "") << ", " << result.time.size() << " samples over "
            << result.time.front() << " .. " << result.time.back() << " s\n"
            << "  peak |" << component << "| = " << std::abs(result.P[peak](0, shear)) * 1e3 << " kPa at t = "
            << result.time[peak] << " s (control " << result.control[peak] << "); final " << component << " = "
            << result.P.back()(0, shear) * 1e3 << " kPa\n";
  if (platen) std::cout << "  platen: foam clear of the platen at " << lift_off << " of " << result.time.size() << " samples\n";
  for (const auto& warning : result.warnings) std::cout << "  warning: " << warning << "\n";
  std::cout << "  output: " << o.output << "\n";
}

const Registrar registrar{"point", [](CLI::App& app) {
  auto options = std::make_shared<PointOptions>();
  CLI::App* sub = app.add_subcommand("point", "Run a strain history at one material point; write stresses to CSV");
  sub->add_option("-m,--material", options->material_file, "Material file (JSON, see README)");
  sub->add_option("--mode", options->mode,
                  "uniaxial_free | uniaxial_constrained | volumetric | simple_shear (default uniaxial_free)");
  options->ramp = sub->add_option("--ramp", options->ramps,
                                  "TARGET,DURATION_S[,STEPS]: linear ramp of the control (nominal strain, tension > 0)")
                      ->expected(1)->take_all()->allow_extra_args(false);
  options->hold = sub->add_option("--hold", options->holds, "DURATION_S[,STEPS]: hold the control")
                      ->expected(1)->take_all()->allow_extra_args(false);
  options->sine = sub->add_option("--sine", options->sines,
                                  "AMPLITUDE,FREQ_HZ,CYCLES[,STEPS_PER_CYCLE]: sine about the current control")
                      ->expected(1)->take_all()->allow_extra_args(false);
  sub->add_option("--protocol", options->protocol_file, "Protocol file (JSON) instead of --ramp/--hold/--sine");
  sub->add_flag("--platen", options->platen, "Axis 1 driven by a platen that only pushes (lift-off allowed)");
  sub->add_option("-o,--output", options->output, "Output CSV file");
  sub->callback([sub, options] { run(*sub, *options); });
}};

}  // namespace

}  // namespace cushion::tools
