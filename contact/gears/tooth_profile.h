#pragma once
// One tooth's outline as the generating rack cuts it (docs/contact.md, "Elastic teeth"): the
// involute flank and the root fillet, the trochoidal envelope of the rack's rounded tip. The FE
// tooth (gear_tooth_fe/) is built on it.

#include <Eigen/Core>
#include <vector>

#include "contact/gears/spur_gear.h"

namespace flexmbs::contact {

/// The right flank (facing -z turning, FlankSide::kNegative) of a tooth in the tooth frame: origin
/// at the wheel's centre, the tooth's centre line along +y; the left flank is its mirror in x.
struct ToothFlankProfile {
  /// The fillet from the root circle (first point, r_f) up to where the involute starts (last).
  std::vector<Eigen::Vector2d> fillet;
  /// t_F [rad]: the involute's roll angle where the fillet meets it (the form circle), > 0.
  double form_roll = 0.0;
};

/// The rack's tip rounding rho_fP / m of ISO 53's profile A (the basic rack).
inline constexpr double kBasicRackTipRadius = 0.38;

/// The flank point [m] at roll angle t [rad] of the right flank in the tooth frame
/// (contact::FlankPoint of tooth 0 on the negative side at phi = pi/2).
Eigen::Vector2d ToothFlankPoint(const SpurGear& gear, double roll);
/// Its outward (tooth to space) unit normal, along the line of action of a load there.
Eigen::Vector2d ToothFlankNormal(const SpurGear& gear, double roll);

/// The right flank's fillet of `gear` (unthinned, from MakeSpurGear) as the basic rack of its
/// dedendum h_f* m with tip radius rho = rack_tip_radius * m [m] generates it: the rack rolls
/// its datum line, x m out from the pitch circle, on the pitch circle; its tip circle's centre
/// C(phi) and the pitch point P give the envelope point C - rho (P - C) / |P - C| (the circle's
/// normal through the instantaneous centre), from phi_F = (X_c + (r - Y_c) / tan(alpha)) / r
/// (where the rack's straight flank ends) down to phi = X_c / r (the root circle), `points`
/// samples. The form roll t_F = (r sin(alpha) - (r - Y_T) / sin(alpha)) / r_b, Y_T = Y_c - rho
/// sin(alpha) where the straight flank ends. InputError when the rounding does not fit the rack's
/// tip, or when t_F <= 0 (the straight flank generates past the base circle's tangent point:
/// undercut).
ToothFlankProfile RightFlankProfile(const SpurGear& gear, double rack_tip_radius, int points);

}  // namespace flexmbs::contact
