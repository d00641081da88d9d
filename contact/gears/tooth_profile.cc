#include "contact/gears/tooth_profile.h"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "contact/gears/gear_flank.h"
#include "contact/laws/law_checks.h"
#include "core/error.h"

namespace flexmbs::contact {
namespace {

/// The point v of the rack's world frame in the tooth frame after the wheel turned by phi
/// (counter-clockwise): Rot(-phi) v.
Eigen::Vector2d IntoWheel(double phi, const Eigen::Vector2d& v) {
  const double c = std::cos(phi), s = std::sin(phi);
  return {c * v.x() + s * v.y(), -s * v.x() + c * v.y()};
}

}  // namespace

Eigen::Vector2d ToothFlankPoint(const SpurGear& gear, double roll) {
  return FlankPoint(gear, 0, FlankSide::kNegative, roll, std::numbers::pi / 2.0);
}

Eigen::Vector2d ToothFlankNormal(const SpurGear& gear, double roll) {
  return FlankNormal(gear, 0, FlankSide::kNegative, roll, std::numbers::pi / 2.0);
}

ToothFlankProfile RightFlankProfile(const SpurGear& gear, double rack_tip_radius, int points) {
  FLEXMBS_CHECK(points >= 2, "RightFlankProfile needs two or more fillet points");
  RequireNonNegative("rack tip radius coefficient", rack_tip_radius);
  const SpurGearSpec& spec = gear.spec;
  const double m = spec.module, alpha = spec.pressure_angle, r = gear.pitch_radius;
  const double rho = rack_tip_radius * m;
  // The rack in its frame at phi = 0: datum line at Y = r + x m, the tooth that cuts the space on
  // the tooth's right centred at X = pi m / 2, its left flank X_f(Y) = pi m / 4 + (r + x m - Y)
  // tan(alpha); its tip line at the gear's root radius, the tip rounding's centre (X_c, Y_c).
  const double datum = r + spec.profile_shift * m;
  const double y_c = datum - spec.dedendum_coefficient * m + rho;
  const double x_c =
      std::numbers::pi * m / 4.0 + (datum - y_c) * std::tan(alpha) + rho / std::cos(alpha);
  if (x_c > std::numbers::pi * m / 2.0) {
    throw InputError(fmt::format(
        "rack tip radius {:.4g} m does not fit the generating rack's tip (its centre {:.4g} m past "
        "the rack tooth's middle)",
        rho, x_c - std::numbers::pi * m / 2.0));
  }
  const Eigen::Vector2d pitch_point(0.0, r);
  const auto envelope = [&](double phi) {
    const Eigen::Vector2d c(x_c - r * phi, y_c);
    return IntoWheel(phi, c - rho * (pitch_point - c).normalized());
  };
  const double phi_form = (x_c + (r - y_c) / std::tan(alpha)) / r;
  const double phi_root = x_c / r;
  ToothFlankProfile profile;
  for (int i = 0; i < points; ++i) {
    const double s = static_cast<double>(i) / (points - 1);
    profile.fillet.push_back(envelope(phi_root + s * (phi_form - phi_root)));
  }
  // Where the straight flank ends, Y_T = Y_c - rho sin(alpha), it generates the flank point on the
  // line of action (r - Y_T) / sin(alpha) from the pitch point towards T1, r sin(alpha) from T1.
  const double from_t1 =
      r * std::sin(alpha) - (r - (y_c - rho * std::sin(alpha))) / std::sin(alpha);
  if (!(from_t1 > 1e-9 * r)) {
    throw InputError(fmt::format(
        "teeth {}, profile shift {}: the generating rack's rounding (tip radius {:.4g} m) reaches "
        "the involute below the base circle ({:.4g} m past its tangent point: undercut)",
        spec.teeth, spec.profile_shift, rho, -from_t1));
  }
  profile.form_roll = from_t1 / gear.base_radius;
  return profile;
}

}  // namespace flexmbs::contact
