#pragma once
// A sphere (in a planar scene: a circle) against a finite segment whose ends act as corners, as a
// unilateral contact (docs/contact.md, "Planar scenes"; scene type sphere_segment).

#include <Eigen/Core>
#include <string>
#include <string_view>

#include "mbs/unilateral_contact.h"

namespace flexmbs::mbs {

/// A sphere of radius r [m] centred on marker S (body A) against the segment from p_ME1_M to
/// p_ME2_M [m] in the frame of marker M (body B), extruded along M's z axis (contact::Segment: the
/// top of a solid, outward normal z_M x (E2 - E1) / |E2 - E1|, the free side on the left walking
/// from E1 to E2; the ends are corners, the solid's sides beneath them planes). One point, W_N and
/// W_T through the material points at the contact points (a corner is B's material point there).
class SphereSegmentUnilateral final : public ShapePairUnilateral {
 public:
  /// radius > 0 [m], the ends finite, apart and at one height along M's z (|(E2 - E1) . z_M| <=
  /// 1e-9 |E2 - E1|); InputError naming the contact and the value otherwise (and as
  /// UnilateralContact).
  SphereSegmentUnilateral(std::string name, MarkerRef sphere, MarkerRef segment,
                          const Eigen::Vector3d& p_ME1_M, const Eigen::Vector3d& p_ME2_M,
                          double radius, UnilateralLaw law);
  std::string_view type() const override { return "sphere_segment"; }

 private:
  UnilateralContactKinematics Geometry(const MarkerKinematics& a,
                                       const MarkerKinematics& b) const override;
  Eigen::Vector3d p_ME1_M_, p_ME2_M_;
  double radius_;
};

}  // namespace flexmbs::mbs
