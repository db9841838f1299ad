#include "io/json_reader.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <cctype>
#include <sstream>

#include "io/input_error.hpp"
#include "io/text_support.hpp"

namespace cushion::io {

namespace {

/// Line and column (1-based) of byte `offset` in `text`.
std::pair<std::size_t, std::size_t> line_column(const std::string& text, std::size_t offset) {
  offset = std::min(offset, text.size());
  std::size_t line = 1, column = 1;
  for (std::size_t i = 0; i < offset; ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return {line, column};
}

/// The last `"key":` before byte `offset`, or "". A backward scan (no regex: std::regex recurses per
/// character and overflows the stack on long strings): the last ':' outside strings, then the string
/// literal before it.
std::string last_key_before(const std::string& text, std::size_t offset) {
  const std::size_t end = std::min(offset, text.size());
  std::size_t colon = std::string::npos;
  bool in_string = false;
  for (std::size_t i = 0; i < end; ++i) {  // forward pass: find colons outside strings
    const char c = text[i];
    if (in_string) {
      if (c == '\\') ++i;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == ':') {
      colon = i;
    }
  }
  if (colon == std::string::npos) return "";
  std::size_t close = colon;
  while (close > 0 && std::isspace(static_cast<unsigned char>(text[close - 1]))) --close;
  if (close < 2 || text[close - 1] != '"') return "";
  const std::size_t open = text.rfind('"', close - 2);  // the key's opening quote
  if (open == std::string::npos) return "";
  return text.substr(open + 1, close - 2 - open);
}

std::string type_name(const nlohmann::json& v) {
  if (v.is_number()) return "a number";
  if (v.is_string()) return "a string";
  if (v.is_boolean()) return "a boolean";
  if (v.is_array()) return "an array";
  if (v.is_object()) return "an object";
  return "null";
}

}  // namespace

nlohmann::json parse_json(const std::string& text, const std::string& source) {
  std::size_t offset = 0;
  std::string reason;
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    offset = e.byte > 0 ? e.byte - 1 : 0;
    reason = e.what();
  } catch (const nlohmann::json::exception& e) {  // e.g. "number overflow parsing '1e999'": locate the token
    reason = e.what();
    const auto open = reason.find('\''), close = reason.rfind('\'');
    if (open != std::string::npos && close > open) {
      const std::size_t at = text.find(reason.substr(open + 1, close - open - 1));
      if (at != std::string::npos) offset = at + 1;
    }
  }
  const auto [line, column] = line_column(text, offset);
  const std::string key = last_key_before(text, offset);
  const auto colon = reason.rfind(": ");
  if (colon != std::string::npos) reason = reason.substr(colon + 2);
  throw InputError(source + ":" + std::to_string(line) + ":" + std::to_string(column) + ": invalid JSON" +
                   (key.empty() ? std::string{} : " in the value of key '" + key + "'") + " (" + reason +
                   "; JSON has no NaN or Infinity)");
}

std::string read_text_file(const std::string& file) {
  require_readable_file(file, "JSON file");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file + ": cannot open file");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

JsonNode::JsonNode(const nlohmann::json& value, std::string source, std::string path)
    : value_(&value), source_(std::move(source)), path_(std::move(path)) {}

void JsonNode::fail(const std::string& problem) const {
  throw InputError(source_ + ": " + (path_.empty() ? std::string{} : path_ + ": ") + problem);
}

void JsonNode::expect_object(const std::vector<std::string>& allowed) const {
  if (!value_->is_object()) fail("must be an object, found " + type_name(*value_));
  for (const auto& [key, ignored] : value_->items())
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
      JsonNode(*value_, source_, path_.empty() ? key : path_ + "." + key)
          .fail("unknown key" + did_you_mean(key, allowed) + "; allowed keys: " + join(allowed, ", "));
    }
}

bool JsonNode::has(const std::string& key) const { return value_->is_object() && value_->contains(key); }

JsonNode JsonNode::at(const std::string& key) const {
  const std::string child = path_.empty() ? key : path_ + "." + key;
  if (!has(key)) JsonNode(*value_, source_, child).fail("missing key");
  return JsonNode((*value_)[key], source_, child);
}

std::optional<JsonNode> JsonNode::find(const std::string& key) const {
  if (!has(key)) return std::nullopt;
  return at(key);
}

std::size_t JsonNode::expect_array(std::size_t min, std::size_t max) const {
  if (!value_->is_array()) fail("must be an array, found " + type_name(*value_));
  const std::size_t n = value_->size();
  if (n < min || n > max)
    fail("must have " + std::to_string(min) + ".." + std::to_string(max) + " entries, found " + std::to_string(n));
  return n;
}

JsonNode JsonNode::operator[](std::size_t index) const {
  return JsonNode((*value_)[index], source_, path_ + "[" + std::to_string(index) + "]");
}

double JsonNode::number() const {
  if (!value_->is_number()) fail("must be a number, found " + type_name(*value_));
  const double x = value_->get<double>();
  if (!std::isfinite(x)) fail("must be a finite number");
  return x;
}

std::string JsonNode::string() const {
  if (!value_->is_string()) fail("must be a string, found " + type_name(*value_));
  return value_->get<std::string>();
}

bool JsonNode::boolean() const {
  if (!value_->is_boolean()) fail("must be true or false, found " + type_name(*value_));
  return value_->get<bool>();
}

long long JsonNode::integer(long long min, long long max) const {
  const double x = number();
  if (x != std::floor(x)) fail("must be a whole number, found " + format_double(x));
  if (x < static_cast<double>(min) || x > static_cast<double>(max))
    fail("must be in [" + std::to_string(min) + ", " + std::to_string(max) + "], found " + format_double(x));
  return static_cast<long long>(x);
}

std::string JsonNode::choice(const std::vector<std::string>& choices) const {
  const std::string s = string();
  if (std::find(choices.begin(), choices.end(), s) != choices.end()) return s;
  fail("\"" + s + "\" is not one of " + join(choices, ", ") + did_you_mean(s, choices));
}

double JsonNode::number_where(bool (*ok)(double), const std::string& what) const {
  const double x = number();
  if (!ok(x)) fail("must be " + what + ", found " + format_double(x));
  return x;
}

}  // namespace cushion::io
