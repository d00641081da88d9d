#include "contact/geometry/sphere_surface.h"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"

namespace flexmbs::contact {
namespace {

/// The bilinear shape functions at (xi, eta).
Eigen::Vector4d Bilinear(double xi, double eta) {
  return {(1.0 - xi) * (1.0 - eta), xi * (1.0 - eta), xi * eta, (1.0 - xi) * eta};
}

/// The nearest point of the quad's four edges to p.
QuadPoint NearestOnQuadEdges(const Eigen::Vector3d& p, const std::array<Eigen::Vector3d, 4>& P) {
  QuadPoint best;
  double best_distance = HUGE_VAL;
  for (int i = 0; i < 4; ++i) {
    const int j = (i + 1) % 4;
    const Eigen::Vector3d edge = P[static_cast<std::size_t>(j)] - P[static_cast<std::size_t>(i)];
    const double s = std::clamp(edge.dot(p - P[static_cast<std::size_t>(i)]) / edge.squaredNorm(), 0.0, 1.0);
    const Eigen::Vector3d point = P[static_cast<std::size_t>(i)] + s * edge;
    if ((point - p).norm() < best_distance) {
      best_distance = (point - p).norm();
      best.point = point;
      best.weights.setZero();
      best.weights(i) = 1.0 - s;
      best.weights(j) = s;
    }
  }
  return best;
}

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

QuadPoint NearestPointOnQuad(const Eigen::Vector3d& p, const std::array<Eigen::Vector3d, 4>& P) {
  double xi = 0.5, eta = 0.5;
  for (int iteration = 0; iteration < 20; ++iteration) {
    const Eigen::Vector4d N = Bilinear(xi, eta);
    const Eigen::Vector3d X = N(0) * P[0] + N(1) * P[1] + N(2) * P[2] + N(3) * P[3];
    const Eigen::Vector3d X_xi = (1.0 - eta) * (P[1] - P[0]) + eta * (P[2] - P[3]);
    const Eigen::Vector3d X_eta = (1.0 - xi) * (P[3] - P[0]) + xi * (P[2] - P[1]);
    Eigen::Matrix<double, 3, 2> J;
    J << X_xi, X_eta;
    const Eigen::Vector2d step = (J.transpose() * J).ldlt().solve(-J.transpose() * (X - p));
    xi += step(0);
    eta += step(1);
    if (step.norm() <= 1e-14 || !(std::abs(xi) < 10.0 && std::abs(eta) < 10.0)) break;
  }
  constexpr double kInside = 1e-12;
  if (!(xi >= -kInside && xi <= 1.0 + kInside && eta >= -kInside && eta <= 1.0 + kInside)) {
    return NearestOnQuadEdges(p, P);
  }
  xi = std::clamp(xi, 0.0, 1.0);
  eta = std::clamp(eta, 0.0, 1.0);
  QuadPoint out;
  out.weights = Bilinear(xi, eta);
  out.point = out.weights(0) * P[0] + out.weights(1) * P[1] + out.weights(2) * P[2] + out.weights(3) * P[3];
  const Eigen::Vector3d X_xi = (1.0 - eta) * (P[1] - P[0]) + eta * (P[2] - P[3]);
  const Eigen::Vector3d X_eta = (1.0 - xi) * (P[3] - P[0]) + xi * (P[2] - P[1]);
  out.normal = X_xi.cross(X_eta).normalized();
  out.interior = true;
  return out;
}

MeshPoint NearestFacePoint(const Eigen::Vector3d& p, const PolygonMesh& mesh, std::size_t first, int size) {
  FLEXMBS_CHECK((size == 3 || size == 4) && first + static_cast<std::size_t>(size) <= mesh.face_vertices.size(),
                "NearestMeshPoint: faces have 3 or 4 vertices");
  MeshPoint face;
  std::array<Eigen::Vector3d, 4> P;
  for (int i = 0; i < size; ++i) {
    const int vertex = mesh.face_vertices[first + static_cast<std::size_t>(i)];
    FLEXMBS_CHECK(vertex >= 0 && vertex < mesh.vertices_W.cols(), "NearestMeshPoint: a face vertex out of range");
    face.vertices[static_cast<std::size_t>(i)] = vertex;
    P[static_cast<std::size_t>(i)] = mesh.vertices_W.col(vertex);
  }
  if (size == 3) {
    const TrianglePoint nearest = NearestPointOnTriangle(p, P[0], P[1], P[2]);
    face.point = nearest.point;
    face.weights.head<3>() = nearest.weights;
    face.normal = (P[1] - P[0]).cross(P[2] - P[0]).normalized();
    face.interior = nearest.interior;
  } else {
    const QuadPoint nearest = NearestPointOnQuad(p, P);
    face.point = nearest.point;
    face.weights = nearest.weights;
    face.normal = nearest.normal;
    face.interior = nearest.interior;
  }
  return face;
}

MeshPoint NearestMeshPoint(const Eigen::Vector3d& p, const PolygonMesh& mesh) {
  MeshPoint best;
  double best_distance = std::numeric_limits<double>::infinity();
  std::size_t first = 0;
  for (const int size : mesh.face_sizes) {
    const MeshPoint face = NearestFacePoint(p, mesh, first, size);
    const double distance = (p - face.point).norm();
    if (distance < best_distance) {
      best_distance = distance;
      best = face;
    }
    first += static_cast<std::size_t>(size);
  }
  FLEXMBS_CHECK(std::isfinite(best_distance), "NearestMeshPoint: a mesh without faces");
  return best;
}

SphereMeshContact SphereMesh(const Sphere& sphere, const PolygonMesh& mesh) {
  FLEXMBS_CHECK(sphere.radius > 0.0, "SphereMesh: the radius must be > 0");
  const MeshPoint nearest = NearestMeshPoint(sphere.p_WS_W, mesh);
  SphereMeshContact contact;
  contact.vertices = nearest.vertices;
  contact.weights = nearest.weights;
  contact.p_WB_W = nearest.point;
  if (nearest.interior) {
    contact.n_W = nearest.normal;
    contact.g_N = contact.n_W.dot(sphere.p_WS_W - contact.p_WB_W) - sphere.radius;
  } else {
    const double distance = (sphere.p_WS_W - nearest.point).norm();
    if (!(distance > 1e-12 * sphere.radius)) {
      throw DegenerateContactError(fmt::format(
          "sphere-surface contact: the sphere's centre lies on the surface's edge (distance {:.3g} m): no normal",
          distance));
    }
    contact.n_W = (sphere.p_WS_W - contact.p_WB_W) / distance;
    contact.g_N = distance - sphere.radius;
  }
  contact.p_WA_W = sphere.p_WS_W - sphere.radius * contact.n_W;
  TangentBasis(contact.n_W, &contact.t1_W, &contact.t2_W);
  return contact;
}

SphereMeshContact PointMesh(const Eigen::Vector3d& p_WA_W, const PolygonMesh& mesh) {
  return PointMeshAt(p_WA_W, NearestMeshPoint(p_WA_W, mesh));
}

SphereMeshContact PointMeshAt(const Eigen::Vector3d& p_WA_W, const MeshPoint& nearest) {
  SphereMeshContact contact;
  contact.vertices = nearest.vertices;
  contact.weights = nearest.weights;
  contact.p_WA_W = p_WA_W;
  contact.p_WB_W = nearest.point;
  const Eigen::Vector3d d = p_WA_W - nearest.point;
  const double along = nearest.normal.dot(d), distance = d.norm();
  if (nearest.interior || std::abs(along) >= (1.0 - 1e-9) * distance) {
    contact.n_W = nearest.normal;
    contact.g_N = along;
  } else {
    contact.n_W = d / distance;
    contact.g_N = distance;
  }
  TangentBasis(contact.n_W, &contact.t1_W, &contact.t2_W);
  return contact;
}

}  // namespace flexmbs::contact
