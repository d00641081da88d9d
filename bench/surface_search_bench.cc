// surface_surface's node-to-surface search (docs/contact.md, "Flexible bodies"; mbs/
// surface_unilateral.h): every vertex of surface A against the faces of surface B, per
// evaluation, on two deformed n x n grids facing each other 2 mm apart (A's (n + 1)^2 vertices
// against B's n^2 bilinear quads or 2 n^2 triangles). Four ways on the same surfaces in one run:
// the brute force over all faces (contact::NearestMeshPoint; timed on at most 1000 of A's vertices
// and scaled), flexmbs' Bvh built per evaluation (SAH and median splits) or refitted, each then
// queried per vertex (contact/pcm/nearest_face.h), and FCL 0.7's BVHModel<OBBRSS> built per
// evaluation with a distance query per vertex (a sphere of 1e-9 m; triangles only, so on the
// triangle surface). Prints milliseconds per evaluation and the ratios; checks the tree's answer
// equals the brute force's on the timed vertices and FCL's distances ours.
//
//   bench_surface_search [grid sizes n, default 8,16,32,64,128]
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <vector>

#include "bench/command_line.h"
#include "contact/geometry/sphere_surface.h"
#include "contact/pcm/bvh.h"
#include "contact/pcm/nearest_face.h"

namespace {

using flexmbs::contact::Bvh;
using flexmbs::contact::BvhSplit;
using flexmbs::contact::MeshPoint;
using flexmbs::contact::PolygonMesh;

/// The square [0, 0.2]^2 m in n x n quads (or each split into two triangles) at height z [m],
/// bent by a wave of 1 mm (a flexible plate's small deformation) with phase `phase`.
PolygonMesh Grid(int n, double z, bool triangles, double phase) {
  PolygonMesh mesh;
  mesh.vertices_W.resize(3, (n + 1) * (n + 1));
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const double x = 0.2 * i / n, y = 0.2 * j / n;
      mesh.vertices_W.col(j * (n + 1) + i) = Eigen::Vector3d(x, y, z + 1e-3 * std::sin(30.0 * x + phase) * std::cos(20.0 * y));
    }
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const int v = j * (n + 1) + i;
      if (triangles) {
        mesh.face_sizes.insert(mesh.face_sizes.end(), {3, 3});
        mesh.face_vertices.insert(mesh.face_vertices.end(), {v, v + 1, v + n + 2, v, v + n + 2, v + n + 1});
      } else {
        mesh.face_sizes.push_back(4);
        mesh.face_vertices.insert(mesh.face_vertices.end(), {v, v + 1, v + n + 2, v + n + 1});
      }
    }
  }
  return mesh;
}

/// The fastest of `repeat` runs of f [s] (a shared machine: the minimum is the steadiest).
double Fastest(int repeat, const std::function<void()>& f) {
  double best = HUGE_VAL;
  for (int r = 0; r < repeat; ++r) {
    const auto start = std::chrono::steady_clock::now();
    f();
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return best;
}

/// FCL's model of a triangle mesh, built.
std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> FclModel(const PolygonMesh& mesh) {
  std::vector<fcl::Vector3d> points(static_cast<std::size_t>(mesh.vertices_W.cols()));
  for (std::size_t v = 0; v < points.size(); ++v) points[v] = mesh.vertices_W.col(static_cast<Eigen::Index>(v));
  std::vector<fcl::Triangle> triangles;
  for (std::size_t f = 0; f < mesh.face_sizes.size(); ++f) {
    triangles.emplace_back(mesh.face_vertices[3 * f], mesh.face_vertices[3 * f + 1], mesh.face_vertices[3 * f + 2]);
  }
  auto model = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  model->beginModel();
  model->addSubModel(points, triangles);
  model->endModel();
  return model;
}

/// Every point's distance to B by FCL: the model built, then a small sphere's distance query per point.
std::vector<double> FclDistances(const PolygonMesh& B, const PolygonMesh& A) {
  const fcl::CollisionObjectd object_B(FclModel(B), fcl::Transform3d::Identity());
  const double radius = 1e-9;
  fcl::CollisionObjectd point(std::make_shared<fcl::Sphered>(radius), fcl::Transform3d::Identity());
  std::vector<double> distances;
  distances.reserve(static_cast<std::size_t>(A.vertices_W.cols()));
  for (Eigen::Index v = 0; v < A.vertices_W.cols(); ++v) {
    point.setTranslation(A.vertices_W.col(v));
    point.computeAABB();
    fcl::DistanceRequestd request(false);
    fcl::DistanceResultd result;
    fcl::distance(&point, &object_B, request, result);
    distances.push_back(result.min_distance + radius);
  }
  return distances;
}

/// Every vertex of A against B through `tree` (built or refitted on B as it is now).
void TreeSearch(const PolygonMesh& A, const PolygonMesh& B, const Bvh& tree, std::vector<MeshPoint>* out) {
  out->clear();
  for (Eigen::Index v = 0; v < A.vertices_W.cols(); ++v) {
    out->push_back(flexmbs::contact::NearestMeshPoint(A.vertices_W.col(v), B, tree));
  }
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<int> sizes = flexmbs::bench::ParseIntList(argc > 1 ? argv[1] : "8,16,32,64,128");
  std::printf("surface_surface search per evaluation [ms]: A's (n+1)^2 vertices against B's faces, 2 mm apart\n");
  std::printf("%5s %7s %7s | %10s %10s %10s %10s %8s %8s | %10s %10s %10s %8s %9s\n", "n", "verts", "quads",
              "brute", "SAH build", "median", "refit", "brute/", "brute/", "tris", "SAH build", "FCL", "FCL/", "|d| diff");
  std::printf("%5s %7s %7s | %10s %10s %10s %10s %8s %8s | %10s %10s %10s %8s %9s\n", "", "", "", "", "+ queries",
              "+ queries", "+ queries", "SAH", "refit", "", "+ queries", "+ queries", "SAH", "[m]");
  for (const int n : sizes) {
    const PolygonMesh A = Grid(n, 2e-3, false, 0.7), B = Grid(n, 0.0, false, 0.0);
    const PolygonMesh rest_B = Grid(n, 0.0, false, 0.4);  // the tree as built at an earlier step
    const Eigen::Index verts = A.vertices_W.cols();
    const int repeat = n <= 32 ? 5 : 2;

    // Brute force on a sample of A's vertices, scaled to all; the tree's answers compared on it.
    const Eigen::Index sample = std::min<Eigen::Index>(verts, 1000);
    std::vector<MeshPoint> brute(static_cast<std::size_t>(sample));
    const double brute_s = Fastest(n <= 32 ? repeat : 1, [&] {
      for (Eigen::Index v = 0; v < sample; ++v) {
        brute[static_cast<std::size_t>(v)] = flexmbs::contact::NearestMeshPoint(A.vertices_W.col(v), B);
      }
    }) * static_cast<double>(verts) / static_cast<double>(sample);
    std::vector<MeshPoint> found;
    const double sah_s = Fastest(repeat, [&] { TreeSearch(A, B, Bvh(B), &found); });
    int differ = 0;
    for (Eigen::Index v = 0; v < sample; ++v) {
      const MeshPoint& a = brute[static_cast<std::size_t>(v)];
      const MeshPoint& b = found[static_cast<std::size_t>(v)];
      differ += !(a.point == b.point && a.vertices == b.vertices && a.weights == b.weights);
    }
    const double median_s = Fastest(repeat, [&] { TreeSearch(A, B, Bvh(B, 0.0, 4, BvhSplit::kMedian), &found); });
    Bvh kept(rest_B);
    const double refit_s = Fastest(repeat, [&] {
      kept.Refit(B);
      TreeSearch(A, B, kept, &found);
    });

    // On triangles: our SAH tree against FCL's OBBRSS model, both built per evaluation.
    const PolygonMesh At = Grid(n, 2e-3, true, 0.7), Bt = Grid(n, 0.0, true, 0.0);
    std::vector<MeshPoint> ours;
    const double tri_s = Fastest(repeat, [&] { TreeSearch(At, Bt, Bvh(Bt), &ours); });
    std::vector<double> fcl_distances;
    const double fcl_s = Fastest(repeat, [&] { fcl_distances = FclDistances(Bt, At); });
    double largest_difference = 0.0;
    for (Eigen::Index v = 0; v < verts; ++v) {
      const double d = (At.vertices_W.col(v) - ours[static_cast<std::size_t>(v)].point).norm();
      largest_difference = std::max(largest_difference, std::abs(d - fcl_distances[static_cast<std::size_t>(v)]));
    }
    std::printf("%5d %7lld %7zu | %10.3f %10.3f %10.3f %10.3f %8.1f %8.1f | %10zu %10.3f %10.3f %8.2f %9.1e%s\n", n,
                static_cast<long long>(verts), B.face_sizes.size(), 1e3 * brute_s, 1e3 * sah_s, 1e3 * median_s,
                1e3 * refit_s, brute_s / sah_s, brute_s / refit_s, Bt.face_sizes.size(), 1e3 * tri_s, 1e3 * fcl_s,
                fcl_s / tri_s, largest_difference, differ == 0 ? "" : "  TREE DIFFERS FROM BRUTE FORCE");
  }
  return 0;
}
