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

/// A point's place against an involute flank along the flank's normal (FootOnFlank).
struct FlankFoot {
  double roll = 0.0;  ///< t [rad] of the foot, the flank point whose normal runs through the point
  /// g [m]: the point's distance from the flank along its outward normal, > 0 outside the tooth.
  double gap = 0.0;
  Eigen::Vector2d normal = Eigen::Vector2d::UnitX();  ///< the flank's outward normal at the foot
};

/// The foot on the flank of `tooth` on `side` (FlankPoint's terms, wheel angle phi [rad]) of the
/// flank's normal through the point p_OP [m] (from the wheel's centre, pair-frame axes, outside
/// the base circle). An involute's normals are the base circle's tangents, and the flank crosses
/// each at right angles where its string is that tangent: the tangent from P touches the base
/// circle at beta_P = angle(p_OP) - sigma atan(L / r_b), L = sqrt(|p_OP|^2 - r_b^2), the flank's
/// point on it has roll t = sigma (theta_0 - beta_P) (taken, modulo 2 pi, nearest L / r_b), and P
/// lies g = L - r_b t from it along the normal sigma u'(beta_P). Exact, no iteration; the foot may
/// lie off the flank (t outside [0, tan(alpha_a)]), which the caller checks.
FlankFoot FootOnFlank(const SpurGear& gear, int tooth, FlankSide side, double phi,
                      const Eigen::Vector2d& p_OP);

}  // namespace flexmbs::contact
