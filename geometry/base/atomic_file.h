#pragma once
// Writing output files so that an interrupted run never leaves a half-written file: the content
// goes to "<path>.tmp.<pid>" in the same directory and is renamed over <path> only once it is
// complete and flushed (rename is atomic within a file system).
#include <filesystem>
#include <functional>
#include <ostream>
#include <string>

namespace windplan {

/// Calls write(stream) on a temporary file beside `path`, then renames it to `path`.
/// Parent directories are created. On any failure the temporary file is removed.
/// \throw IoError naming the path when the file cannot be created, written or renamed.
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write, bool binary = false);

/// Convenience: writes a whole string atomically.
void write_text_atomically(const std::filesystem::path& path, const std::string& text);

/// Reads a whole regular file of at most kCsvFileCap bytes (geometry/base/input_file.h).
/// \throw IoError if it is missing, unreadable, a directory or special file, or too large.
std::string read_text_file(const std::filesystem::path& path);

}  // namespace windplan
