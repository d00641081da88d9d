#include "contact/geometry/sphere_segment.h"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <cmath>

#include "core/error.h"

namespace flexmbs::contact {
namespace {

/// Below this share of the radius the centre lies on an edge.
constexpr double kOnTheEdge = 1e-12;

}  // namespace

PointContactKinematics SphereSegment(const Sphere& sphere, const Segment& segment) {
  FLEXMBS_CHECK(sphere.radius > 0.0, "SphereSegment: the radius must be > 0");
  const Eigen::Vector3d span = segment.p_WE2_W - segment.p_WE1_W;
  const double length = span.norm();
  FLEXMBS_CHECK(length > 0.0, "SphereSegment: the segment's ends must differ");
  const Eigen::Vector3d d = span / length;
  FLEXMBS_CHECK(
      std::abs(segment.e_W.norm() - 1.0) <= 1e-9 && std::abs(segment.e_W.dot(d)) <= 1e-9,
      "SphereSegment: the extrusion axis must be a unit vector perpendicular to the segment");
  const Eigen::Vector3d n = segment.e_W.cross(d);
  const Eigen::Vector3d& c = sphere.p_WS_W;
  const double s = d.dot(c - segment.p_WE1_W);
  if (s >= 0.0 && s <= length) return SpherePlane(sphere, {segment.p_WE1_W, n});
  const Eigen::Vector3d& end = s < 0.0 ? segment.p_WE1_W : segment.p_WE2_W;
  if (!(n.dot(c - end) > 0.0)) return SpherePlane(sphere, {end, s < 0.0 ? Eigen::Vector3d(-d) : d});
  const Eigen::Vector3d q = end + segment.e_W * segment.e_W.dot(c - end);
  const double distance = (c - q).norm();
  if (!(distance > kOnTheEdge * sphere.radius)) {
    throw DegenerateContactError(
        fmt::format("sphere-segment contact: the centre lies on the segment's end (distance {:.3g} "
                    "m, radius {:g} m): no normal",
                    distance, sphere.radius));
  }
  PointContactKinematics contact;
  contact.n_W = (c - q) / distance;
  contact.g_N = distance - sphere.radius;
  contact.p_WA_W = c - sphere.radius * contact.n_W;
  contact.p_WB_W = q;
  TangentBasis(contact.n_W, &contact.t1_W, &contact.t2_W);
  return contact;
}

}  // namespace flexmbs::contact
