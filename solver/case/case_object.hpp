#pragma once
/// The checked JSON object every part of the case-file parser reads through (internal to
/// solver/case): unknown keys are rejected with the closest known key suggested, a known key with
/// another unit suffix is named as a wrong unit ("time_period_ms": this quantity is given as
/// "time_period_s"), and every getter's error names the file and the key path, e.g.
/// "case.json: steps[2].steady_state.excitation.dof: ...".
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/json_reader.hpp"

namespace cushion::solver::case_parse {

/// Context shared by the whole parse: file name for messages, folder for relative paths.
struct Context {
  std::string source;            ///< the case file as given, prefix of every message
  std::filesystem::path folder;  ///< folder of the case file (relative paths start here)
};

/// "a.b" from path "a" and key "b"; just the key at the top level.
std::string join(const std::string& path, const std::string& key);

/// A JSON object whose keys must all be in `allowed`; typed, path-naming getters on top of io::JsonNode.
class Obj {
 public:
  /// Checks the keys of `value` (an object, else InputError) at key path `path` [-].
  Obj(const nlohmann::json& value, const Context& ctx, std::string path, const std::vector<std::string>& allowed);
  /// The member object `key` with its own allowed keys.
  Obj child(const std::string& key, const std::vector<std::string>& allowed) const;
  /// Element `index` of the member array `key` (an object with `allowed` keys).
  Obj element(const std::string& key, std::size_t index, const std::vector<std::string>& allowed) const;

  bool has(const std::string& key) const { return value_.contains(key); }
  /// True if member `key` exists and is a string (for keys that take a number or a word).
  bool is_string(const std::string& key) const { return has(key) && value_.at(key).is_string(); }
  /// True if member `key` exists and is an object.
  bool is_object(const std::string& key) const { return has(key) && value_.at(key).is_object(); }
  io::JsonNode at(const std::string& key) const { return node_.at(key); }  ///< required member
  const nlohmann::json& raw(const std::string& key) const;                  ///< required member, unchecked
  std::string path(const std::string& key) const { return join(path_, key); }  ///< key path of a member
  const std::string& here() const { return path_; }                            ///< key path of this object
  const Context& ctx() const { return ctx_; }
  [[noreturn]] void fail(const std::string& key, const std::string& problem) const;  ///< about member `key`
  [[noreturn]] void fail_here(const std::string& problem) const;                     ///< about this object

  double number(const std::string& key) const { return at(key).number(); }  ///< finite number
  double positive(const std::string& key) const;                            ///< number > 0
  double positive_or(const std::string& key, double fallback) const;        ///< positive, fallback if absent
  double non_negative(const std::string& key) const;                        ///< number >= 0
  int integer(const std::string& key, int min, int max) const;  ///< whole number in [min, max] (else names the key)
  std::string string(const std::string& key) const { return at(key).string(); }
  /// A string out of `choices`.
  std::string choice(const std::string& key, const std::vector<std::string>& choices) const;
  /// As choice, `fallback` if absent.
  std::string choice_or(const std::string& key, const std::vector<std::string>& choices,
                        const std::string& fallback) const;
  /// Existing file named relative to the case folder.
  std::filesystem::path file(const std::string& key) const;
  /// Array of n_min..n_max finite numbers.
  std::vector<double> numbers(const std::string& key, std::size_t n_min, std::size_t n_max) const;

 private:
  const nlohmann::json& value_;
  const Context& ctx_;
  std::string path_;
  io::JsonNode node_;
};

}  // namespace cushion::solver::case_parse
