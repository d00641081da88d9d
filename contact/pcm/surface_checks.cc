#include "contact/pcm/surface_checks.h"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <map>
#include <utility>

#include "core/error.h"

namespace flexmbs::contact {

void RequirePcmSurface(const PolygonMesh& mesh, std::string_view name, bool closed) {
  const int num_faces = static_cast<int>(mesh.face_sizes.size());
  if (num_faces == 0) throw InputError(fmt::format("surface '{}' has no triangles", name));
  // Each directed edge (i, j) with the triangle running it.
  std::map<std::pair<int, int>, int> edges;
  for (int f = 0; f < num_faces; ++f) {
    if (mesh.face_sizes[f] != 3) {  // faces before f are triangles: face f starts at 3 f
      throw InputError(fmt::format("surface '{}': face {} has {} vertices; the polygonal contact model needs triangles",
                                   name, f, mesh.face_sizes[f]));
    }
    const int* v = &mesh.face_vertices[3 * f];
    for (int k = 0; k < 3; ++k) {
      if (v[k] < 0 || v[k] >= mesh.vertices_W.cols()) {
        throw InputError(fmt::format("surface '{}': triangle {} names vertex {} of {}", name, f, v[k], mesh.vertices_W.cols()));
      }
    }
    const Eigen::Vector3d a = mesh.vertices_W.col(v[0]), b = mesh.vertices_W.col(v[1]), c = mesh.vertices_W.col(v[2]);
    if (!((b - a).cross(c - a).norm() > 0.0)) {
      throw InputError(fmt::format("surface '{}': triangle {} ({}, {}, {}) has no area", name, f, v[0], v[1], v[2]));
    }
    for (int k = 0; k < 3; ++k) {
      const auto [existing, inserted] = edges.emplace(std::pair{v[k], v[(k + 1) % 3]}, f);
      if (!inserted) {
        throw InputError(fmt::format("surface '{}': triangles {} and {} both run edge {} -> {}: inconsistent "
                                     "orientation (a flipped triangle) or an edge of more than two triangles",
                                     name, existing->second, f, v[k], v[(k + 1) % 3]));
      }
    }
  }
  if (!closed) return;
  for (const auto& [edge, face] : edges) {
    if (!edges.contains({edge.second, edge.first})) {
      throw InputError(fmt::format("surface '{}': edge {} - {} of triangle {} has no neighbour: a hole in a surface "
                                   "that must be closed",
                                   name, edge.first, edge.second, face));
    }
  }
}

}  // namespace flexmbs::contact
