// contact/geometry/sphere_surface.h: the nearest point of a triangle and of a warped bilinear quad
// against brute-force searches over their parameters, and a sphere against a polygon mesh above
// a face, beside an edge and with its centre on an edge; a point against a mesh (node to surface).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <random>

#include "contact/geometry/sphere_surface.h"
#include "tests/support/random_draws.h"

namespace flexmbs::contact {
namespace {

/// The triangle point nearest to p by sampling the barycentric coordinates on a grid of 1/n.
Eigen::Vector3d NearestBySampling(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                  const Eigen::Vector3d& c, int n) {
  Eigen::Vector3d best = a;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; i + j <= n; ++j) {
      const double u = static_cast<double>(i) / n, v = static_cast<double>(j) / n;
      const Eigen::Vector3d q = (1.0 - u - v) * a + u * b + v * c;
      if ((q - p).norm() < (best - p).norm()) best = q;
    }
  }
  return best;
}

TEST(SphereSurface, NearestPointOnTriangleIsTheSampledMinimumAndItsWeightsRebuildIt) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  const auto random_point = [&] { return flexmbs::testing::DrawVector3(coordinate, rng); };
  int interior = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Vector3d a = random_point(), b = random_point(), c = random_point();
    const Eigen::Vector3d p = 0.5 * random_point() + (a + b + c) / 3.0;
    const TrianglePoint nearest = NearestPointOnTriangle(p, a, b, c);
    const Eigen::Vector3d sampled = NearestBySampling(p, a, b, c, 400);
    // The grid's spacing is at most 2/400 of an edge of length <= 3.5: distances agree to it.
    EXPECT_LE((nearest.point - p).norm(), (sampled - p).norm() + 1e-12) << trial;
    EXPECT_NEAR((nearest.point - p).norm(), (sampled - p).norm(), 0.02) << trial;
    EXPECT_NEAR(nearest.weights.sum(), 1.0, 1e-12);
    EXPECT_GE(nearest.weights.minCoeff(), 0.0);
    EXPECT_LT((nearest.weights(0) * a + nearest.weights(1) * b + nearest.weights(2) * c - nearest.point).norm(), 1e-12);
    interior += nearest.interior;
  }
  EXPECT_GT(interior, 10);  // the trials reach faces, edges and vertices
  EXPECT_LT(interior, 190);
}

/// The unit square z = 0 as one quad, counter-clockwise seen from +z (outward normal +z).
PolygonMesh UnitSquare() {
  PolygonMesh mesh;
  mesh.vertices_W.resize(3, 4);
  mesh.vertices_W << 0, 1, 1, 0, 0, 0, 1, 1, 0, 0, 0, 0;
  mesh.face_sizes = {4};
  mesh.face_vertices = {0, 1, 2, 3};
  return mesh;
}

TEST(SphereSurface, SphereAboveAFaceBesideAnEdgeAndOnAnEdge) {
  const PolygonMesh square = UnitSquare();
  const SphereMeshContact above = SphereMesh({Eigen::Vector3d(0.25, 0.6, 0.3), 0.1}, square);
  EXPECT_NEAR((above.n_W - Eigen::Vector3d::UnitZ()).norm(), 0.0, 1e-15);
  EXPECT_NEAR(above.g_N, 0.2, 1e-15);
  EXPECT_LT((above.p_WB_W - Eigen::Vector3d(0.25, 0.6, 0.0)).norm(), 1e-15);
  EXPECT_LT((above.p_WA_W - Eigen::Vector3d(0.25, 0.6, 0.2)).norm(), 1e-15);
  Eigen::Vector3d rebuilt = Eigen::Vector3d::Zero();
  for (int i = 0; i < 4; ++i) {
    rebuilt += above.weights(i) * square.vertices_W.col(above.vertices[static_cast<std::size_t>(i)]);
  }
  // A flat square's bilinear weights at (0.25, 0.6).
  EXPECT_LT((above.weights - Eigen::Vector4d(0.75 * 0.4, 0.25 * 0.4, 0.25 * 0.6, 0.75 * 0.6)).norm(), 1e-15);
  EXPECT_LT((rebuilt - above.p_WB_W).norm(), 1e-15);
  EXPECT_NEAR(above.n_W.cross(above.t1_W).dot(above.t2_W), 1.0, 1e-15);

  // Beside the edge x = 1: the nearest point is on the edge, the normal towards the centre.
  const SphereMeshContact beside = SphereMesh({Eigen::Vector3d(1.3, 0.5, 0.4), 0.1}, square);
  EXPECT_LT((beside.p_WB_W - Eigen::Vector3d(1.0, 0.5, 0.0)).norm(), 1e-15);
  EXPECT_LT((beside.n_W - Eigen::Vector3d(0.6, 0.0, 0.8)).norm(), 1e-15);
  EXPECT_NEAR(beside.g_N, 0.4, 1e-15);

  // A centre on a quad's edge lies in the closed bilinear face: the face's normal, g_N = -r.
  const SphereMeshContact on_edge = SphereMesh({Eigen::Vector3d(1.0, 0.5, 0.0), 0.1}, square);
  EXPECT_LT((on_edge.n_W - Eigen::Vector3d::UnitZ()).norm(), 1e-15);
  EXPECT_NEAR(on_edge.g_N, -0.1, 1e-15);
  // On a triangle's edge it has no normal.
  PolygonMesh triangles = square;
  triangles.face_sizes = {3, 3};
  triangles.face_vertices = {0, 1, 2, 0, 2, 3};
  EXPECT_THROW(SphereMesh({Eigen::Vector3d(1.0, 0.5, 0.0), 0.1}, triangles), DegenerateContactError);
}

TEST(SphereSurface, NodeToSurfaceUsesTheFaceNormalOverTheFaceAndOnItsRimLine) {
  const PolygonMesh square = UnitSquare();
  // Inside the face's prism, above and below: the face normal, g_N its signed distance.
  const SphereMeshContact above = PointMesh(Eigen::Vector3d(0.3, 0.6, 0.2), square);
  EXPECT_LT((above.n_W - Eigen::Vector3d::UnitZ()).norm(), 1e-15);
  EXPECT_NEAR(above.g_N, 0.2, 1e-15);
  const SphereMeshContact below = PointMesh(Eigen::Vector3d(0.3, 0.6, -0.01), square);
  EXPECT_NEAR(below.g_N, -0.01, 1e-15);
  EXPECT_LT((below.p_WB_W - Eigen::Vector3d(0.3, 0.6, 0.0)).norm(), 1e-15);
  // A node level with a vertex (where two aligned meshes' nodes meet), on a triangle mesh whose
  // nearest point there is a vertex, not an interior point: still the face normal.
  PolygonMesh triangles = square;
  triangles.face_sizes = {3, 3};
  triangles.face_vertices = {0, 1, 2, 0, 2, 3};
  const SphereMeshContact corner = PointMesh(Eigen::Vector3d(1.0, 1.0, -1e-3), triangles);
  EXPECT_LT((corner.n_W - Eigen::Vector3d::UnitZ()).norm(), 1e-15);
  EXPECT_NEAR(corner.g_N, -1e-3, 1e-15);
  // Off the surface (beside an edge, below its plane): apart, the distance to the edge.
  const SphereMeshContact beside = PointMesh(Eigen::Vector3d(1.3, 0.5, -0.4), square);
  EXPECT_NEAR(beside.g_N, 0.5, 1e-15);
  EXPECT_LT((beside.n_W - Eigen::Vector3d(0.6, 0.0, -0.8)).norm(), 1e-15);
}

TEST(SphereSurface, NearestPointOnAWarpedQuadIsTheSampledMinimum) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> jitter(-0.1, 0.1);
  for (int trial = 0; trial < 50; ++trial) {
    std::array<Eigen::Vector3d, 4> P{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(1, 1, 0),
                                     Eigen::Vector3d(0, 1, 0)};
    for (Eigen::Vector3d& corner : P) corner += flexmbs::testing::DrawVector3(jitter, rng);
    const Eigen::Vector3d draw = flexmbs::testing::DrawVector3(jitter, rng);
    const Eigen::Vector3d p(0.2 + 0.6 * (draw.x() + 0.1) / 0.2, 0.5 + 3.0 * draw.y(), 0.3 + draw.z());
    const QuadPoint nearest = NearestPointOnQuad(p, P);
    double sampled = HUGE_VAL;  // the bilinear patch sampled on a 400 x 400 grid
    for (int i = 0; i <= 400; ++i) {
      for (int j = 0; j <= 400; ++j) {
        const double xi = i / 400.0, eta = j / 400.0;
        const Eigen::Vector3d X =
            (1 - xi) * (1 - eta) * P[0] + xi * (1 - eta) * P[1] + xi * eta * P[2] + (1 - xi) * eta * P[3];
        sampled = std::min(sampled, (X - p).norm());
      }
    }
    EXPECT_LE((nearest.point - p).norm(), sampled + 1e-12) << trial;
    EXPECT_NEAR((nearest.point - p).norm(), sampled, 1e-4) << trial;
    EXPECT_NEAR(nearest.weights.sum(), 1.0, 1e-12);
    Eigen::Vector3d rebuilt = Eigen::Vector3d::Zero();
    for (int i = 0; i < 4; ++i) rebuilt += nearest.weights(i) * P[static_cast<std::size_t>(i)];
    EXPECT_LT((rebuilt - nearest.point).norm(), 1e-12);
  }
}

}  // namespace
}  // namespace flexmbs::contact
