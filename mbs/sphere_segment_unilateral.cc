#include "mbs/sphere_segment_unilateral.h"

#include <fmt/format.h>

#include <cmath>
#include <utility>

#include "contact/geometry/sphere_segment.h"
#include "core/error.h"

namespace flexmbs::mbs {

SphereSegmentUnilateral::SphereSegmentUnilateral(std::string name, MarkerRef sphere,
                                                 MarkerRef segment, const Eigen::Vector3d& p_ME1_M,
                                                 const Eigen::Vector3d& p_ME2_M, double radius,
                                                 UnilateralLaw law)
    : ShapePairUnilateral(std::move(name), std::move(sphere), std::move(segment), law),
      p_ME1_M_(p_ME1_M),
      p_ME2_M_(p_ME2_M),
      radius_(radius) {
  if (!(radius_ > 0.0) || !std::isfinite(radius_)) {
    throw InputError(
        fmt::format("contact '{}': radius [m] {:g} must be finite and > 0", this->name(), radius_));
  }
  const Eigen::Vector3d span = p_ME2_M_ - p_ME1_M_;
  const std::string ends =
      fmt::format("({:g}, {:g}, {:g}) and ({:g}, {:g}, {:g}) m", p_ME1_M_.x(), p_ME1_M_.y(),
                  p_ME1_M_.z(), p_ME2_M_.x(), p_ME2_M_.y(), p_ME2_M_.z());
  if (!p_ME1_M_.allFinite() || !p_ME2_M_.allFinite() || !(span.norm() > 0.0)) {
    throw InputError(fmt::format("contact '{}': the segment's ends {} must be finite and apart",
                                 this->name(), ends));
  }
  if (std::abs(span.z()) > 1e-9 * span.norm()) {
    throw InputError(fmt::format(
        "contact '{}': the segment's ends {} must lie at one z of their marker (the segment "
        "is extruded along its z axis)",
        this->name(), ends));
  }
}

UnilateralContactKinematics SphereSegmentUnilateral::Geometry(const MarkerKinematics& a,
                                                              const MarkerKinematics& b) const {
  const Eigen::Vector3d p_WE1_W = b.p_WM_W + b.R_WM * p_ME1_M_,
                        p_WE2_W = b.p_WM_W + b.R_WM * p_ME2_M_;
  // The marker's z made exactly perpendicular to the segment (the ends lie at one z within 1e-9 of
  // their distance, and a node marker's frame is orthonormal to round-off only).
  const Eigen::Vector3d d_W = (p_WE2_W - p_WE1_W).normalized();
  const Eigen::Vector3d e_W = (b.R_WM.col(2) - b.R_WM.col(2).dot(d_W) * d_W).normalized();
  const contact::Segment segment{p_WE1_W, p_WE2_W, e_W};
  UnilateralContactKinematics k;
  static_cast<contact::PointContactKinematics&>(k) =
      contact::SphereSegment({a.p_WM_W, radius_}, segment);
  return k;
}

}  // namespace flexmbs::mbs
