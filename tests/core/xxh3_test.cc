// XXH3-128 hashes against xxHash's own command-line tool, xxhsum -H2 (package xxhash).
#include "core/xxh3.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <fmt/format.h>
#include <string>
#include <string_view>
#include <vector>

namespace flexmbs {
namespace {

std::string HashOf(std::string_view text) { return Xxh3_128Hex(std::as_bytes(std::span(text.data(), text.size()))); }

/// The 32 hex digits `xxhsum -H2` prints for the output of the shell command `source`.
std::string XxhsumOf(const std::string& source) {
  FILE* pipe = popen(fmt::format("{} | xxhsum -H2", source).c_str(), "r");
  EXPECT_NE(pipe, nullptr);
  if (pipe == nullptr) return "";
  char digits[33] = {};
  const std::size_t got = std::fread(digits, 1, 32, pipe);
  pclose(pipe);
  return std::string(digits, got);
}

TEST(Xxh3_128, EqualsXxhsumOnShortInputs) {
  EXPECT_EQ(XxhsumOf("printf ''"), "99aa06d3014798d86001c324468d497f");
  EXPECT_EQ(HashOf(""), XxhsumOf("printf ''"));
  EXPECT_EQ(HashOf("abc"), XxhsumOf("printf abc"));
  EXPECT_EQ(HashOf("a flexible body, reduced"), XxhsumOf("printf 'a flexible body, reduced'"));
}

// 200 kB (past XXH3's 240-byte short path and its 1 KiB stripes' blocks), fed in uneven pieces:
// the streamed hash equals the one-shot hash and xxhsum's.
TEST(Xxh3_128, StreamedInPiecesEqualsXxhsumOnALongInput) {
  std::vector<std::byte> bytes(200000);
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<std::byte>(i * 7919 % 251);
  Xxh3_128 streamed;
  for (std::size_t start = 0, piece = 1; start < bytes.size(); start += piece, piece = piece * 3 + 1) {
    streamed.Update(bytes.data() + start, std::min(piece, bytes.size() - start));
  }
  const std::string so_far = streamed.HexDigest();
  EXPECT_EQ(so_far, Xxh3_128Hex(bytes));
  EXPECT_EQ(streamed.HexDigest(), so_far);  // asking does not end the hash
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / fmt::format("flexmbs_xxh3_test_{}.bin", getpid());
  {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  }
  EXPECT_EQ(so_far, XxhsumOf(fmt::format("cat '{}'", path.string())));
  std::filesystem::remove(path);
  streamed.Update(bytes.data(), 1);
  EXPECT_NE(streamed.HexDigest(), so_far);
}

}  // namespace
}  // namespace flexmbs
