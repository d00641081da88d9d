#include "contact/pcm/bvh.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <numeric>

#include "core/error.h"

namespace flexmbs::contact {
namespace {

/// Binned surface-area split (Wald 2007, "On fast construction of SAH-based bounding volume
/// hierarchies"): the face centres of [begin, end) sorted into 16 bins along `axis`, the plane
/// between bins that minimises SA(left) n_left + SA(right) n_right, the faces partitioned by it.
/// Returns the first face of the right part, or -1 if all centres share a bin.
int SurfaceAreaSplit(std::vector<int>& faces, int begin, int end, const std::vector<Aabb>& boxes,
                     const std::vector<Eigen::Vector3d>& centres, const Aabb& centre_box, int axis) {
  constexpr int kBins = 16;
  const double lo = centre_box.lo(axis), extent = centre_box.hi(axis) - lo;
  if (!(extent > 0.0)) return -1;
  const auto bin = [&](int face) { return std::min(kBins - 1, static_cast<int>(kBins * (centres[face](axis) - lo) / extent)); };
  std::array<Aabb, kBins> bin_boxes;
  std::array<int, kBins> counts{};
  for (int i = begin; i < end; ++i) {
    const int b = bin(faces[i]);
    if (counts[b]++ == 0) bin_boxes[b] = boxes[faces[i]];
    bin_boxes[b].Extend(boxes[faces[i]]);
  }
  // right_cost[k]: SA of bins k.. times their count.
  std::array<double, kBins> right_cost{};
  Aabb right;
  int right_count = 0;
  for (int k = kBins - 1; k > 0; --k) {
    if (counts[k] > 0 && right_count == 0) right = bin_boxes[k];
    if (counts[k] > 0) right.Extend(bin_boxes[k]);
    right_count += counts[k];
    right_cost[k] = right_count > 0 ? right.SurfaceArea() * right_count : 0.0;
  }
  Aabb left;
  int left_count = 0, best_split = -1;
  double best_cost = 0.0;
  for (int k = 1; k < kBins; ++k) {
    if (counts[k - 1] > 0 && left_count == 0) left = bin_boxes[k - 1];
    if (counts[k - 1] > 0) left.Extend(bin_boxes[k - 1]);
    left_count += counts[k - 1];
    if (left_count == 0 || left_count == end - begin) continue;
    const double cost = left.SurfaceArea() * left_count + right_cost[k];
    if (best_split < 0 || cost < best_cost) {
      best_split = k;
      best_cost = cost;
    }
  }
  if (best_split < 0) return -1;
  return static_cast<int>(std::partition(faces.begin() + begin, faces.begin() + end,
                                         [&](int face) { return bin(face) < best_split; }) -
                          faces.begin());
}

}  // namespace

Aabb FaceBox(const PolygonMesh& mesh, const std::vector<int>& face_offsets, int face, double depth) {
  const int* v = &mesh.face_vertices[face_offsets[face]];
  const Eigen::Vector3d p0 = mesh.vertices_W.col(v[0]);
  Aabb box{p0, p0};
  Eigen::Vector3d twice_area = Eigen::Vector3d::Zero();
  for (int k = 1; k < mesh.face_sizes[face]; ++k) {
    const Eigen::Vector3d p = mesh.vertices_W.col(v[k]);
    box.lo = box.lo.cwiseMin(p);
    box.hi = box.hi.cwiseMax(p);
    if (k + 1 < mesh.face_sizes[face]) twice_area += (p - p0).cross(mesh.vertices_W.col(v[k + 1]) - p0);
  }
  if (depth == 0.0) return box;
  const double norm = twice_area.norm();
  if (!(norm > 0.0)) {
    box.lo.array() -= depth;
    box.hi.array() += depth;
    return box;
  }
  const Eigen::Vector3d sweep = -depth / norm * twice_area;
  box.Extend(Aabb{box.lo + sweep, box.hi + sweep});
  return box;
}

Bvh::Bvh(const PolygonMesh& mesh, double depth, int leaf_size, BvhSplit split)
    : depth_(depth), leaf_size_(leaf_size), split_(split) {
  FLEXMBS_CHECK(leaf_size >= 1 && depth >= 0.0, "a BVH needs leaf_size >= 1 and depth >= 0");
  FLEXMBS_CHECK(!mesh.face_sizes.empty(), "a BVH needs at least one face");
  face_offsets_.resize(mesh.face_sizes.size());
  int offset = 0;
  for (std::size_t f = 0; f < mesh.face_sizes.size(); ++f) {
    FLEXMBS_CHECK(mesh.face_sizes[f] >= 3, "a face has at least 3 vertices");
    face_offsets_[f] = offset;
    offset += mesh.face_sizes[f];
  }
  FLEXMBS_CHECK(offset == static_cast<int>(mesh.face_vertices.size()), "face sizes and vertices disagree");
  for (const int v : mesh.face_vertices) {
    FLEXMBS_CHECK(v >= 0 && v < mesh.vertices_W.cols(), "a face vertex out of range");
  }
  Rebuild(mesh);
}

void Bvh::UpdateFaceBoxes(const PolygonMesh& mesh) {
  FLEXMBS_CHECK(mesh.face_sizes.size() == face_offsets_.size(), "a BVH refits the mesh it was built on");
  face_boxes_.resize(face_offsets_.size());
  for (std::size_t f = 0; f < face_offsets_.size(); ++f) {
    face_boxes_[f] = FaceBox(mesh, face_offsets_, static_cast<int>(f), depth_);
  }
}

void Bvh::Rebuild(const PolygonMesh& mesh) {
  UpdateFaceBoxes(mesh);
  const int num_faces = static_cast<int>(face_boxes_.size());
  faces_.resize(num_faces);
  std::iota(faces_.begin(), faces_.end(), 0);
  std::vector<Eigen::Vector3d> centres(num_faces);
  for (int f = 0; f < num_faces; ++f) centres[f] = 0.5 * (face_boxes_[f].lo + face_boxes_[f].hi);
  nodes_.clear();
  nodes_.reserve(2 * (num_faces / leaf_size_) + 1);
  Build(0, num_faces, centres);
  built_relative_area_ = RelativeSurfaceArea();
}

int Bvh::Build(int begin, int end, std::vector<Eigen::Vector3d>& centres) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Aabb box = face_boxes_[faces_[begin]];
  Aabb centre_box{centres[faces_[begin]], centres[faces_[begin]]};
  for (int i = begin + 1; i < end; ++i) {
    box.Extend(face_boxes_[faces_[i]]);
    centre_box.Extend(Aabb{centres[faces_[i]], centres[faces_[i]]});
  }
  nodes_[index].box = box;
  if (end - begin <= leaf_size_) {
    nodes_[index].first = begin;
    nodes_[index].count = end - begin;
    return index;
  }
  int axis = 0;
  (centre_box.hi - centre_box.lo).maxCoeff(&axis);
  int middle = split_ == BvhSplit::kSurfaceArea
                   ? SurfaceAreaSplit(faces_, begin, end, face_boxes_, centres, centre_box, axis)
                   : -1;
  if (middle < 0) {
    middle = begin + (end - begin) / 2;
    std::nth_element(faces_.begin() + begin, faces_.begin() + middle, faces_.begin() + end,
                     [&](int a, int b) { return centres[a](axis) < centres[b](axis); });
  }
  Build(begin, middle, centres);
  const int right = Build(middle, end, centres);
  nodes_[index].first = right;
  nodes_[index].count = 0;
  return index;
}

void Bvh::Refit(const PolygonMesh& mesh) {
  UpdateFaceBoxes(mesh);
  for (auto node = nodes_.rbegin(); node != nodes_.rend(); ++node) {
    if (node->count > 0) {
      node->box = face_boxes_[faces_[node->first]];
      for (int i = 1; i < node->count; ++i) node->box.Extend(face_boxes_[faces_[node->first + i]]);
    } else {
      const BvhNode* self = &*node;
      node->box = self[1].box;
      node->box.Extend(nodes_[node->first].box);
    }
  }
}

double Bvh::RelativeSurfaceArea() const {
  double sum = 0.0;
  for (const BvhNode& node : nodes_) sum += node.box.SurfaceArea();
  const double root = nodes_.front().box.SurfaceArea();
  return root > 0.0 ? sum / root : 1.0;
}

}  // namespace flexmbs::contact
