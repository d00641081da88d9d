// contact/pcm/bvh.h and candidate_pairs.h: the tree-vs-tree candidate pairs equal a brute-force
// test of all face-box pairs on random, spherical and deformed meshes, a refitted tree finds
// the same pairs as a rebuilt one, and the degradation measure sees what refitting costs.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "contact/pcm/bvh.h"
#include "contact/pcm/candidate_pairs.h"
#include "tests/contact/pcm_meshes.h"

namespace flexmbs::contact {
namespace {

using testing::FlatGrid;
using testing::Icosphere;
using testing::RandomTriangles;
using testing::Wave;

/// Every face pair whose boxes (each swept by its depth) overlap, by testing all pairs.
std::vector<FacePair> BruteForcePairs(const PolygonMesh& A, double depth_A, const PolygonMesh& B, double depth_B) {
  const auto offsets = [](const PolygonMesh& mesh) {
    std::vector<int> result;
    int offset = 0;
    for (const int size : mesh.face_sizes) {
      result.push_back(offset);
      offset += size;
    }
    return result;
  };
  const std::vector<int> offsets_A = offsets(A), offsets_B = offsets(B);
  std::vector<FacePair> pairs;
  for (int a = 0; a < static_cast<int>(A.face_sizes.size()); ++a) {
    const Aabb box_A = FaceBox(A, offsets_A, a, depth_A);
    for (int b = 0; b < static_cast<int>(B.face_sizes.size()); ++b) {
      if (box_A.Overlaps(FaceBox(B, offsets_B, b, depth_B))) pairs.push_back({a, b});
    }
  }
  return pairs;
}

std::vector<FacePair> Sorted(std::vector<FacePair> pairs) {
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

TEST(PcmBvh, CandidatePairsOfRandomSoupsEqualTheBruteForcePairsForEveryLeafSizeDepthAndSplit) {
  const PolygonMesh A = RandomTriangles(700, 1.0, 0.08, 1), B = RandomTriangles(500, 1.0, 0.1, 2);
  for (const BvhSplit split : {BvhSplit::kMedian, BvhSplit::kSurfaceArea}) {
    for (const int leaf_size : {1, 2, 5}) {
      for (const double depth : {0.0, 0.02}) {
        const std::vector<FacePair> expected = BruteForcePairs(A, depth, B, 0.0);
        ASSERT_GT(expected.size(), 100u);  // the soups touch in many places
        const std::vector<FacePair> found =
            CandidatePairs(Bvh(A, depth, leaf_size, split), Bvh(B, 0.0, leaf_size, split));
        EXPECT_EQ(found.size(), expected.size()) << "no pair twice; leaf size " << leaf_size << ", depth " << depth;
        EXPECT_EQ(Sorted(found), expected) << "leaf size " << leaf_size << ", depth " << depth;
      }
    }
  }
}

TEST(PcmBvh, CandidatePairsOfASpherePressedIntoAFlatEqualTheBruteForcePairs) {
  const PolygonMesh sphere = Icosphere(Eigen::Vector3d(0.1, -0.05, 0.9), 1.0, 3);
  const PolygonMesh flat = FlatGrid(1.5, 12, 0.0);
  const std::vector<FacePair> expected = BruteForcePairs(sphere, 0.0, flat, 0.15);
  ASSERT_GT(expected.size(), 50u);
  EXPECT_EQ(Sorted(CandidatePairs(Bvh(sphere, 0.0), Bvh(flat, 0.15))), expected);
  EXPECT_EQ(Sorted(CandidatePairs(Bvh(sphere, 0.0, 2, BvhSplit::kSurfaceArea), Bvh(flat, 0.15, 2, BvhSplit::kSurfaceArea))),
            expected);
}

TEST(PcmBvh, RefittedTreesFindTheRebuiltTreesPairsOnDeformingMeshes) {
  PolygonMesh A = Icosphere(Eigen::Vector3d(0.0, 0.0, 0.0), 1.0, 4);
  PolygonMesh B = Icosphere(Eigen::Vector3d(1.7, 0.2, 0.1), 1.0, 3);
  Bvh tree_A(A, 0.01), tree_B(B, 0.0, 2, BvhSplit::kSurfaceArea);
  for (int step = 1; step <= 5; ++step) {
    Wave(A, 0.03, 4.0, 0.7 * step);
    Wave(B, 0.05, 3.0, -0.4 * step);
    tree_A.Refit(A);
    tree_B.Refit(B);
    const std::vector<FacePair> refitted = Sorted(CandidatePairs(tree_A, tree_B));
    const std::vector<FacePair> rebuilt = Sorted(CandidatePairs(Bvh(A, 0.01), Bvh(B)));
    ASSERT_GT(rebuilt.size(), 20u) << step;
    EXPECT_EQ(refitted, rebuilt) << "step " << step;
    EXPECT_EQ(refitted, BruteForcePairs(A, 0.01, B, 0.0)) << "step " << step;
  }
}

TEST(PcmBvh, RefittingEqualsTheFreshBoxesAndDegradationGrowsWhenFacesMoveApart) {
  PolygonMesh mesh = RandomTriangles(400, 1.0, 0.05, 3);
  Bvh tree(mesh);
  EXPECT_DOUBLE_EQ(tree.Degradation(), 1.0);
  // A rigid translation keeps every box's shape: no degradation.
  mesh.vertices_W.colwise() += Eigen::Vector3d(0.3, -0.2, 0.1);
  tree.Refit(mesh);
  EXPECT_NEAR(tree.Degradation(), 1.0, 1e-12);
  EXPECT_TRUE((tree.nodes().front().box.lo - mesh.vertices_W.rowwise().minCoeff()).isZero(1e-15));
  EXPECT_TRUE((tree.nodes().front().box.hi - mesh.vertices_W.rowwise().maxCoeff()).isZero(1e-15));
  // Every node box encloses its children's after refitting.
  for (std::size_t n = 0; n < tree.nodes().size(); ++n) {
    const BvhNode& node = tree.nodes()[n];
    if (node.count > 0) continue;
    for (const BvhNode* child : {&tree.nodes()[n + 1], &tree.nodes()[node.first]}) {
      EXPECT_TRUE((node.box.lo.array() <= child->box.lo.array()).all() && (child->box.hi.array() <= node.box.hi.array()).all());
    }
  }
  // Scrambling the triangles' places leaves the tree's grouping meaningless: refitted boxes span
  // the whole soup; the rebuilt tree returns to 1.
  PolygonMesh scrambled = RandomTriangles(400, 1.0, 0.05, 4);
  tree.Refit(scrambled);
  EXPECT_GT(tree.Degradation(), 3.0);
  tree.Rebuild(scrambled);
  EXPECT_DOUBLE_EQ(tree.Degradation(), 1.0);
}

}  // namespace
}  // namespace flexmbs::contact
