#include "contact/pcm/candidate_pairs.h"

#include <utility>

namespace flexmbs::contact {

std::vector<FacePair> CandidatePairs(const Bvh& A, const Bvh& B) {
  std::vector<FacePair> pairs;
  const std::vector<BvhNode>& nodes_A = A.nodes();
  const std::vector<BvhNode>& nodes_B = B.nodes();
  std::vector<std::pair<int, int>> stack{{0, 0}};
  while (!stack.empty()) {
    const auto [a, b] = stack.back();
    stack.pop_back();
    const BvhNode& node_A = nodes_A[a];
    const BvhNode& node_B = nodes_B[b];
    if (!node_A.box.Overlaps(node_B.box)) continue;
    const bool leaf_A = node_A.count > 0, leaf_B = node_B.count > 0;
    if (leaf_A && leaf_B) {
      for (int i = node_A.first; i < node_A.first + node_A.count; ++i) {
        const int face_A = A.faces()[i];
        const Aabb& box_A = A.face_boxes()[face_A];
        for (int j = node_B.first; j < node_B.first + node_B.count; ++j) {
          const int face_B = B.faces()[j];
          if (box_A.Overlaps(B.face_boxes()[face_B])) pairs.push_back({face_A, face_B});
        }
      }
    } else if (leaf_B || (!leaf_A && node_A.box.SurfaceArea() >= node_B.box.SurfaceArea())) {
      stack.emplace_back(a + 1, b);
      stack.emplace_back(node_A.first, b);
    } else {
      stack.emplace_back(a, b + 1);
      stack.emplace_back(a, node_B.first);
    }
  }
  return pairs;
}

}  // namespace flexmbs::contact
