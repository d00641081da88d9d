#include "contact/gears/gear_flank.h"

#include <cmath>
#include <numbers>

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

}  // namespace flexmbs::contact
