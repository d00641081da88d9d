#pragma once
// The contact search of a rigid spur gear pair (docs/contact.md, "Spur gears"): every tooth pair
// that can mesh, on both lines of action, with its signed distance along the line, the exact
// normal gap of two involutes.

#include <Eigen/Core>
#include <vector>

#include "contact/gears/gear_flank.h"
#include "contact/gears/spur_gear.h"

namespace flexmbs::contact {

/// Where a tooth pair touches: both involutes on the line of action, or one tooth's tip corner
/// (where its involute meets the tip circle) on the other's involute, off the line: a pair under
/// load whose flank point on the line lies beyond a tip, before the path of contact's start
/// (wheel 2's corner) or after its end (wheel 1's).
enum class ToothContact { kFlanks, kTip1OnFlank2, kTip2OnFlank1 };

/// One tooth of wheel 1 facing one tooth of wheel 2 across a line of action, or a tip corner
/// facing the other tooth's flank along that flank's normal.
struct ToothPair {
  FlankSide side = FlankSide::kPositive;  ///< the flanks (and the line of action) they meet on
  int tooth1 = 0, tooth2 = 0;             ///< tooth indices, 0 ... z - 1 (FlankPoint)
  ToothContact contact = ToothContact::kFlanks;  ///< flanks on the line, or a tip corner
  /// t1, t2 [rad]: the roll angles of the flank points on the line; for a corner the tip's
  /// (tan(alpha_a)) and the foot's on the other flank (FootOnFlank).
  double roll1 = 0.0, roll2 = 0.0;
  /// g [m]: the distance from wheel 1's flank to wheel 2's along the line of action (for a
  /// corner: from the flank to the corner along the flank's normal); > 0 apart, < 0 penetration
  /// (the teeth overlap by -g).
  double gap = 0.0;
  /// The middle of the two flank points (or of the corner and its foot) [m], in the pair frame.
  Eigen::Vector2d p_O1C = Eigen::Vector2d::Zero();
  /// The unit direction along which wheel 1 pushes wheel 2: on the line of action wheel 1's
  /// flank's outward normal n_12 = (sin alpha_w, sigma cos alpha_w); for a corner the normal of
  /// the flank it touches (wheel 1's outward, or wheel 2's inward), off the line.
  Eigen::Vector2d n_12 = Eigen::Vector2d::UnitX();
};

/// The tooth pairs of `pair` that can mesh at centre distance a [m] (> r_b1 + r_b2; the pair's own
/// or the current one of moving axes) and wheel angles phi1, phi2 [rad] (FlankPoint), on both
/// sides. On side sigma the line of action touches the base circles at T1 = r_b1 (cos alpha_w,
/// -sigma sin alpha_w) and T2 = O2 - T1 (alpha_w = acos((r_b1 + r_b2) / a)); wheel 1's flank of
/// tooth k crosses it at s1 = r_b1 t1 from T1, t1 = alpha_w + sigma (phi1 + 2 pi k / z1) + psi_b1,
/// wheel 2's at s2 = a sin(alpha_w) - r_b2 t2, t2 = alpha_w + pi + sigma (phi2 + 2 pi k / z2) +
/// psi_b2, both normal to the line there, so the gap g = s2 - s1 = a sin(alpha_w) - r_b1 t1 - r_b2
/// t2 is the exact normal distance of the two flanks, plus both teeth's tip relief (TipRelief at
/// t1 and t2: the relieved flanks taken as the involutes moved in along the line; a relief's
/// slope turns the normal by C_a / L_Ca at most, left out). A pair is listed where both flank points
/// exist (0 <= t_i <= tan(alpha_ai)); wheel 2's tooth is the one whose gap lies within half a base
/// pitch of half the backlash at a (PairBacklash). With pair.tip_corners, a pair whose flank
/// point on the line lies beyond wheel 2's tip (t2 > tan(alpha_a2), before the path's start) is
/// listed as wheel 2's tip corner on wheel 1's flank (kTip2OnFlank1: FootOnFlank of the corner,
/// FlankPoint at tan(alpha_a2), with roll1 the foot's, listed where the foot lies on the flank),
/// one beyond wheel 1's tip as kTip1OnFlank2; the corners' gaps add the tip relief at both ends
/// (the corner's C_a, the foot's). At the path's ends a corner's gap equals the line's, so the
/// pair's gap runs on without a step; a corner touches only where the line's extension
/// overlaps (under load: docs/contact.md, "Corner contact").
std::vector<ToothPair> MeshingToothPairs(const GearPair& pair, double centre_distance, double phi1,
                                         double phi2);

/// The smallest gap [m] among the flank pairs (ToothContact::kFlanks) of `pairs` on `side`;
/// +infinity if none is on it. Corners are left out: they never touch first (a rigid pair's
/// corners stand off its flanks' gap), and the rigid transmission is the involutes'.
double SmallestGap(const std::vector<ToothPair>& pairs, FlankSide side);

/// Wheel 2's angle [rad] nearest phi2_guess at which the teeth touch on `side` (smallest gap 0)
/// with wheel 1 at phi1: the rigid kinematic transmission. From dg/dphi2 = -sigma r_b2, each
/// step turns wheel 2 by sigma g / r_b2 until |g| <= 1e-15 a.
double TouchingAngle2(const GearPair& pair, double centre_distance, double phi1, double phi2_guess,
                      FlankSide side);

}  // namespace flexmbs::contact
