// contact/geometry: sphere-plane and sphere-sphere kinematics against hand-computed cases.
#include "contact/geometry/point_contact.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

namespace flexmbs::contact {
namespace {

constexpr double kRoundOff = 1e-14;

void ExpectRightHandedFrame(const PointContactKinematics& c) {
  EXPECT_NEAR(c.n_W.norm(), 1.0, kRoundOff);
  EXPECT_NEAR(c.t1_W.norm(), 1.0, kRoundOff);
  EXPECT_NEAR(c.t2_W.norm(), 1.0, kRoundOff);
  EXPECT_NEAR(c.n_W.dot(c.t1_W), 0.0, kRoundOff);
  EXPECT_NEAR(c.n_W.dot(c.t2_W), 0.0, kRoundOff);
  EXPECT_NEAR(c.t1_W.dot(c.t2_W), 0.0, kRoundOff);
  EXPECT_LT((c.n_W.cross(c.t1_W) - c.t2_W).norm(), kRoundOff);
}

TEST(PointContact, SphereAboveTheHorizontalPlaneHasGapHeightMinusRadius) {
  const PointContactKinematics c = SpherePlane({{0.3, -0.2, 1.1}, 0.1}, {{0.0, 0.0, 0.0}, Eigen::Vector3d::UnitZ()});
  EXPECT_NEAR(c.g_N, 1.0, kRoundOff);
  EXPECT_LT((c.n_W - Eigen::Vector3d::UnitZ()).norm(), kRoundOff);
  EXPECT_LT((c.t1_W - Eigen::Vector3d::UnitX()).norm(), kRoundOff);  // the documented choice for n = +z
  EXPECT_LT((c.t2_W - Eigen::Vector3d::UnitY()).norm(), kRoundOff);
  EXPECT_LT((c.p_WA_W - Eigen::Vector3d(0.3, -0.2, 1.0)).norm(), kRoundOff);
  EXPECT_LT((c.p_WB_W - Eigen::Vector3d(0.3, -0.2, 0.0)).norm(), kRoundOff);
  ExpectRightHandedFrame(c);
}

TEST(PointContact, SphereOnAnInclinedPlanePenetratesByTheDistanceAlongItsNormal) {
  const double angle = 0.4;
  const Eigen::Vector3d n(-std::sin(angle), 0.0, std::cos(angle));
  const Eigen::Vector3d p_WP_W(1.0, 2.0, 3.0);
  const Eigen::Vector3d along(std::cos(angle), 0.0, std::sin(angle));
  const Eigen::Vector3d centre = p_WP_W + 0.7 * along + 0.05 * n;  // 5 cm above, radius 8 cm
  const PointContactKinematics c = SpherePlane({centre, 0.08}, {p_WP_W, n});
  EXPECT_NEAR(c.g_N, -0.03, kRoundOff);
  EXPECT_LT((c.p_WB_W - (p_WP_W + 0.7 * along)).norm(), kRoundOff);
  EXPECT_LT((c.p_WA_W - c.p_WB_W - c.g_N * c.n_W).norm(), kRoundOff);
  ExpectRightHandedFrame(c);
}

TEST(PointContact, TangentBasisIsOrthonormalAndRightHandedForAnyNormal) {
  for (const Eigen::Vector3d& direction :
       {Eigen::Vector3d(0, 0, -1), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, -1, 0), Eigen::Vector3d(1, 2, 3),
        Eigen::Vector3d(-1, 1e-9, -1e-12), Eigen::Vector3d(0.3, -0.4, -1e-17)}) {
    PointContactKinematics c;
    c.n_W = direction.normalized();
    TangentBasis(c.n_W, &c.t1_W, &c.t2_W);
    ExpectRightHandedFrame(c);
  }
}

TEST(PointContact, TwoSpheresHaveGapDistanceMinusRadiiAndNormalFromBToA) {
  const PointContactKinematics c = SphereSphere({{0.0, 0.0, 0.5}, 0.2}, {{0.0, 0.4, 0.2}, 0.25});
  EXPECT_NEAR(c.g_N, 0.5 - 0.45, kRoundOff);
  EXPECT_LT((c.n_W - Eigen::Vector3d(0.0, -0.8, 0.6)).norm(), kRoundOff);
  EXPECT_LT((c.p_WA_W - Eigen::Vector3d(0.0, 0.16, 0.38)).norm(), kRoundOff);
  EXPECT_LT((c.p_WB_W - Eigen::Vector3d(0.0, 0.2, 0.35)).norm(), kRoundOff);
  EXPECT_LT((c.p_WA_W - c.p_WB_W - c.g_N * c.n_W).norm(), kRoundOff);
  ExpectRightHandedFrame(c);
}

TEST(PointContact, OverlappingSpheresHaveNegativeGap) {
  const PointContactKinematics c = SphereSphere({{0.1, 0.0, 0.0}, 0.1}, {{0.0, 0.0, 0.0}, 0.05});
  EXPECT_NEAR(c.g_N, -0.05, kRoundOff);
  EXPECT_LT((c.n_W - Eigen::Vector3d::UnitX()).norm(), kRoundOff);
}

TEST(PointContact, CoincidentCentresAreRefusedWithAClearError) {
  try {
    SphereSphere({{1.0, 1.0, 1.0}, 0.1}, {{1.0, 1.0, 1.0}, 0.2});
    FAIL() << "no error";
  } catch (const DegenerateContactError& e) {
    EXPECT_NE(std::string(e.what()).find("centres coincide"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace flexmbs::contact
