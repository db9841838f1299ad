#pragma once
/// The output-folder policy of the cushion commands (`-o DIR`), checked before any computation:
///  - DIR missing: it will be created; its nearest existing parent must be a writable folder.
///  - DIR an empty folder: used as it is (it must be writable).
///  - DIR a non-empty folder: refused unless `--overwrite`; with it, only a folder that holds an earlier
///    output of the same command (a `marker` file) and no input of this command, and that is not the
///    current folder or one above it; its whole content is then replaced by the new outputs.
///  - DIR a file: refused.
/// Every refusal is an InputError "<DIR>: <option>: <problem>"; nothing is written by the check.
#include <filesystem>
#include <string>
#include <vector>

namespace cushion::io {

struct OutputFolder {
  std::filesystem::path dir;
  bool overwrite = false;
  std::string command;                      ///< e.g. "cushion run", for messages
  std::vector<std::string> markers;         ///< files of an earlier output of the command (any one of them)
  std::vector<std::filesystem::path> inputs;  ///< input files and folders of the command (never deleted)
  bool staged_next_to_it = false;           ///< outputs written to DIR.partial, then renamed: the parent must be writable
  bool append = false;                      ///< outputs added to what DIR holds (compare --history): never refused as non-empty
  std::string option = "--output";
};

/// Throws InputError unless `folder` can take the command's outputs (see the file comment). Writes nothing.
void check_output_folder(const OutputFolder& folder);

/// check_output_folder, then (with overwrite) removes the folder's content and creates the folder (with
/// missing parents). Call just before the first output is written. InputError naming DIR if it fails.
void prepare_output_folder(const OutputFolder& folder);

/// Throws InputError "<dir>: <option>: no such folder" or "...: is a file, not a folder" unless `dir` is an
/// existing folder (an input folder, e.g. `compare --run DIR`).
void require_input_folder(const std::filesystem::path& dir, const std::string& option);

/// Creates `dir` and its missing parents; InputError "<dir>: cannot create the folder: <reason>" if it fails.
void create_folder(const std::filesystem::path& dir);

/// Replaces `dir` by the finished folder `staged` (DIR.partial): removes `dir`, renames `staged` to it.
/// InputError naming `dir` if the rename fails (e.g. the parent is not writable).
void replace_folder(const std::filesystem::path& staged, const std::filesystem::path& dir);

}  // namespace cushion::io
