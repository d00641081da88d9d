#pragma once

#include <cstddef>
#include <memory>
#include <span>
#include <string>

struct XXH3_state_s;

namespace flexmbs {

/// An XXH3 128-bit hash (xxHash 0.8, Debian's libxxhash; on x86-64 its run-time dispatch picks
/// the widest vector unit) fed piece by piece. A fast hash that detects damage (any change of
/// the input changes it but with probability 2^-128 for damage unrelated to the hash), not a
/// cryptographic one: it does not withstand someone who crafts a change to keep it (docs/sid.md,
/// "Content digest").
class Xxh3_128 {
 public:
  Xxh3_128();
  /// Adds `size` bytes at `data` to the hash.
  void Update(const void* data, std::size_t size);
  /// The hash of everything added so far as 32 lower-case hex digits, in the canonical
  /// (big-endian) form `xxhsum -H2` prints; more can be added afterwards.
  std::string HexDigest() const;

 private:
  std::unique_ptr<XXH3_state_s, void (*)(XXH3_state_s*)> state_;
};

/// The XXH3 128-bit hash of `bytes` as 32 lower-case hex digits (Xxh3_128::HexDigest).
std::string Xxh3_128Hex(std::span<const std::byte> bytes);

}  // namespace flexmbs
