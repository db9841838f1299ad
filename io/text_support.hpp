#pragma once
/// Small text helpers shared by the file readers and writers of cushion (CSV, material, protocol).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace cushion::io {

/// The known name closest to `word` (case-insensitive edit distance), or "" when none is close
/// enough to be a plausible misspelling (distance > max(2, |word|/3)).
std::string closest_name(const std::string& word, const std::vector<std::string>& known);

/// " (did you mean 'x'?)" for the closest known name, or "" when there is none.
std::string did_you_mean(const std::string& word, const std::vector<std::string>& known);

/// Checks that `file` is an existing, readable regular file; throws InputError "<file>: no such file",
/// "<file>: is a folder, not a <what>" or "<file>: cannot read (permission?)" otherwise.
void require_readable_file(const std::filesystem::path& file, const std::string& what);

/// Writes `content` to `file` atomically: into a temporary file in the same folder, then renamed
/// over `file`, so a reader never sees a half-written file. Creates missing parent folders.
/// Throws InputError naming the file when it cannot be written.
void write_file_atomically(const std::filesystem::path& file, const std::string& content);

/// The items separated by `separator`.
std::string join(const std::vector<std::string>& items, const std::string& separator);

/// s in upper case (ASCII).
std::string upper_case(std::string s);

/// The value of `text` when the WHOLE text is one finite number (std::stod syntax), else nullopt.
std::optional<double> parse_finite_number(const std::string& text);

/// Shortest decimal text that reads back to exactly `x` (std::to_chars round trip).
std::string format_double(double x);
/// File-name safe form of a set name: letters, digits, '-' and '_' kept, anything else '_'.
std::string file_safe_name(const std::string& name);

/// `x` formatted by a printf conversion for one double, e.g. format_with("%.4g", x) (at most 63 chars).
std::string format_with(const char* printf_format, double x);

}  // namespace cushion::io
