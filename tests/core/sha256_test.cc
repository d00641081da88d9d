// SHA-256 digests against the FIPS 180-4 examples and coreutils' sha256sum.
#include "core/sha256.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <string_view>

#include "core/error.h"

namespace flexmbs {
namespace {

std::string DigestOf(std::string_view text) {
  return Sha256Hex(std::as_bytes(std::span(text.data(), text.size())));
}

TEST(Sha256, MatchesTheFipsExamples) {
  EXPECT_EQ(DigestOf(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(DigestOf("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(DigestOf("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
}

TEST(Sha256, FileDigestEqualsSha256sum) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / fmt::format("flexmbs_sha256_test_{}.bin", getpid());
  {
    std::ofstream out(path, std::ios::binary);
    for (int i = 0; i < 200000; ++i) out.put(static_cast<char>(i * 7919 % 251));
  }
  std::array<char, 65> expected{};
  FILE* pipe = popen(fmt::format("sha256sum '{}'", path.string()).c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  ASSERT_EQ(std::fread(expected.data(), 1, 64, pipe), 64u);
  pclose(pipe);
  EXPECT_EQ(Sha256OfFile(path), std::string(expected.data(), 64));
  std::filesystem::remove(path);
}

TEST(Sha256, MissingFileIsAnInputErrorNamingIt) {
  try {
    Sha256OfFile("/nonexistent/body.geo");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "/nonexistent/body.geo: cannot be read");
  }
}

}  // namespace
}  // namespace flexmbs
