#pragma once
// The broad phase of the Polygonal Contact Model (docs/contact.md, "Polygonal Contact Model"):
// the face pairs of two meshes whose (swept) boxes overlap, by descending both
// hierarchies together.

#include <vector>

#include "contact/pcm/bvh.h"

namespace flexmbs::contact {

/// A face of mesh A and a face of mesh B.
struct FacePair {
  int face_A = 0;
  int face_B = 0;
  friend bool operator==(const FacePair&, const FacePair&) = default;
  friend auto operator<=>(const FacePair&, const FacePair&) = default;
};

/// Every pair (a, b) with a's box in `A` overlapping b's box in `B` (Bvh::face_boxes(), each
/// swept by its tree's depth), each once, in no particular order: the tree-vs-tree descent
/// (the node with the larger box is opened first) ending in face-box tests at leaf pairs.
std::vector<FacePair> CandidatePairs(const Bvh& A, const Bvh& B);

}  // namespace flexmbs::contact
