#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <span>
#include <string>

struct evp_md_ctx_st;

namespace flexmbs {

/// A SHA-256 digest (FIPS 180-4, OpenSSL's libcrypto) fed piece by piece.
class Sha256 {
 public:
  Sha256();
  /// Adds `size` bytes at `data` to the digest.
  void Update(const void* data, std::size_t size);
  /// The digest of everything added, as 64 lower-case hex digits. Call once.
  std::string HexDigest();

 private:
  std::unique_ptr<evp_md_ctx_st, void (*)(evp_md_ctx_st*)> context_;
};

/// The SHA-256 digest (FIPS 180-4) of `bytes` as 64 lower-case hex digits (OpenSSL's libcrypto).
std::string Sha256Hex(std::span<const std::byte> bytes);

/// The SHA-256 digest of a file's content. Throws InputError naming `path` if it cannot be read.
std::string Sha256OfFile(const std::filesystem::path& path);

}  // namespace flexmbs
