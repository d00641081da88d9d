#include "contact/geometry/point_contact.h"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "core/error.h"

namespace flexmbs::contact {
namespace {

/// Below this share of r_A + r_B the centres of two spheres count as coincident.
constexpr double kCoincidentCentres = 1e-12;

PointContactKinematics WithTangents(PointContactKinematics contact) {
  TangentBasis(contact.n_W, &contact.t1_W, &contact.t2_W);
  return contact;
}

}  // namespace

void TangentBasis(const Eigen::Vector3d& n_W, Eigen::Vector3d* t1_W, Eigen::Vector3d* t2_W) {
  const double sign = std::copysign(1.0, n_W.z());
  const double a = -1.0 / (sign + n_W.z());
  const double b = n_W.x() * n_W.y() * a;
  *t1_W = Eigen::Vector3d(1.0 + sign * n_W.x() * n_W.x() * a, sign * b, -sign * n_W.x());
  *t2_W = Eigen::Vector3d(b, sign + n_W.y() * n_W.y() * a, -n_W.y());
}

PointContactKinematics SpherePlane(const Sphere& sphere, const Plane& plane) {
  FLEXMBS_CHECK(sphere.radius > 0.0, "SpherePlane: the radius must be > 0");
  FLEXMBS_CHECK(std::abs(plane.n_W.norm() - 1.0) <= 1e-9, "SpherePlane: the plane's normal must be a unit vector");
  PointContactKinematics contact;
  contact.n_W = plane.n_W;
  const double height = plane.n_W.dot(sphere.p_WS_W - plane.p_WP_W);
  contact.g_N = height - sphere.radius;
  contact.p_WA_W = sphere.p_WS_W - sphere.radius * plane.n_W;
  contact.p_WB_W = sphere.p_WS_W - height * plane.n_W;
  return WithTangents(contact);
}

PointContactKinematics PointPlane(const Eigen::Vector3d& p_WA_W, const Plane& plane) {
  FLEXMBS_CHECK(std::abs(plane.n_W.norm() - 1.0) <= 1e-9, "PointPlane: the plane's normal must be a unit vector");
  PointContactKinematics contact;
  contact.n_W = plane.n_W;
  contact.g_N = plane.n_W.dot(p_WA_W - plane.p_WP_W);
  contact.p_WA_W = p_WA_W;
  contact.p_WB_W = p_WA_W - contact.g_N * plane.n_W;
  return WithTangents(contact);
}

std::array<Eigen::Vector3d, 8> BoxCorners(const Eigen::Vector3d& half_extents) {
  std::array<Eigen::Vector3d, 8> corners;
  for (int i = 0; i < 8; ++i) {
    corners[static_cast<std::size_t>(i)] =
        half_extents.cwiseProduct(Eigen::Vector3d(i & 1 ? 1.0 : -1.0, i & 2 ? 1.0 : -1.0, i & 4 ? 1.0 : -1.0));
  }
  return corners;
}

std::array<Eigen::Vector3d, 6> CylinderSupportPoints(double radius, double half_length, const Eigen::Vector3d& n_C) {
  FLEXMBS_CHECK(radius > 0.0 && half_length > 0.0, "CylinderSupportPoints: radius and half length must be > 0");
  const Eigen::Vector3d down(-n_C.x(), -n_C.y(), 0.0);  // -n_C projected onto the circles' plane
  constexpr double kAlongAxis = 1e-12;
  const Eigen::Vector3d d = down.norm() > kAlongAxis ? Eigen::Vector3d(down.normalized()) : Eigen::Vector3d::UnitX();
  const Eigen::Vector3d e(-d.y(), d.x(), 0.0);  // z x d
  constexpr double kThird = 2.0 * std::numbers::pi / 3.0;
  std::array<Eigen::Vector3d, 6> points;
  for (int end = 0; end < 2; ++end) {
    const Eigen::Vector3d centre(0.0, 0.0, end == 0 ? -half_length : half_length);
    for (int k = 0; k < 3; ++k) {
      const double angle = (k == 0 ? 0.0 : (k == 1 ? kThird : -kThird));
      points[static_cast<std::size_t>(3 * end + k)] = centre + radius * (std::cos(angle) * d + std::sin(angle) * e);
    }
  }
  return points;
}

PointContactKinematics SphereSphere(const Sphere& a, const Sphere& b) {
  FLEXMBS_CHECK(a.radius > 0.0 && b.radius > 0.0, "SphereSphere: the radii must be > 0");
  const Eigen::Vector3d d = a.p_WS_W - b.p_WS_W;
  const double length = d.norm();
  if (!(length > kCoincidentCentres * (a.radius + b.radius))) {
    throw DegenerateContactError(fmt::format(
        "sphere-sphere contact: the centres coincide (distance {:.3g} m, radii {:g} m and {:g} m): no normal", length,
        a.radius, b.radius));
  }
  PointContactKinematics contact;
  contact.n_W = d / length;
  contact.g_N = length - a.radius - b.radius;
  contact.p_WA_W = a.p_WS_W - a.radius * contact.n_W;
  contact.p_WB_W = b.p_WS_W + b.radius * contact.n_W;
  return WithTangents(contact);
}

}  // namespace flexmbs::contact
