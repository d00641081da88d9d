#pragma once
// The content digest of a reduced body (docs/sid.md, "Content digest"): a hash over every value
// the simulator reads, written by `flexmbs reduce` as a root attribute and recomputed by the
// reader, so that a damaged or hand-edited body is named as such. Schema 5 hashes with
// XXH3-128 (attribute `content_xxh3_128`), schema 4 with SHA-256 (`content_sha256`).

#include <string>

#include "sid/reduced_body.h"

namespace flexmbs::sid {

/// The hash a content digest is computed with.
enum class DigestAlgorithm {
  kSha256,    ///< SHA-256 (FIPS 180-4), 64 hex digits: schema 4
  kXxh3_128,  ///< XXH3-128 (xxHash 0.8), 32 hex digits: schema 5
};

/// The hash of `algorithm` over every field of `body` but its provenance, in a fixed order:
/// each name or string with its length, each matrix with its dims and its doubles bit for bit,
/// each index list as 64-bit integers; marker nodes and surfaces in the order of their names.
/// Equal for a body and its exact round trip through a file.
std::string ContentDigest(const ReducedBody& body, DigestAlgorithm algorithm = DigestAlgorithm::kXxh3_128);

}  // namespace flexmbs::sid
