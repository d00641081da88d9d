// contact::NearestMeshPoint through a Bvh (contact/pcm/nearest_face.h) against the brute force
// over all faces on random deformed surfaces: the same face point, weights, normal and side,
// bit for bit, ties between faces (a vertex shared by several faces, a node of an aligned mesh on
// an edge) included, on trees built on the deformed surface or refitted to it.

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include "contact/geometry/sphere_surface.h"
#include "contact/pcm/bvh.h"
#include "contact/pcm/nearest_face.h"
#include "tests/support/random_draws.h"

namespace flexmbs::contact {
namespace {

/// The square [0, 1]^2 at z = 0 in n x n quads, counter-clockwise seen from +z.
PolygonMesh QuadGrid(int n) {
  PolygonMesh mesh;
  mesh.vertices_W.resize(3, (n + 1) * (n + 1));
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) mesh.vertices_W.col(j * (n + 1) + i) = Eigen::Vector3d(1.0 * i / n, 1.0 * j / n, 0.0);
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const int v = j * (n + 1) + i;
      mesh.face_sizes.push_back(4);
      mesh.face_vertices.insert(mesh.face_vertices.end(), {v, v + 1, v + n + 2, v + n + 1});
    }
  }
  return mesh;
}

/// A sphere of radius r [m] about `centre` by latitude and longitude: triangles at the poles,
/// quads between the rings (`rings` rings of `sectors` vertices).
PolygonMesh LatitudeSphere(const Eigen::Vector3d& centre, double r, int rings, int sectors) {
  PolygonMesh mesh;
  mesh.vertices_W.resize(3, 2 + rings * sectors);
  mesh.vertices_W.col(0) = centre + Eigen::Vector3d(0, 0, r);
  mesh.vertices_W.col(1) = centre - Eigen::Vector3d(0, 0, r);
  const auto at = [&](int ring, int sector) { return 2 + ring * sectors + sector % sectors; };
  for (int ring = 0; ring < rings; ++ring) {
    const double theta = std::numbers::pi * (ring + 1) / (rings + 1);
    for (int sector = 0; sector < sectors; ++sector) {
      const double phi = 2.0 * std::numbers::pi * sector / sectors;
      mesh.vertices_W.col(at(ring, sector)) =
          centre + r * Eigen::Vector3d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
    }
  }
  for (int sector = 0; sector < sectors; ++sector) {
    mesh.face_sizes.insert(mesh.face_sizes.end(), {3, 3});
    mesh.face_vertices.insert(mesh.face_vertices.end(), {0, at(0, sector), at(0, sector + 1)});
    mesh.face_vertices.insert(mesh.face_vertices.end(), {1, at(rings - 1, sector + 1), at(rings - 1, sector)});
    for (int ring = 0; ring + 1 < rings; ++ring) {
      mesh.face_sizes.push_back(4);
      mesh.face_vertices.insert(mesh.face_vertices.end(),
                                {at(ring, sector), at(ring + 1, sector), at(ring + 1, sector + 1), at(ring, sector + 1)});
    }
  }
  return mesh;
}

/// Moves every vertex by amplitude (sin(k y + phase), sin(k z + phase), sin(k x + phase)) [m]: a
/// smooth deformation, as a flexible body's.
void Wave(PolygonMesh& mesh, double amplitude, double k, double phase) {
  for (Eigen::Index v = 0; v < mesh.vertices_W.cols(); ++v) {
    const Eigen::Vector3d p = mesh.vertices_W.col(v);
    mesh.vertices_W.col(v) +=
        amplitude * Eigen::Vector3d(std::sin(k * p.y() + phase), std::sin(k * p.z() + phase), std::sin(k * p.x() + phase));
  }
}

/// Moves every vertex by up to `amplitude` [m] in each direction, uniformly at random.
void Jitter(PolygonMesh& mesh, double amplitude, std::mt19937& random) {
  std::uniform_real_distribution<double> uniform(-amplitude, amplitude);
  for (Eigen::Index v = 0; v < mesh.vertices_W.cols(); ++v) {
    mesh.vertices_W.col(v) += flexmbs::testing::DrawVector3(uniform, random);
  }
}

/// How many of `points` have their nearest distance on more than one face, and whether the tree
/// gives the brute force's face point for every one (the first mismatch reported).
int CompareOnPoints(const PolygonMesh& mesh, const Bvh& tree, const std::vector<Eigen::Vector3d>& points) {
  int ties = 0;
  for (const Eigen::Vector3d& p : points) {
    const MeshPoint brute = NearestMeshPoint(p, mesh);
    const MeshPoint fast = NearestMeshPoint(p, mesh, tree);
    const bool same = brute.point == fast.point && brute.vertices == fast.vertices && brute.weights == fast.weights &&
                      brute.normal == fast.normal && brute.interior == fast.interior;
    EXPECT_TRUE(same) << "at " << p.transpose() << ": brute " << brute.point.transpose() << " tree "
                      << fast.point.transpose();
    if (!same) break;
    const double best = (p - brute.point).norm();
    int at_best = 0;
    std::size_t first = 0;
    for (const int size : mesh.face_sizes) {
      at_best += (p - NearestFacePoint(p, mesh, first, size).point).norm() == best;
      first += static_cast<std::size_t>(size);
    }
    ties += at_best > 1;
  }
  return ties;
}

/// Points uniform in the mesh's box grown by `margin` [m], the mesh's own vertices, and the
/// vertices of `aligned` (another mesh's nodes, on the faces' edges where the meshes agree).
std::vector<Eigen::Vector3d> QueryPoints(const PolygonMesh& mesh, const PolygonMesh& aligned, int count, double margin,
                                         std::mt19937& random) {
  const Eigen::Vector3d lo = mesh.vertices_W.rowwise().minCoeff().array() - margin;
  const Eigen::Vector3d hi = mesh.vertices_W.rowwise().maxCoeff().array() + margin;
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<Eigen::Vector3d> points;
  for (int k = 0; k < count; ++k) {
    points.push_back(lo + (hi - lo).cwiseProduct(flexmbs::testing::DrawVector3(uniform, random)));
  }
  for (Eigen::Index v = 0; v < mesh.vertices_W.cols(); ++v) points.push_back(mesh.vertices_W.col(v));
  for (Eigen::Index v = 0; v < aligned.vertices_W.cols(); ++v) points.push_back(aligned.vertices_W.col(v));
  return points;
}

TEST(NearestFace, TheTreeFindsTheBruteForcesFacePointOnRandomDeformedQuadSurfaces) {
  std::mt19937 random(16);
  for (const int n : {1, 3, 24}) {
    SCOPED_TRACE(n);
    // A SID-like quad surface: bent out of its plane and in it, each node moved at random.
    PolygonMesh mesh = QuadGrid(n);
    const PolygonMesh undeformed = mesh;
    Wave(mesh, 0.05, 4.0, 0.3);
    Jitter(mesh, 0.1 / n, random);
    // The nodes of an aligned coarser grid lie on the undeformed grid's vertices and edges: ties.
    const PolygonMesh aligned = QuadGrid(std::max(1, n / 3));
    const std::vector<Eigen::Vector3d> points = QueryPoints(mesh, aligned, 1000, 0.2, random);
    const std::vector<Eigen::Vector3d> flat_points = QueryPoints(undeformed, aligned, 500, 0.2, random);
    const Bvh built(mesh);  // SAH, leaf 2, on the deformed surface
    Bvh refitted(undeformed, 0.0, 4, BvhSplit::kMedian);
    refitted.Refit(mesh);
    const int ties = CompareOnPoints(mesh, built, points);
    CompareOnPoints(mesh, refitted, points);
    const int flat_ties = CompareOnPoints(undeformed, Bvh(undeformed), flat_points);
    std::printf("%d x %d quads: %zu points deformed (%d ties), %zu undeformed (%d ties)\n", n, n, points.size(), ties,
                flat_points.size(), flat_ties);
    if (n > 1) {
      EXPECT_GT(flat_ties, 0);  // the undeformed grid's shared vertices and edges
    }
  }
}

TEST(NearestFace, TheTreeFindsTheBruteForcesFacePointOnADeformedClosedSurface) {
  std::mt19937 random(17);
  PolygonMesh sphere = LatitudeSphere(Eigen::Vector3d(0.1, -0.2, 0.3), 0.5, 20, 30);  // 60 triangles, 570 quads
  const PolygonMesh undeformed = sphere;
  Wave(sphere, 0.03, 6.0, 1.1);
  Jitter(sphere, 0.005, random);
  const std::vector<Eigen::Vector3d> points = QueryPoints(sphere, undeformed, 600, 0.3, random);
  CompareOnPoints(sphere, Bvh(sphere), points);
  Bvh refitted(undeformed, 0.0, 2, BvhSplit::kMedian);
  refitted.Refit(sphere);
  CompareOnPoints(sphere, refitted, points);
  const int ties = CompareOnPoints(undeformed, Bvh(undeformed), points);
  std::printf("closed surface: %zu points, %d ties on the undeformed one\n", points.size(), ties);
  EXPECT_GT(ties, 0);  // the poles' fans at least
}

}  // namespace
}  // namespace flexmbs::contact
