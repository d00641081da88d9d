// Euler parameters and rotation matrices (core/rotation.h).
#include "core/rotation.h"

#include <gtest/gtest.h>

namespace flexmbs {
namespace {

// Round-off of a few products of unit-size numbers.
constexpr double kRoundOff = 1e-14;

TEST(Rotation, EulerParametersRoundTripThroughTheRotationMatrix) {
  const Eigen::Vector4d e = Eigen::Vector4d(0.3, -0.5, 0.7, 0.1).normalized();
  const Eigen::Matrix3d R = RotationFromEulerParameters(e);
  EXPECT_LE((R.transpose() * R - Eigen::Matrix3d::Identity()).norm(), kRoundOff);
  EXPECT_LE((EulerParametersFromRotation(R) - e).norm(), kRoundOff);
  // The rotation of the axis (e1, e2, e3) leaves it fixed.
  EXPECT_LE((R * e.tail<3>() - e.tail<3>()).norm(), kRoundOff);
}

}  // namespace
}  // namespace flexmbs
