#pragma once
// SHA-256 (FIPS 180-4) of files and strings, for the output manifest (export/files/manifest.h): a
// shop checks a set with `sha256sum` before loading a program. Small and self-contained so that
// windplan needs no crypto library; verified against the FIPS test vectors and sha256sum. On x86
// processors with the SHA extensions (Intel since 2016-2019, AMD since Zen) the blocks go
// through the sha256rnds2 / sha256msg instructions, about 8x faster (1,450 against 140-175 MB/s
// on 103 MB; a job's files are hashed after they are written: 150 MB for vessel_unequal);
// elsewhere through portable code.
#include <cstdint>
#include <filesystem>
#include <string>

namespace windplan {

/// Incremental SHA-256.
class Sha256 {
 public:
  /// \param hardware use the processor's SHA instructions where it has them (the same digest)
  explicit Sha256(bool hardware = true);
  /// Whether this processor has the SHA instructions Sha256 uses.
  static bool hardware_available();
  void update(const void* data, std::size_t size);
  /// The digest as 64 lower-case hex digits; the object is spent afterwards.
  std::string hex_digest();

 private:
  void blocks(const unsigned char* p, std::size_t n);  // n whole 64-byte blocks
  void block(const unsigned char* p);                   // one, portable
  bool hardware_;
  std::uint32_t h_[8];
  unsigned char buf_[64];
  std::size_t buf_len_ = 0;
  std::uint64_t total_ = 0;
};

/// SHA-256 of a string, hex.
std::string sha256_hex(const std::string& data);

/// SHA-256 of a file's bytes, hex. \throw IoError if it cannot be read.
std::string sha256_file(const std::filesystem::path& path);

}  // namespace windplan
