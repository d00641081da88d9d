#include "contact/laws/friction.h"

#include <cmath>

#include "contact/laws/law_checks.h"

namespace flexmbs::contact {

RegularisedCoulomb MakeRegularisedCoulomb(double coefficient, double regularisation_speed) {
  RequireNonNegative("friction coefficient", coefficient);
  RequirePositive("friction regularisation speed [m/s]", regularisation_speed);
  return {coefficient, regularisation_speed};
}

TangentialForce Evaluate(const RegularisedCoulomb& friction, const Eigen::Vector3d& slip_velocity,
                         double normal_force) {
  const double eps = friction.regularisation_speed;
  const double s = std::sqrt(slip_velocity.squaredNorm() + eps * eps);
  const Eigen::Vector3d direction = slip_velocity / s;  // |direction| < 1, smooth at v_T = 0
  const double scale = friction.coefficient * normal_force;
  TangentialForce out;
  out.force = -scale * direction;
  out.d_slip = -(scale / s) * (Eigen::Matrix3d::Identity() - direction * direction.transpose());
  out.d_normal_force = -friction.coefficient * direction;
  return out;
}

}  // namespace flexmbs::contact
