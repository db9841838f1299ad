#include "io/output_folder.hpp"

#include <unistd.h>

#include <algorithm>
#include <system_error>

#include "io/input_error.hpp"

namespace cushion::io {

namespace fs = std::filesystem;

namespace {

fs::path absolute_normal(const fs::path& p) {
  std::error_code ec;
  const fs::path a = fs::absolute(p, ec);
  return (ec ? p : a).lexically_normal();
}

/// The absolute, normal form of `p` with symbolic links resolved where they exist, and no trailing separator.
fs::path resolved(const fs::path& p) {
  std::error_code ec;
  fs::path r = fs::weakly_canonical(p, ec);
  if (ec) r = absolute_normal(p);
  return r.has_filename() ? r : r.parent_path();
}

/// True if `path` is `dir` or lies below it.
bool lies_inside(const fs::path& path, const fs::path& dir) {
  const fs::path rel = resolved(path).lexically_relative(resolved(dir));
  return !rel.empty() && *rel.begin() != "..";
}

bool writable(const fs::path& dir) { return ::access(dir.c_str(), W_OK | X_OK) == 0; }

/// The nearest existing path at or above `p` (the current folder for a relative path with no existing part).
fs::path nearest_existing(const fs::path& p) {
  std::error_code ec;
  for (fs::path q = absolute_normal(p); !q.empty(); q = q.parent_path()) {
    if (fs::exists(fs::symlink_status(q, ec))) return q;
    if (q == q.parent_path()) break;
  }
  return fs::current_path(ec);
}

struct Refusal {
  const OutputFolder& f;
  [[noreturn]] void operator()(const std::string& problem) const {
    throw InputError(f.dir.string() + ": " + f.option + ": " + problem);
  }
};

void check_overwrite_allowed(const OutputFolder& f, const Refusal& refuse) {
  if (!f.overwrite)
    refuse("the folder exists and is not empty; pass --overwrite to replace its content, or choose another folder");
  std::error_code ec;
  if (lies_inside(fs::current_path(ec), f.dir))
    refuse("--overwrite refused: it is the current folder or a folder above it; choose another folder");
  for (const fs::path& input : f.inputs)
    if (!input.empty() && lies_inside(input, f.dir))
      refuse("--overwrite refused: the folder holds the input '" + input.string() + "'; choose another folder");
  const bool earlier = std::any_of(f.markers.begin(), f.markers.end(),
                                   [&](const std::string& m) { return fs::exists(f.dir / m, ec); });
  if (!earlier)
    refuse("--overwrite refused: the folder holds no earlier `" + f.command + "` output (no " +
           (f.markers.empty() ? std::string("marker file") : f.markers.front()) + "); choose another folder");
}

}  // namespace

void check_output_folder(const OutputFolder& f) {
  const Refusal refuse{f};
  std::error_code ec;
  const fs::file_status status = fs::status(f.dir, ec);
  if (!fs::exists(status)) {
    const fs::path parent = nearest_existing(f.dir);
    if (!fs::is_directory(parent, ec)) refuse("cannot create the folder: '" + parent.string() + "' is a file, not a folder");
    if (!writable(parent)) refuse("cannot create the folder: '" + parent.string() + "' is not writable");
    return;
  }
  if (!fs::is_directory(status)) refuse("exists and is a file, not a folder");
  if (!f.append && !fs::is_empty(f.dir, ec)) check_overwrite_allowed(f, refuse);
  if (!writable(f.dir)) refuse("the folder is not writable (permission denied)");
  if (f.staged_next_to_it && !writable(absolute_normal(f.dir).parent_path()))
    refuse("the folder above it is not writable (the outputs are written next to it first, then renamed)");
}

void prepare_output_folder(const OutputFolder& f) {
  check_output_folder(f);
  std::error_code ec;
  if (f.overwrite && fs::is_directory(f.dir, ec))
    for (const auto& entry : fs::directory_iterator(f.dir, ec)) {
      fs::remove_all(entry.path(), ec);
      if (ec) Refusal{f}("cannot remove '" + entry.path().string() + "': " + ec.message());
    }
  create_folder(f.dir);
}

void require_input_folder(const fs::path& dir, const std::string& option) {
  std::error_code ec;
  const fs::file_status status = fs::status(dir, ec);
  if (!fs::exists(status)) throw InputError(dir.string() + ": " + option + ": no such folder");
  if (!fs::is_directory(status)) throw InputError(dir.string() + ": " + option + ": is a file, not a folder");
}

void create_folder(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError(dir.string() + ": cannot create the folder: " + ec.message());
}

void replace_folder(const fs::path& staged, const fs::path& dir) {
  std::error_code ec;
  fs::remove_all(dir, ec);
  if (!ec) fs::rename(staged, dir, ec);
  if (ec) throw InputError(dir.string() + ": cannot replace the folder by '" + staged.string() + "': " + ec.message());
}

}  // namespace cushion::io
