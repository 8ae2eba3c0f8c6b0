// export/files/sha256.h against the FIPS 180-4 examples and against sha256sum (an independent
// reader), through the processor's SHA instructions and through the portable code.
#include "export/files/sha256.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <string>

namespace windplan {
namespace {

TEST(Sha256, FipsExamples) {
  EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  Sha256 h;  // one million 'a', fed in uneven pieces
  const std::string chunk(997, 'a');
  std::size_t left = 1000000;
  while (left > 0) {
    const std::size_t n = std::min(left, chunk.size());
    h.update(chunk.data(), n);
    left -= n;
  }
  EXPECT_EQ(h.hex_digest(), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

std::string digest(const std::string& data, bool hardware, std::size_t piece) {
  Sha256 h(hardware);
  for (std::size_t at = 0; at < data.size(); at += piece)
    h.update(data.data() + at, std::min(piece, data.size() - at));
  return h.hex_digest();
}

TEST(Sha256, PortableCodeGivesTheFipsDigests) {
  EXPECT_EQ(digest("abc", false, 1),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(digest(std::string(1000000, 'a'), false, 4099),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST(Sha256, ShaInstructionsAgreeWithThePortableCode) {
  if (!Sha256::hardware_available()) {
    GTEST_SKIP() << "this processor has no SHA instructions: only the portable code runs";
  }
  EXPECT_EQ(digest("abc", true, 1),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  // Every length across the padding's edges (55, 56, 63, 64 bytes ...), whole and in pieces
  // that straddle blocks, and a megabyte of random bytes.
  std::mt19937 rng(7);
  std::string data(300, '\0');
  for (char& c : data) c = static_cast<char>(rng());
  for (std::size_t n = 0; n <= data.size(); ++n) {
    const std::string d = data.substr(0, n);
    EXPECT_EQ(digest(d, true, 1000), digest(d, false, 1000)) << n << " bytes";
    EXPECT_EQ(digest(d, true, 37), digest(d, false, 1000)) << n << " bytes in pieces of 37";
  }
  std::string mb(1 << 20, '\0');
  for (char& c : mb) c = static_cast<char>(rng());
  EXPECT_EQ(digest(mb, true, 65521), digest(mb, false, 64));
}

TEST(Sha256, FileAgreesWithSha256sum) {
  const std::filesystem::path p =
      std::filesystem::temp_directory_path() / "windplan_sha256_test.bin";
  {
    std::ofstream out(p, std::ios::binary);
    for (int i = 0; i < 200000; ++i) out.put(static_cast<char>((i * 7919) & 255));
  }
  std::string line(64, '\0');
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(("sha256sum '" + p.string() + "'").c_str(), "r"),
                                             pclose);
  ASSERT_TRUE(pipe);
  ASSERT_EQ(std::fread(line.data(), 1, 64, pipe.get()), 64u);
  EXPECT_EQ(sha256_file(p), line);
  std::filesystem::remove(p);
}

}  // namespace
}  // namespace windplan
