#pragma once
// An axis-aligned bounding-box hierarchy over the faces of a polygon mesh (docs/contact.md,
// "Polygonal Contact Model"): built top-down by median or surface-area splits, refitted bottom-up when the
// vertices move (a deforming flexible surface), with a measure of how far refitting has degraded
// it against the tree as built.

#include <Eigen/Core>
#include <vector>

#include "contact/geometry/sphere_surface.h"

namespace flexmbs::contact {

/// An axis-aligned box in W [m]: the points x with lo <= x <= hi component-wise.
struct Aabb {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1.0);
  Eigen::Vector3d hi = Eigen::Vector3d::Constant(-1.0);  ///< lo > hi: empty
  /// The smallest box holding this one and `other`.
  void Extend(const Aabb& other) {
    lo = lo.cwiseMin(other.lo);
    hi = hi.cwiseMax(other.hi);
  }
  /// Whether the two closed boxes share a point (touching counts).
  bool Overlaps(const Aabb& other) const {
    return (lo.array() <= other.hi.array()).all() && (other.lo.array() <= hi.array()).all();
  }
  /// 2 (dx dy + dy dz + dz dx) [m^2], the surface area that bounds the chance a ray or box hits it.
  double SurfaceArea() const {
    const Eigen::Vector3d d = (hi - lo).cwiseMax(0.0);
    return 2.0 * (d.x() * d.y() + d.y() * d.z() + d.z() * d.x());
  }
};

/// The box of face `face` of `mesh` swept inward along its unit normal n (right-hand rule,
/// Newell's) by `depth` [m] >= 0: the box of the face and of the face moved by -depth n, which
/// holds every point under the face to that depth (where a PCM element of the face can lie). A
/// face without area is grown by depth on every side instead.
Aabb FaceBox(const PolygonMesh& mesh, const std::vector<int>& face_offsets, int face, double depth);

/// How a node's faces are split in two: at the median of their box centres along the longest
/// axis of the centres' box, or by the binned surface-area heuristic along that axis (the median
/// where all centres fall in one bin). bench/pcm_bench.cc measures both (docs/contact.md): SAH
/// builds take 0.85 to 1.33x the median's time, queries on SAH trees are 1.6 to 2.0x faster,
/// so SAH is the default.
enum class BvhSplit { kMedian, kSurfaceArea };

/// One node of a Bvh: a leaf holds faces [first, first + count) of Bvh::faces(); an inner node
/// has count 0, its left child is the node right after it and its right child node `first`.
struct BvhNode {
  Aabb box;
  int first = 0;  ///< leaf: first entry in Bvh::faces(); inner: index of the right child
  int count = 0;  ///< leaf: number of faces (> 0); inner: 0 (the left child is the next node)
};

/// The hierarchy of one mesh. Nodes are stored depth first (a parent before its children, the
/// left child right after its parent), so a reverse sweep refits children before parents.
class Bvh {
 public:
  /// Builds top-down: each node's faces are split in two by `split` until at most `leaf_size`
  /// faces remain. Each face's box
  /// is swept inward by `depth` [m] (FaceBox: the deepest penetration a contact search must see;
  /// 0 for plain overlap). Preconditions (InternalError): leaf_size >= 1, depth >= 0, faces of >= 3 valid
  /// vertices, at least one face.
  Bvh(const PolygonMesh& mesh, double depth = 0.0, int leaf_size = 2,
      BvhSplit split = BvhSplit::kSurfaceArea);

  /// Recomputes every face box and node box from the moved vertices of `mesh` (same faces as
  /// at construction), leaves first; the tree's shape is kept. O(faces).
  void Refit(const PolygonMesh& mesh);
  /// Builds the tree anew on `mesh` (same depth, leaf size and split).
  void Rebuild(const PolygonMesh& mesh);

  /// The sum of all nodes' surface areas over the root's, >= 1 (the expected number of nodes a
  /// small query box visits, up to a constant: MacDonald & Booth's surface area heuristic).
  double RelativeSurfaceArea() const;
  /// RelativeSurfaceArea() now over its value when the tree was last built: 1 after a build,
  /// growing as refitting stretches boxes over faces that have moved apart. Measured in
  /// bench/pcm_bench.cc (docs/contact.md): queries as fast as a fresh tree's up to 1.04, 1.5x at
  /// 1.15, 1.6x at 1.35; rebuild past about 1.3 if the surface stays deformed that much.
  double Degradation() const { return RelativeSurfaceArea() / built_relative_area_; }

  const std::vector<BvhNode>& nodes() const { return nodes_; }
  /// Face indices, permuted so each leaf's faces are contiguous.
  const std::vector<int>& faces() const { return faces_; }
  /// The (swept) box of each face, by face index.
  const std::vector<Aabb>& face_boxes() const { return face_boxes_; }
  /// Where each face's vertices start in the mesh's face_vertices, by face index.
  const std::vector<int>& face_offsets() const { return face_offsets_; }

 private:
  int Build(int begin, int end, std::vector<Eigen::Vector3d>& centres);
  void UpdateFaceBoxes(const PolygonMesh& mesh);

  double depth_;
  int leaf_size_;
  BvhSplit split_;
  std::vector<int> face_offsets_;
  std::vector<int> faces_;
  std::vector<Aabb> face_boxes_;
  std::vector<BvhNode> nodes_;
  double built_relative_area_ = 1.0;
};

}  // namespace flexmbs::contact
