#include "contact/pcm/nearest_face.h"

#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

#include "core/error.h"

namespace flexmbs::contact {
namespace {

/// The squared distance from p to a box [m^2] (0 inside).
double SquaredDistance(const Eigen::Vector3d& p, const Aabb& box) {
  const Eigen::Vector3d outside = (box.lo - p).cwiseMax(p - box.hi).cwiseMax(0.0);
  return outside.squaredNorm();
}

}  // namespace

MeshPoint NearestMeshPoint(const Eigen::Vector3d& p, const PolygonMesh& mesh, const Bvh& tree) {
  FLEXMBS_CHECK(tree.face_offsets().size() == mesh.face_sizes.size() && !tree.nodes().empty(),
                "NearestMeshPoint: a tree of the mesh's faces");
  MeshPoint best;
  int best_face = -1;
  double best_distance = std::numeric_limits<double>::infinity();
  const auto farther = [&](double squared) {
    return squared > best_distance * best_distance * (1.0 + 1e-12);
  };
  // Nodes still to visit with their boxes' squared distances; depth-first, so at most one pending
  // sibling per level of the tree.
  std::vector<std::pair<int, double>> stack;
  stack.reserve(64);
  stack.emplace_back(0, SquaredDistance(p, tree.nodes()[0].box));
  while (!stack.empty()) {
    const auto [index, squared] = stack.back();
    stack.pop_back();
    if (farther(squared)) continue;
    const BvhNode& node = tree.nodes()[static_cast<std::size_t>(index)];
    if (node.count > 0) {
      for (int k = node.first; k < node.first + node.count; ++k) {
        const int face = tree.faces()[static_cast<std::size_t>(k)];
        const MeshPoint candidate =
            NearestFacePoint(p, mesh, static_cast<std::size_t>(tree.face_offsets()[static_cast<std::size_t>(face)]),
                             mesh.face_sizes[static_cast<std::size_t>(face)]);
        const double distance = (p - candidate.point).norm();
        if (distance < best_distance || (distance == best_distance && face < best_face)) {
          best_distance = distance;
          best_face = face;
          best = candidate;
        }
      }
      continue;
    }
    const int left = index + 1, right = node.first;
    const double d_left = SquaredDistance(p, tree.nodes()[static_cast<std::size_t>(left)].box);
    const double d_right = SquaredDistance(p, tree.nodes()[static_cast<std::size_t>(right)].box);
    // The nearer child on top, visited first.
    if (d_left <= d_right) {
      stack.emplace_back(right, d_right);
      stack.emplace_back(left, d_left);
    } else {
      stack.emplace_back(left, d_left);
      stack.emplace_back(right, d_right);
    }
  }
  FLEXMBS_CHECK(best_face >= 0, "NearestMeshPoint: a mesh without faces");
  return best;
}

}  // namespace flexmbs::contact
