#include "solver/case/case_object.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include "io/text_support.hpp"

namespace cushion::solver::case_parse {

namespace {

/// Unit suffixes used in key names and what they mean (for "wrong unit" messages).
const std::vector<std::pair<std::string, std::string>> kUnits = {
    {"s", "seconds"}, {"mm", "millimetres"}, {"mm3", "cubic millimetres"}, {"deg", "degrees"},
    {"Hz", "hertz"},  {"mm2", "square millimetres"}, {"kg", "kilograms"}};

/// Suffixes that look like a unit (so "time_period_ms" is a wrong unit, "initial_ss" a misspelling).
const std::set<std::string> kUnitLike = {"s",   "ms",  "us",  "min", "h",  "mm",  "m",   "cm",  "um", "in", "mm3", "m3",
                                         "cm3", "deg", "rad", "mm2", "m2", "cm2", "Hz",  "kHz", "MHz", "s2", "kg", "g",
                                         "lb"};

/// Key stem and unit suffix: "time_period_ms" -> {"time_period", "ms"}; no '_' -> {key, ""}.
std::pair<std::string, std::string> split_unit(const std::string& key) {
  const auto underscore = key.rfind('_');
  if (underscore == std::string::npos) return {key, ""};
  return {key.substr(0, underscore), key.substr(underscore + 1)};
}

/// Throws "wrong unit" if `key` is one of `allowed` with another unit suffix; returns otherwise.
void check_unit(const nlohmann::json& value, const Context& ctx, const std::string& path, const std::string& key,
                const std::vector<std::string>& allowed) {
  const auto [stem, unit] = split_unit(key);
  if (!kUnitLike.count(unit)) return;
  for (const auto& a : allowed) {
    const auto [a_stem, a_unit] = split_unit(a);
    if (a_unit.empty() || stem != a_stem) continue;
    const std::string& wanted = a_unit;  // a structured binding cannot be captured by clang 14 (fuzz build)
    const auto meaning =
        std::find_if(kUnits.begin(), kUnits.end(), [&wanted](const auto& u) { return u.first == wanted; });
    io::JsonNode(value[key], ctx.source, join(path, key))
        .fail("wrong unit '" + unit + "': this quantity is given as '" + a + "'" +
              (meaning != kUnits.end() ? " (" + meaning->second + ")" : std::string{}));
  }
}

/// Largest magnitude of a number in a case file, and of a length (a key ending in "_mm", not "_per_mm"): beyond them a value
/// is a typo or an overflow waiting to happen (1e308 mm), never a seat.
constexpr double kLargestNumber = 1e12, kLargestLength = 1e6;

/// Throws, naming the key (and the index in an array), if a number of member `key` is past its bound.
void check_magnitude(const nlohmann::json& value, const Context& ctx, const std::string& path, const std::string& key) {
  const auto [stem, unit] = split_unit(key);
  const bool length = unit == "mm" && !(stem.size() >= 4 && stem.compare(stem.size() - 4, 4, "_per") == 0);
  const double bound = length ? kLargestLength : kLargestNumber;
  const auto check = [&](const nlohmann::json& x, const std::string& where) {
    if (x.is_number() && !(std::abs(x.get<double>()) <= bound))
      io::JsonNode(x, ctx.source, where)
          .fail("must be within +-" + io::format_double(bound) + (length ? " mm" : "") + ", found " +
                io::format_double(x.get<double>()));
  };
  const nlohmann::json& member = value[key];
  if (!member.is_array()) return check(member, join(path, key));
  for (std::size_t i = 0; i < member.size(); ++i) check(member[i], join(path, key) + "[" + std::to_string(i) + "]");
}

}  // namespace

std::string join(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }

Obj::Obj(const nlohmann::json& value, const Context& ctx, std::string path, const std::vector<std::string>& allowed)
    : value_(value), ctx_(ctx), path_(std::move(path)), node_(value, ctx.source, path_) {
  if (value.is_object())
    for (const auto& [key, ignored] : value.items())
      if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) check_unit(value, ctx, path_, key, allowed);
  node_.expect_object(allowed);
  for (const auto& [key, ignored] : value.items()) check_magnitude(value, ctx, path_, key);
}

Obj Obj::child(const std::string& key, const std::vector<std::string>& allowed) const {
  return Obj(raw(key), ctx_, path(key), allowed);
}

Obj Obj::element(const std::string& key, std::size_t index, const std::vector<std::string>& allowed) const {
  return Obj(raw(key)[index], ctx_, path(key) + "[" + std::to_string(index) + "]", allowed);
}

const nlohmann::json& Obj::raw(const std::string& key) const {
  node_.at(key);  // "missing key" if absent
  return value_.at(key);
}

void Obj::fail(const std::string& key, const std::string& problem) const {
  io::JsonNode(value_, ctx_.source, path(key)).fail(problem);
}

void Obj::fail_here(const std::string& problem) const { node_.fail(problem); }

double Obj::positive(const std::string& key) const {
  const double x = number(key);
  if (!(x > 0.0)) fail(key, "must be > 0, found " + io::format_double(x));
  return x;
}

double Obj::positive_or(const std::string& key, double fallback) const { return has(key) ? positive(key) : fallback; }

double Obj::non_negative(const std::string& key) const {
  const double x = number(key);
  if (!(x >= 0.0)) fail(key, "must be >= 0, found " + io::format_double(x));
  return x;
}

int Obj::integer(const std::string& key, int min, int max) const {
  const double x = number(key);
  if (x != std::floor(x)) fail(key, "must be an integer, found " + io::format_double(x));
  if (x < static_cast<double>(min) || x > static_cast<double>(max))
    fail(key, "must be an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "], found " +
                  io::format_double(x));
  return static_cast<int>(x);
}

std::string Obj::choice(const std::string& key, const std::vector<std::string>& choices) const {
  return at(key).choice(choices);
}

std::string Obj::choice_or(const std::string& key, const std::vector<std::string>& choices,
                           const std::string& fallback) const {
  return has(key) ? choice(key, choices) : fallback;
}

std::filesystem::path Obj::file(const std::string& key) const {
  const std::string name = string(key);
  if (name.empty()) fail(key, "must name a file");
  const std::filesystem::path p = ctx_.folder / name;
  if (std::filesystem::is_directory(p)) fail(key, "is a folder, not a file: " + p.string());
  if (!std::filesystem::is_regular_file(p)) fail(key, "file not found: " + p.string());
  return p;
}

std::vector<double> Obj::numbers(const std::string& key, std::size_t n_min, std::size_t n_max) const {
  const io::JsonNode array = at(key);
  const std::size_t n = array.expect_array(n_min, n_max);
  std::vector<double> out(n);
  for (std::size_t i = 0; i < n; ++i) out[i] = array[i].number();
  return out;
}

}  // namespace cushion::solver::case_parse
