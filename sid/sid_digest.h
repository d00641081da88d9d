#pragma once
// The content digest of a reduced body (docs/sid.md, "Content digest"): SHA-256 over every
// value the simulator reads, written by `flexmbs reduce` as the root attribute `content_sha256`
// and recomputed by the reader, so that a damaged or hand-edited body is named as such.

#include <string>

#include "sid/reduced_body.h"

namespace flexmbs::sid {

/// SHA-256 (64 hex digits) over every field of `body` but its provenance, in a fixed order:
/// each name or string with its length, each matrix with its dims and its doubles bit for bit,
/// each index list as 64-bit integers; marker nodes and surfaces in the order of their names.
/// Equal for a body and its exact round trip through a file.
std::string ContentDigest(const ReducedBody& body);

}  // namespace flexmbs::sid
