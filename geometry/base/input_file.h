#pragma once
// Reading a user's input file safely: only a regular file of bounded size, read once (issue 28:
// a job, profile, program or pairs file that was /dev/zero grew to GBs, a FIFO blocked forever,
// a directory gave "Operation not supported" or "empty file").
//
// - The file is opened without blocking (a FIFO with no writer does not hang the open), then
//   fstat'ed: a directory, FIFO, character device (/dev/zero, a terminal), block device or
//   socket is refused at once, named as such; a regular file above `cap` bytes is refused with
//   its size and the bound. Symbolic links are followed (to a regular file they are fine).
// - The bytes are read from that same descriptor, at most cap + 1 of them (a file that grows
//   past the bound while read is refused too).
// The caps of windplan's readers (documented in docs/bad_inputs.md):
#include <cstdint>
#include <filesystem>
#include <string>

namespace windplan {

constexpr std::uintmax_t kMiB = 1024 * 1024;
constexpr std::uintmax_t kJobFileCap = 16 * kMiB;        ///< a job file (YAML)
constexpr std::uintmax_t kCsvFileCap = 256 * kMiB;       ///< a profile or cut-line CSV, pairs
constexpr std::uintmax_t kProgramFileCap = 1024 * kMiB;  ///< a G-code program for simulate
constexpr std::uintmax_t kMeshFileCap = 4096 * kMiB;     ///< a mesh (OBJ/OFF/PLY/STL)
constexpr std::uintmax_t kCadFileCap = 2048 * kMiB;      ///< a STEP/IGES/BREP model

/// Checks that `path` is a regular file of at most `cap` bytes and returns its size.
/// `what` names the expected content in messages ("a job file", "a mesh file").
/// \throw IoError "<path>: is a FIFO (named pipe), not a file; give a job file" and the like.
std::uintmax_t check_input_file(const std::filesystem::path& path, std::uintmax_t cap,
                                const std::string& what);

/// Reads the whole regular file `path` of at most `cap` bytes. \throw IoError as above.
std::string read_input_file(const std::filesystem::path& path, std::uintmax_t cap,
                            const std::string& what);

/// "20005 bytes", "15.2 MB", "4.295 GB": a byte count for messages (exact below 10 MB).
std::string byte_size_text(std::uintmax_t bytes);

}  // namespace windplan
