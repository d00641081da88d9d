#include "core/xxh3.h"

#include <fmt/format.h>
#include <xxhash.h>
#if defined(__x86_64__)
#include <xxh_x86dispatch.h>  // XXH3_128bits_update -> the dispatching variant (AVX2 where present)
#endif

#include "core/error.h"

namespace flexmbs {
namespace {

void FreeState(XXH3_state_s* state) { XXH3_freeState(state); }

}  // namespace

Xxh3_128::Xxh3_128() : state_(XXH3_createState(), FreeState) {
  FLEXMBS_CHECK(state_ && XXH3_128bits_reset(state_.get()) == XXH_OK, "libxxhash could not start an XXH3 hash");
}

void Xxh3_128::Update(const void* data, std::size_t size) {
  FLEXMBS_CHECK(XXH3_128bits_update(state_.get(), data, size) == XXH_OK, "libxxhash XXH3 update failed");
}

std::string Xxh3_128::HexDigest() const {
  XXH128_canonical_t canonical;
  XXH128_canonicalFromHash(&canonical, XXH3_128bits_digest(state_.get()));
  std::string hex;
  for (const unsigned char byte : canonical.digest) hex += fmt::format("{:02x}", byte);
  return hex;
}

std::string Xxh3_128Hex(std::span<const std::byte> bytes) {
  Xxh3_128 hash;
  hash.Update(bytes.data(), bytes.size());
  return hash.HexDigest();
}

}  // namespace flexmbs
