#include "contact/gears/gear_flank.h"

#include <cmath>
#include <numbers>

#include "core/error.h"

namespace flexmbs::contact {
namespace {

/// beta = theta_0 - sigma t: where the flank's string touches the base circle at roll t.
double TangentAngle(const SpurGear& gear, int tooth, FlankSide side, double roll, double phi) {
  const double sigma = Sign(side);
  return phi + 2.0 * std::numbers::pi * tooth / gear.spec.teeth +
         sigma * (gear.base_half_angle - roll);
}

}  // namespace

double Sign(FlankSide side) { return side == FlankSide::kPositive ? 1.0 : -1.0; }

Eigen::Vector2d FlankPoint(const SpurGear& gear, int tooth, FlankSide side, double roll,
                           double phi) {
  const double beta = TangentAngle(gear, tooth, side, roll, phi);
  const Eigen::Vector2d u(std::cos(beta), std::sin(beta));
  const Eigen::Vector2d u_perp(-u.y(), u.x());
  return gear.base_radius * (u + Sign(side) * roll * u_perp);
}

Eigen::Vector2d FlankNormal(const SpurGear& gear, int tooth, FlankSide side, double roll,
                            double phi) {
  const double beta = TangentAngle(gear, tooth, side, roll, phi);
  return Sign(side) * Eigen::Vector2d(-std::sin(beta), std::cos(beta));
}

FlankFoot FootOnFlank(const SpurGear& gear, int tooth, FlankSide side, double phi,
                      const Eigen::Vector2d& p_OP) {
  const double sigma = Sign(side);
  const double r_b = gear.base_radius;
  const double radius = p_OP.norm();
  FLEXMBS_CHECK(radius > r_b, "FootOnFlank needs a point outside the base circle");
  const double string = std::sqrt((radius - r_b) * (radius + r_b));  // L
  const double beta = std::atan2(p_OP.y(), p_OP.x()) - sigma * std::atan2(string, r_b);
  const double theta_0 = TangentAngle(gear, tooth, side, 0.0, phi);
  const double roll = string / r_b + std::remainder(sigma * (theta_0 - beta) - string / r_b,
                                                    2.0 * std::numbers::pi);
  FlankFoot foot;
  foot.roll = roll;
  foot.gap = string - r_b * roll;
  foot.normal = sigma * Eigen::Vector2d(-std::sin(beta), std::cos(beta));
  return foot;
}

}  // namespace flexmbs::contact
