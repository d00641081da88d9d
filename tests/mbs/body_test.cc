// Body kinematics shared by every body: the Euler-parameter rate.
#include "mbs/body.h"

#include <gtest/gtest.h>

#include <cmath>


namespace flexmbs::mbs {
namespace {

// Round-off of a few products of unit-size numbers.
constexpr double kRoundOff = 1e-14;

TEST(PositionDerivative, EulerParameterRateIsTheDerivativeOfARotationAboutAFixedAxis) {
  // e(t) = (cos(w t / 2), sin(w t / 2) n) rotates about the fixed body axis n at rate w.
  const Eigen::Vector3d n = Eigen::Vector3d(1.0, -2.0, 0.5).normalized();
  const double w = 3.0, t = 0.7;
  Eigen::VectorXd x(9), u(8), xdot(9);
  x << 1.0, 2.0, 3.0, std::cos(w * t / 2), std::sin(w * t / 2) * n, 0.25, -0.5;
  u << 4.0, 5.0, 6.0, w * n, 7.0, 8.0;
  PositionDerivative(x, u, xdot);
  Eigen::VectorXd expected(9);
  expected << 4.0, 5.0, 6.0, -0.5 * w * std::sin(w * t / 2), 0.5 * w * std::cos(w * t / 2) * n, 7.0, 8.0;
  EXPECT_LE((xdot - expected).cwiseAbs().maxCoeff(), kRoundOff);
}

}  // namespace
}  // namespace flexmbs::mbs
