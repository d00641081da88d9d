#include "core/sha256.h"

#include <openssl/evp.h>

#include <array>
#include <fmt/format.h>
#include <fstream>
#include <memory>

#include "core/error.h"

namespace flexmbs {

Sha256::Sha256() : context_(EVP_MD_CTX_new(), EVP_MD_CTX_free) {
  FLEXMBS_CHECK(context_ && EVP_DigestInit_ex(context_.get(), EVP_sha256(), nullptr) == 1,
                "OpenSSL could not start a SHA-256 digest");
}

void Sha256::Update(const void* data, std::size_t size) {
  FLEXMBS_CHECK(EVP_DigestUpdate(context_.get(), data, size) == 1, "OpenSSL SHA-256 update failed");
}

std::string Sha256::HexDigest() {
  std::array<unsigned char, EVP_MAX_MD_SIZE> digest{};
  unsigned int length = 0;
  FLEXMBS_CHECK(EVP_DigestFinal_ex(context_.get(), digest.data(), &length) == 1, "OpenSSL SHA-256 final failed");
  std::string hex;
  for (unsigned int i = 0; i < length; ++i) hex += fmt::format("{:02x}", digest[i]);
  return hex;
}

std::string Sha256Hex(std::span<const std::byte> bytes) {
  Sha256 sha;
  sha.Update(bytes.data(), bytes.size());
  return sha.HexDigest();
}

std::string Sha256OfFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot be read", path.string()));
  Sha256 sha;
  std::array<char, 1 << 16> buffer{};
  while (in.read(buffer.data(), buffer.size()) || in.gcount() > 0) {
    sha.Update(buffer.data(), static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) throw InputError(fmt::format("{}: read error", path.string()));
  return sha.HexDigest();
}

}  // namespace flexmbs
