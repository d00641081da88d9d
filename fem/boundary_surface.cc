#include "fem/boundary_surface.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <span>

#include "core/error.h"
#include "core/polygon.h"

namespace flexmbs::fem {
namespace {

// One face of a reference element (gmsh node order, reference_element.cc): its corners
// counter-clockwise seen from outside, then the mid-side node of edge k -> k + 1 (quadratic
// types). Outward orientation is checked against the reference element's interior in
// tests/fem/boundary_surface_test.cc.
struct FaceTable {
  int num_corners;
  std::array<int, 8> nodes;
};

constexpr FaceTable kTetFaces[] = {
    {3, {0, 2, 1, 6, 5, 4}},  // zeta = 0
    {3, {0, 1, 3, 4, 9, 7}},  // eta = 0
    {3, {0, 3, 2, 7, 8, 6}},  // xi = 0
    {3, {1, 2, 3, 5, 8, 9}},  // xi + eta + zeta = 1
};
constexpr FaceTable kHexFaces[] = {
    {4, {0, 3, 2, 1, 9, 13, 11, 8}},    // zeta = -1
    {4, {4, 5, 6, 7, 16, 18, 19, 17}},  // zeta = +1
    {4, {0, 1, 5, 4, 8, 12, 16, 10}},   // eta = -1
    {4, {3, 7, 6, 2, 15, 19, 14, 13}},  // eta = +1
    {4, {0, 4, 7, 3, 10, 17, 15, 9}},   // xi = -1
    {4, {1, 2, 6, 5, 11, 14, 18, 12}},  // xi = +1
};
constexpr FaceTable kWedgeFaces[] = {
    {3, {0, 2, 1, 7, 9, 6}},           // zeta = -1
    {3, {3, 4, 5, 12, 14, 13}},        // zeta = +1
    {4, {0, 1, 4, 3, 6, 10, 12, 8}},   // eta = 0
    {4, {0, 3, 5, 2, 8, 13, 11, 7}},   // xi = 0
    {4, {1, 2, 5, 4, 9, 11, 14, 10}},  // xi + eta = 1
};

std::span<const FaceTable> FacesOf(ElementType type) {
  switch (type) {
    case ElementType::kTet4:
    case ElementType::kTet10:
      return kTetFaces;
    case ElementType::kHex8:
    case ElementType::kHex20:
      return kHexFaces;
    case ElementType::kWedge6:
    case ElementType::kWedge15:
      return kWedgeFaces;
  }
  return {};
}

// A face of the mesh with its sorted corners as the matching key.
struct KeyedFace {
  std::array<int, 4> key;  // the corner nodes and -1 for a triangle's fourth, sorted
  BoundaryFace face;
};

void AddPolygon(std::initializer_list<int> fe_nodes, std::vector<int>* sizes,
                std::vector<int>* polygon_nodes) {
  sizes->push_back(static_cast<int>(fe_nodes.size()));
  polygon_nodes->insert(polygon_nodes->end(), fe_nodes);
}

// The polygons of one face through its FE nodes (see BoundarySurface).
void SplitFace(const BoundaryFace& f, std::vector<int>* sizes, std::vector<int>* polygon_nodes) {
  const auto& v = f.nodes;
  if (f.num_nodes == f.num_corners) {
    if (f.num_corners == 3)
      AddPolygon({v[0], v[1], v[2]}, sizes, polygon_nodes);
    else
      AddPolygon({v[0], v[1], v[2], v[3]}, sizes, polygon_nodes);
    return;
  }
  const int c = f.num_corners;
  // Corner k with the mid-side nodes of its two edges: corner k, mid(k, k+1), mid(k-1, k).
  for (int k = 0; k < c; ++k)
    AddPolygon({v[k], v[c + k], v[c + (k + c - 1) % c]}, sizes, polygon_nodes);
  if (c == 3)
    AddPolygon({v[3], v[4], v[5]}, sizes, polygon_nodes);
  else
    AddPolygon({v[4], v[5], v[6], v[7]}, sizes, polygon_nodes);
}

}  // namespace

std::vector<BoundaryFace> BoundaryFaces(const Mesh& mesh) {
  std::vector<KeyedFace> all;
  for (const ElementBlock& block : mesh.blocks) {
    const std::span<const FaceTable> tables = FacesOf(block.type);
    const bool quadratic = Traits(block.type).order == 2;
    for (Eigen::Index e = 0; e < block.num_elements(); ++e) {
      for (const FaceTable& table : tables) {
        KeyedFace k;
        k.face.num_corners = table.num_corners;
        k.face.num_nodes = quadratic ? 2 * table.num_corners : table.num_corners;
        for (int a = 0; a < k.face.num_nodes; ++a)
          k.face.nodes[static_cast<std::size_t>(a)] =
              block.connectivity(table.nodes[static_cast<std::size_t>(a)], e);
        k.key = {-1, -1, -1, -1};
        std::copy_n(k.face.nodes.begin(), table.num_corners, k.key.begin());
        std::sort(k.key.begin(), k.key.end());
        all.push_back(k);
      }
    }
  }
  // Faces whose key occurs once, in their original order.
  std::vector<std::size_t> order(all.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return all[a].key < all[b].key; });
  std::vector<bool> unique(all.size(), false);
  for (std::size_t i = 0; i < order.size();) {
    std::size_t j = i + 1;
    while (j < order.size() && all[order[j]].key == all[order[i]].key) ++j;
    if (j == i + 1) unique[order[i]] = true;
    i = j;
  }
  std::vector<BoundaryFace> boundary;
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (unique[i]) boundary.push_back(all[i].face);
  }
  return boundary;
}

PolygonSurface BoundarySurface(const Mesh& mesh, const std::vector<BoundaryFace>& faces,
                               const std::vector<int>& node_set) {
  FLEXMBS_CHECK(std::is_sorted(node_set.begin(), node_set.end()), "node sets are sorted");
  auto in_set = [&](int node) {
    return std::binary_search(node_set.begin(), node_set.end(), node);
  };

  std::vector<int> sizes;
  std::vector<int> polygon_nodes;  // FE node indices, renumbered to vertices below
  for (const BoundaryFace& f : faces) {
    const auto used = std::span<const int>(f.nodes).first(static_cast<std::size_t>(f.num_nodes));
    if (std::all_of(used.begin(), used.end(), in_set)) SplitFace(f, &sizes, &polygon_nodes);
  }

  PolygonSurface surface;
  surface.fe_nodes = polygon_nodes;
  std::sort(surface.fe_nodes.begin(), surface.fe_nodes.end());
  surface.fe_nodes.erase(std::unique(surface.fe_nodes.begin(), surface.fe_nodes.end()),
                         surface.fe_nodes.end());
  const auto num_vertices = static_cast<Eigen::Index>(surface.fe_nodes.size());
  surface.vertices.resize(num_vertices, 3);
  for (Eigen::Index v = 0; v < num_vertices; ++v) {
    surface.vertices.row(v) =
        mesh.nodes.col(surface.fe_nodes[static_cast<std::size_t>(v)]).transpose();
  }
  surface.face_vertices.reserve(polygon_nodes.size());
  for (const int node : polygon_nodes) {
    const auto it = std::lower_bound(surface.fe_nodes.begin(), surface.fe_nodes.end(), node);
    surface.face_vertices.push_back(static_cast<int>(it - surface.fe_nodes.begin()));
  }
  surface.face_sizes = std::move(sizes);

  const auto num_faces = static_cast<Eigen::Index>(surface.face_sizes.size());
  surface.face_normals.resize(num_faces, 3);
  surface.face_areas.resize(num_faces);
  std::size_t first = 0;
  for (Eigen::Index f = 0; f < num_faces; ++f) {
    const auto size = static_cast<std::size_t>(surface.face_sizes[static_cast<std::size_t>(f)]);
    const Eigen::Vector3d area = PolygonAreaVector(
        surface.vertices, std::span<const int>(surface.face_vertices).subspan(first, size));
    const double norm = area.norm();
    FLEXMBS_CHECK(norm > 0.0, "a boundary polygon of a valid element has a non-zero area");
    surface.face_areas(f) = norm;
    surface.face_normals.row(f) = (area / norm).transpose();
    first += size;
  }
  return surface;
}

PolygonSurface BoundarySurface(const Mesh& mesh, const std::vector<int>& node_set) {
  return BoundarySurface(mesh, BoundaryFaces(mesh), node_set);
}

}  // namespace flexmbs::fem
