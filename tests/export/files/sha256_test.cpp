// export/files/sha256.h against the FIPS 180-4 examples and against sha256sum (an independent
// reader).
#include "export/files/sha256.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
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
