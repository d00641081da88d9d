#pragma once

#include <Eigen/Core>
#include <span>

namespace flexmbs {

/// The vector area of a polygon: 1/2 sum_k (v_k - v_0) x (v_k+1 - v_0) over its vertices,
/// given as indices into the rows of `vertices` (V x 3) in order. Its norm is the area of a
/// planar polygon, its direction the normal by the right-hand rule (Newell's method; the
/// differences from v_0 reduce round-off).
inline Eigen::Vector3d PolygonAreaVector(const Eigen::MatrixX3d& vertices, std::span<const int> polygon) {
  auto vertex = [&](std::size_t k) { return Eigen::Vector3d(vertices.row(polygon[k]).transpose()); };
  Eigen::Vector3d twice_area = Eigen::Vector3d::Zero();
  for (std::size_t k = 1; k + 1 < polygon.size(); ++k) {
    twice_area += (vertex(k) - vertex(0)).cross(vertex(k + 1) - vertex(0));
  }
  return 0.5 * twice_area;
}

}  // namespace flexmbs
