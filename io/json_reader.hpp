#pragma once
/// Checked reading of JSON input files (material, protocol): every problem becomes an InputError
/// "<file>: <key.path>: <problem>", unknown keys are rejected with the closest known key suggested.
#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace cushion::io {

/// Parses JSON text; a syntax error (NaN, trailing comma, ...) is an InputError naming the file,
/// line, column and the last key before the error.
nlohmann::json parse_json(const std::string& text, const std::string& source);

/// Reads a whole text file; InputError if it cannot be opened.
std::string read_text_file(const std::string& file);

/// A JSON value together with the file and key path it came from.
class JsonNode {
 public:
  JsonNode(const nlohmann::json& value, std::string source, std::string path = "");

  [[noreturn]] void fail(const std::string& problem) const;  ///< throws "source: path: problem"
  const std::string& path() const { return path_; }

  /// Requires an object whose keys are all in `allowed` (else names the unknown key).
  void expect_object(const std::vector<std::string>& allowed) const;
  bool has(const std::string& key) const;               ///< object has `key`
  JsonNode at(const std::string& key) const;            ///< required member (else "missing key")
  std::optional<JsonNode> find(const std::string& key) const;  ///< optional member

  /// Requires an array of min..max elements; returns its size.
  std::size_t expect_array(std::size_t min, std::size_t max) const;
  JsonNode operator[](std::size_t index) const;         ///< array element (after expect_array)

  double number() const;       ///< a finite number
  std::string string() const;  ///< a string
  bool boolean() const;        ///< true or false
  long long integer(long long min, long long max) const;  ///< a whole number in [min, max]
  /// A string that must be one of `choices`.
  std::string choice(const std::vector<std::string>& choices) const;

  /// Finite number checked against a range; `what` is the text after "must be", e.g. "> 0".
  double number_where(bool (*ok)(double), const std::string& what) const;

 private:
  const nlohmann::json* value_;
  std::string source_, path_;
};

}  // namespace cushion::io
