#pragma once
// Writing the harness's output files: every failure (unwritable folder, full disk) is an error
// naming the path and the reason, never a silently missing or truncated file.

#include <string>

namespace modalbench {

/// Creates `dir` and its parents if needed; throws std::runtime_error naming the path and the
/// reason if that fails or `dir` is not a writable folder.
void make_output_dir(const std::string& dir);

/// Writes `content` to `path` (replacing it); throws std::runtime_error naming the path and the
/// reason if the file cannot be opened, written completely, or closed.
void write_text_file(const std::string& path, const std::string& content);

}  // namespace modalbench
