#include "contact/geometry/sphere_surface.h"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>

#include "core/error.h"

namespace flexmbs::contact {
namespace {

/// The nearest point of one triangle of the mesh, with its vertices.
struct Candidate {
  TrianglePoint nearest;
  std::array<int, 3> vertices{0, 0, 0};
};

TrianglePoint OnVertex(const Eigen::Vector3d& point, int vertex) {
  TrianglePoint out;
  out.point = point;
  out.weights(vertex) = 1.0;
  return out;
}

TrianglePoint OnEdge(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double s, int i, int j) {
  TrianglePoint out;
  out.point = from + s * (to - from);
  out.weights(i) = 1.0 - s;
  out.weights(j) = s;
  return out;
}

}  // namespace

TrianglePoint NearestPointOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                     const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return OnVertex(a, 0);
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return OnVertex(b, 1);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return OnEdge(a, b, d1 / (d1 - d3), 0, 1);
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return OnVertex(c, 2);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return OnEdge(a, c, d2 / (d2 - d6), 0, 2);
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) return OnEdge(b, c, (d4 - d3) / ((d4 - d3) + (d5 - d6)), 1, 2);
  const double denominator = 1.0 / (va + vb + vc);
  TrianglePoint out;
  out.weights = Eigen::Vector3d(va, vb, vc) * denominator;
  out.point = out.weights(0) * a + out.weights(1) * b + out.weights(2) * c;
  out.interior = true;
  return out;
}

SphereMeshContact SphereMesh(const Sphere& sphere, const PolygonMesh& mesh) {
  FLEXMBS_CHECK(sphere.radius > 0.0, "SphereMesh: the radius must be > 0");
  Candidate best;
  double best_distance = std::numeric_limits<double>::infinity();
  std::size_t first = 0;
  for (const int size : mesh.face_sizes) {
    FLEXMBS_CHECK((size == 3 || size == 4) && first + static_cast<std::size_t>(size) <= mesh.face_vertices.size(),
                  "SphereMesh: faces have 3 or 4 vertices");
    for (int split = 0; split + 2 < size; ++split) {
      const std::array<int, 3> v{mesh.face_vertices[first], mesh.face_vertices[first + 1 + split],
                                 mesh.face_vertices[first + 2 + split]};
      for (const int vertex : v) {
        FLEXMBS_CHECK(vertex >= 0 && vertex < mesh.vertices_W.cols(), "SphereMesh: a face vertex out of range");
      }
      const TrianglePoint nearest = NearestPointOnTriangle(sphere.p_WS_W, mesh.vertices_W.col(v[0]),
                                                           mesh.vertices_W.col(v[1]), mesh.vertices_W.col(v[2]));
      const double distance = (sphere.p_WS_W - nearest.point).norm();
      if (distance < best_distance) {
        best_distance = distance;
        best = {nearest, v};
      }
    }
    first += static_cast<std::size_t>(size);
  }
  FLEXMBS_CHECK(std::isfinite(best_distance), "SphereMesh: a mesh without faces");
  SphereMeshContact contact;
  contact.vertices = best.vertices;
  contact.weights = best.nearest.weights;
  contact.p_WB_W = best.nearest.point;
  if (best.nearest.interior) {
    const Eigen::Vector3d a = mesh.vertices_W.col(best.vertices[0]);
    contact.n_W = (mesh.vertices_W.col(best.vertices[1]) - a).cross(mesh.vertices_W.col(best.vertices[2]) - a).normalized();
    contact.g_N = contact.n_W.dot(sphere.p_WS_W - contact.p_WB_W) - sphere.radius;
  } else {
    if (!(best_distance > 1e-12 * sphere.radius)) {
      throw DegenerateContactError(fmt::format(
          "sphere-surface contact: the sphere's centre lies on the surface's edge (distance {:.3g} m): no normal",
          best_distance));
    }
    contact.n_W = (sphere.p_WS_W - contact.p_WB_W) / best_distance;
    contact.g_N = best_distance - sphere.radius;
  }
  contact.p_WA_W = sphere.p_WS_W - sphere.radius * contact.n_W;
  TangentBasis(contact.n_W, &contact.t1_W, &contact.t2_W);
  return contact;
}

}  // namespace flexmbs::contact
