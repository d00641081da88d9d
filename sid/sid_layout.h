#pragma once
// Names and units of the `.sid.h5` layout (docs/sid.md), shared by the writer and the reader
// so the two cannot drift apart. Internal to the sid module.

#include <array>
#include <string_view>

#include "sid/reduced_body.h"
#include "sid/sid_digest.h"

namespace flexmbs::sid::layout {

/// The units of a Taylor block's m0, m1 and m2 ("q" is the unit of a modal coordinate).
struct TaylorUnits {
  std::string_view m0, m1, m2;
};

/// One SID invariant: its name in /invariants, its member of ReducedBody and its units.
struct InvariantField {
  std::string_view name;
  TaylorMatrix ReducedBody::*member;
  TaylorUnits units;
};

inline constexpr std::array<InvariantField, 11> kInvariants{{
    {"mdCM", &ReducedBody::mdCM, {"kg m", "kg m/q", ""}},
    {"J", &ReducedBody::J, {"kg m^2", "kg m^2/q", "kg m^2/q^2"}},
    {"Ct", &ReducedBody::Ct, {"kg m/q", "kg m/q^2", ""}},
    {"Cr", &ReducedBody::Cr, {"kg m^2/q", "kg m^2/q^2", ""}},
    {"Me", &ReducedBody::Me, {"kg m^2/q^2", "", ""}},
    {"Gr", &ReducedBody::Gr, {"kg m^2/q", "kg m^2/q^2", ""}},
    {"Ge", &ReducedBody::Ge, {"kg m^2/q^2", "", ""}},
    {"Oe", &ReducedBody::Oe, {"kg m^2/q", "kg m^2/q^2", ""}},
    {"Ke", &ReducedBody::Ke, {"N m/q^2", "", ""}},
    {"De", &ReducedBody::De, {"N m s/q^2", "", ""}},
    {"ksigma", &ReducedBody::ksigma, {"N m/q", "", ""}},
}};

/// The node Taylor blocks: name in /nodes/<node>, member of Node, units.
struct NodeField {
  std::string_view name;
  TaylorMatrix Node::*member;
  TaylorUnits units;
};

inline constexpr std::array<NodeField, 4> kNodeFields{{
    {"origin", &Node::origin, {"m", "m/q", ""}},
    {"phi", &Node::phi, {"m/q", "m/q^2", ""}},
    {"psi", &Node::psi, {"1/q", "1/q^2", ""}},
    {"AP", &Node::AP, {"1", "1/q", ""}},
}};

/// The root attribute holding the body's content digest (sid_digest.h) and its hash, by schema.
struct ContentDigestField {
  std::string_view attribute;
  DigestAlgorithm algorithm;
};

/// The content digest of a file of `schema_version` (4: SHA-256, 5 on: XXH3-128).
constexpr ContentDigestField ContentDigestOf(int schema_version) {
  return schema_version <= 4 ? ContentDigestField{"content_sha256", DigestAlgorithm::kSha256}
                             : ContentDigestField{"content_xxh3_128", DigestAlgorithm::kXxh3_128};
}

/// The stiffening matrices in /stiffening: dataset name suffixes and units per load case.
inline constexpr std::array<std::string_view, 3> kAxes{"x", "y", "z"};
inline constexpr std::array<std::string_view, 6> kOmegaProducts{"xx", "yy", "zz", "xy", "yz", "zx"};
inline constexpr std::string_view kK0tUnits = "kg m/q^2";
inline constexpr std::string_view kK0rUnits = "kg m^2/q^2";
inline constexpr std::string_view kK0omegaUnits = "kg m^2/q^2";

}  // namespace flexmbs::sid::layout
