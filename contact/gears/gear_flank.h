#pragma once
// The involute flanks of a spur gear's teeth in the transverse plane (docs/contact.md, "Spur
// gears"): every tooth's two flanks as functions of the roll angle, at the wheel's rotation.

#include <Eigen/Core>

#include "contact/gears/spur_gear.h"

namespace flexmbs::contact {

/// A tooth's flank by the way it faces: kPositive faces the wheel's positive turning (+z, counter-
/// clockwise), kNegative the other way. A pair meshes positive flank on positive flank (wheel 1
/// driving +z) or negative on negative.
enum class FlankSide { kNegative, kPositive };

/// sigma = +1 for kPositive, -1 for kNegative.
double Sign(FlankSide side);

/// The rotation angle phi [rad] of a wheel: tooth 0's centre line at phi from the pair frame's x
/// axis (the line of centres, docs/contact.md), tooth k's at phi + 2 pi k / z, turning about +z.
/// The flank of tooth k on `side` is the involute of the base circle that leaves it at
/// theta_0 = phi + 2 pi k / z + sigma psi_b (psi_b = gear.base_half_angle); at roll angle t >= 0
/// the string touches the base circle at beta = theta_0 - sigma t and the flank point is
///   p = r_b (u(beta) + sigma t u'(beta)),  u = (cos, sin), u' = (-sin, cos),
/// with the outward (tooth to space) normal sigma u'(beta). t runs from 0 (base circle) to
/// gear.tip_roll (tip circle). Returns p [m] from the wheel's centre, in the pair frame's axes.
Eigen::Vector2d FlankPoint(const SpurGear& gear, int tooth, FlankSide side, double roll,
                           double phi);

/// The flank's outward unit normal sigma u'(beta) at roll angle t (FlankPoint's terms).
Eigen::Vector2d FlankNormal(const SpurGear& gear, int tooth, FlankSide side, double roll,
                            double phi);

}  // namespace flexmbs::contact
