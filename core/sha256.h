#pragma once

#include <filesystem>
#include <span>
#include <string>

namespace flexmbs {

/// The SHA-256 digest (FIPS 180-4) of `bytes` as 64 lower-case hex digits (OpenSSL's libcrypto).
std::string Sha256Hex(std::span<const std::byte> bytes);

/// The SHA-256 digest of a file's content. Throws InputError naming `path` if it cannot be read.
std::string Sha256OfFile(const std::filesystem::path& path);

}  // namespace flexmbs
