#include "tests/contact/pcm_meshes.h"
#include "tests/support/random_draws.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <utility>
#include <vector>

namespace flexmbs::contact::testing {
namespace {

PolygonMesh TriangleMesh(const std::vector<Eigen::Vector3d>& points, const std::vector<std::array<int, 3>>& triangles) {
  PolygonMesh mesh;
  mesh.vertices_W.resize(3, static_cast<Eigen::Index>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) mesh.vertices_W.col(static_cast<Eigen::Index>(i)) = points[i];
  for (const auto& t : triangles) {
    mesh.face_sizes.push_back(3);
    mesh.face_vertices.insert(mesh.face_vertices.end(), t.begin(), t.end());
  }
  return mesh;
}

/// Appends the counter-clockwise quad q of `points` as triangles: by its diagonal q0-q2, or about
/// its centre (appended to points), which keeps every mirror symmetry of the quad.
void SplitQuad(const std::array<int, 4>& q, QuadSplit split, std::vector<Eigen::Vector3d>& points,
               std::vector<std::array<int, 3>>& triangles) {
  if (split == QuadSplit::kDiagonal) {
    triangles.push_back({q[0], q[1], q[2]});
    triangles.push_back({q[0], q[2], q[3]});
    return;
  }
  const Eigen::Vector3d p_centre = 0.25 * (points[q[0]] + points[q[1]] + points[q[2]] + points[q[3]]);
  const int centre = static_cast<int>(points.size());
  points.push_back(p_centre);
  for (int k = 0; k < 4; ++k) triangles.push_back({q[k], q[(k + 1) % 4], centre});
}

}  // namespace

PolygonMesh Icosphere(const Eigen::Vector3d& centre, double radius, int level) {
  const double g = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Eigen::Vector3d> unit = {{-1, g, 0}, {1, g, 0},  {-1, -g, 0}, {1, -g, 0}, {0, -1, g},  {0, 1, g},
                                       {0, -1, -g}, {0, 1, -g}, {g, 0, -1},  {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
  for (auto& p : unit) p.normalize();
  std::vector<std::array<int, 3>> triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                               {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                               {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                               {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int l = 0; l < level; ++l) {
    std::map<std::pair<int, int>, int> midpoints;
    const auto midpoint = [&](int a, int b) {
      const std::pair<int, int> key{std::min(a, b), std::max(a, b)};
      const auto found = midpoints.find(key);
      if (found != midpoints.end()) return found->second;
      unit.push_back((unit[a] + unit[b]).normalized());
      const int index = static_cast<int>(unit.size()) - 1;
      midpoints.emplace(key, index);
      return index;
    };
    std::vector<std::array<int, 3>> finer;
    for (const auto& [a, b, c] : triangles) {
      const int ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      finer.push_back({a, ab, ca});
      finer.push_back({b, bc, ab});
      finer.push_back({c, ca, bc});
      finer.push_back({ab, bc, ca});
    }
    triangles = std::move(finer);
  }
  for (auto& p : unit) p = centre + radius * p;
  return TriangleMesh(unit, triangles);
}

PolygonMesh FlatGrid(double half_width, int n, double height, QuadSplit split) {
  std::vector<Eigen::Vector3d> points;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      points.emplace_back(-half_width + 2.0 * half_width * i / n, -half_width + 2.0 * half_width * j / n, height);
    }
  }
  std::vector<std::array<int, 3>> triangles;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const int v = j * (n + 1) + i;
      SplitQuad({v, v + 1, v + n + 2, v + n + 1}, split, points, triangles);
    }
  }
  return TriangleMesh(points, triangles);
}

PolygonMesh Box(const Eigen::Vector3d& half_extents, QuadSplit split) {
  std::vector<Eigen::Vector3d> corners;
  for (int k = 0; k < 8; ++k) {
    corners.push_back(Eigen::Vector3d(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1).cwiseProduct(half_extents));
  }
  std::vector<std::array<int, 3>> triangles;
  for (int axis = 0; axis < 3; ++axis) {
    for (const int side : {0, 1}) {
      // The face's corners in cyclic order around it: the two other axes' bits as 00, 10, 11, 01.
      const int u = 1 << ((axis + 1) % 3), v = 1 << ((axis + 2) % 3), base = side << axis;
      std::array<int, 4> quad{base, base | u, base | u | v, base | v};
      const Eigen::Vector3d outward = (side ? 1.0 : -1.0) * Eigen::Vector3d::Unit(axis);
      const Eigen::Vector3d &a = corners[quad[0]], &b = corners[quad[1]], &c = corners[quad[2]];
      if ((b - a).cross(c - a).dot(outward) < 0.0) std::swap(quad[1], quad[3]);
      SplitQuad(quad, split, corners, triangles);
    }
  }
  return TriangleMesh(corners, triangles);
}

PolygonMesh RandomTriangles(int count, double size, double edge, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> position(0.0, size), offset(-edge, edge);
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<int, 3>> triangles;
  for (int t = 0; t < count; ++t) {
    const Eigen::Vector3d p = flexmbs::testing::DrawVector3(position, rng);
    points.push_back(p);
    points.push_back(p + flexmbs::testing::DrawVector3(offset, rng));
    points.push_back(p + flexmbs::testing::DrawVector3(offset, rng));
    triangles.push_back({3 * t, 3 * t + 1, 3 * t + 2});
  }
  return TriangleMesh(points, triangles);
}

PolygonMesh LowerCap(double radius, int level) {
  const PolygonMesh sphere = Icosphere(Eigen::Vector3d::Zero(), radius, level);
  PolygonMesh cap{sphere.vertices_W, {}, {}};
  for (std::size_t f = 0; f < sphere.face_sizes.size(); ++f) {
    bool low = true;
    for (int k = 0; k < 3; ++k) low = low && sphere.vertices_W(2, sphere.face_vertices[3 * f + k]) < -0.6 * radius;
    if (!low) continue;
    cap.face_sizes.push_back(3);
    for (int k = 0; k < 3; ++k) cap.face_vertices.push_back(sphere.face_vertices[3 * f + k]);
  }
  return cap;
}

PolygonMesh MirroredInX(PolygonMesh mesh) {
  mesh.vertices_W.row(0) *= -1.0;
  auto face = mesh.face_vertices.begin();
  for (const int size : mesh.face_sizes) {
    std::reverse(face, face + size);
    face += size;
  }
  return mesh;
}

void Wave(PolygonMesh& mesh, double amplitude, double wave_number, double phase) {
  for (Eigen::Index v = 0; v < mesh.vertices_W.cols(); ++v) {
    const Eigen::Vector3d p = mesh.vertices_W.col(v);
    mesh.vertices_W.col(v) += amplitude * Eigen::Vector3d(std::sin(wave_number * p.y() + phase),
                                                          std::sin(wave_number * p.z() + phase),
                                                          std::sin(wave_number * p.x() + phase));
  }
}

}  // namespace flexmbs::contact::testing
