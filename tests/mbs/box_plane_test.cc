// A box against a plane (mbs/unilateral_contact.h, BoxPlaneUnilateral; docs/contact.md): W_N u is
// every corner's gap rate on a moving, turning box above a moving, tilted plane; a box dropped
// flat comes to rest on its four bottom corners with the weight's impulse; on an incline it sticks
// below the friction angle and slides with g (sin a - mu cos a) above it. The compliant box
// (mbs/contact_force.h, BoxPlaneContact) settles at its static sinkage.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <vector>

#include "contact/laws/normal_law.h"
#include "mbs/contact_force.h"
#include "mbs/moreau_jean.h"
#include "mbs/multibody_system.h"
#include "mbs/rigid_body.h"
#include "mbs/simulation.h"
#include "mbs/unilateral_contact.h"
#include "tests/mbs/moreau_jean_support.h"
#include "tests/mbs/rigid_test_support.h"

namespace flexmbs::mbs {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Eigen::VectorXd;

constexpr double kMass = 1.0, kG = 9.81;
const Vector3d kHalfExtents(0.1, 0.1, 0.05);  // [m]: a 0.2 x 0.2 x 0.1 m box

/// The inertia of the uniform box of kMass and kHalfExtents about its centre [kg m^2].
Matrix3d BoxInertia() {
  const Vector3d edges = 2.0 * kHalfExtents;
  return (kMass / 12.0 * Vector3d(edges.y() * edges.y() + edges.z() * edges.z(),
                                 edges.x() * edges.x() + edges.z() * edges.z(),
                                 edges.x() * edges.x() + edges.y() * edges.y()))
      .asDiagonal();
}

/// A box of kMass (uniform) with the marker "centre" at its centre, against the plane through
/// W's origin tilted by `angle` [rad] about W's y axis (law e = 0, mu), gravity -z; the box rests
/// on the plane, flat, `gap` [m] above it. Down the slope is (cos a, 0, -sin a).
testing::ContactScene BoxOnPlane(double angle, double friction, double gap) {
  testing::ContactScene scene{std::make_unique<MultibodySystem>(Vector3d(0.0, 0.0, -kG)), VectorXd()};
  MultibodySystem& system = *scene.system;
  system.AddBody(std::make_unique<RigidBody>("box", kMass, Vector3d::Zero(), BoxInertia(),
                                             std::vector<RigidBodyMarker>{{"centre"}}));
  const Matrix3d R_WP = Eigen::AngleAxisd(angle, Vector3d::UnitY()).toRotationMatrix();
  system.AddUnilateralContact(std::make_unique<BoxPlaneUnilateral>("floor", system.Marker("box", "centre"),
                                                                   kHalfExtents, MarkerRef::Ground(Vector3d::Zero(), R_WP),
                                                                   UnilateralLaw{0.0, friction}));
  scene.y0 = system.NeutralState();
  VectorXd u = VectorXd::Zero(6);
  system.SetBodyState(0, testing::RigidPositions(R_WP * Vector3d(0.0, 0.0, kHalfExtents.z() + gap), R_WP), u, scene.y0);
  return scene;
}

TEST(BoxPlane, JacobianGivesEveryCornersGapRate) {
  std::mt19937 rng(3);
  MultibodySystem system(Vector3d::Zero());
  system.AddBody(testing::RandomRigidBody(rng, "box", 1));  // the box about its marker m0
  system.AddBody(testing::RandomRigidBody(rng, "table", 1));  // the plane through its marker m0
  system.AddUnilateralContact(std::make_unique<BoxPlaneUnilateral>(
      "floor", system.Marker("box", "m0"), kHalfExtents, system.Marker("table", "m0"), UnilateralLaw{}));
  VectorXd y = system.NeutralState();
  for (int b = 0; b < 2; ++b) {
    VectorXd u(6);
    u << testing::RandomVector(rng, 0.5), testing::RandomVector(rng, 2.0);
    system.SetBodyState(b, testing::RigidPositions(testing::RandomVector(rng, 0.3), testing::RandomRotation(rng)), u, y);
  }
  const UnilateralContact& contact = system.unilateral_contact(0);
  const double dt = 1e-6;
  const std::vector<UnilateralContactKinematics> points = contact.Evaluate(0.0, system, y);
  const std::vector<UnilateralContactKinematics> ahead = contact.Evaluate(0.0, system, testing::Advance(system, y, dt));
  const std::vector<UnilateralContactKinematics> behind =
      contact.Evaluate(0.0, system, testing::Advance(system, y, -dt));
  ASSERT_EQ(points.size(), 8u);
  double largest = 0.0;
  for (std::size_t p = 0; p < points.size(); ++p) {
    const double rate = (ahead[p].g_N - behind[p].g_N) / (2.0 * dt);
    largest = std::max(largest, std::abs(points[p].W_N.dot(y.tail(12)) - rate));
  }
  std::printf("box on plane: largest |W_N u - dg/dt| %.3e m/s over 8 corners\n", largest);
  EXPECT_LT(largest, 1e-9);  // central differences O(dt^2) and round-off: measured 1.0e-10
}

TEST(BoxPlane, DroppedBoxRestsOnItsFourBottomCorners) {
  testing::ContactScene scene = BoxOnPlane(0.0, 0.0, 0.01);
  const double h = 1e-3;
  const testing::StepHistory history = testing::RunMoreauJean(scene, h, 0.2);
  const MoreauJeanStepReport& last = history.steps.back();
  std::printf("box dropped 1 cm flat: %d corners active at the end, impulse per step %.12g N s (m g h = %.12g)\n",
              last.active_contacts, last.contacts[0].P_N, kMass * kG * h);
  EXPECT_EQ(last.active_contacts, 4);
  EXPECT_EQ(last.contacts[0].active_points, 4);
  EXPECT_NEAR(last.contacts[0].P_N, kMass * kG * h, 1e-14);
  EXPECT_LT(history.y.back().segment<6>(7).norm(), 1e-12);  // at rest
}

TEST(BoxPlane, BoxOnAnInclineSticksBelowAndSlidesAboveTheFrictionAngle) {
  const double h = 1e-3;
  testing::ContactScene sticking = BoxOnPlane(0.35, 0.5, -1e-12);
  const testing::StepHistory stuck = testing::RunMoreauJean(sticking, h, 0.5);
  double speed = 0.0;
  for (const VectorXd& y : stuck.y) speed = std::max(speed, y.segment<3>(7).norm());
  testing::ContactScene sliding = BoxOnPlane(0.5, 0.3, -1e-12);
  const testing::StepHistory slid = testing::RunMoreauJean(sliding, h, 0.5);
  const double a = kG * (std::sin(0.5) - 0.3 * std::cos(0.5));
  const Vector3d down_slope(std::cos(0.5), 0.0, -std::sin(0.5));
  double worst = 0.0;
  for (std::size_t k = 0; k < slid.t.size(); ++k) {
    worst = std::max(worst, std::abs(slid.y[k].segment<3>(7).dot(down_slope) - a * slid.t[k]));
  }
  std::printf("box on an incline: sticking speed <= %.3e m/s; sliding velocity off g (sin a - mu cos a) t by %.3e m/s\n",
              speed, worst);
  EXPECT_LT(speed, 1.5e-12);  // measured 1.4e-13 (the friction solver's tolerance on ~m g h / 4)
  EXPECT_LT(worst, 6e-13);    // measured 6.0e-14
}

TEST(BoxPlane, CompliantBoxSettlesAtItsStaticSinkage) {
  // The penalty counterpart (box_plane_contact): a linear spring k per corner, damped; the flat
  // box comes to rest sunk by m g / (4 k) on its four bottom corners.
  constexpr double kStiffness = 1e5, kDamping = 200.0;  // [N/m], [N s/m] per corner
  MultibodySystem system(Vector3d(0.0, 0.0, -kG));
  system.AddBody(std::make_unique<RigidBody>("box", kMass, Vector3d::Zero(), BoxInertia(),
                                             std::vector<RigidBodyMarker>{{"centre"}}));
  auto element = std::make_unique<BoxPlaneContact>("floor", system.Marker("box", "centre"), kHalfExtents,
                                                   MarkerRef::Ground(Vector3d::Zero()),
                                                   CompliantContactLaw{contact::LinearLaw(kStiffness, kDamping), {}});
  const BoxPlaneContact* floor = element.get();
  system.AddForceElement(std::move(element));
  VectorXd y = system.NeutralState();
  system.SetBodyState(0, testing::RigidPositions(Vector3d(0.0, 0.0, kHalfExtents.z() + 1e-3), Matrix3d::Identity()),
                      VectorXd::Zero(6), y);
  SimulationOptions options;
  options.end_time = 1.0;
  options.output_interval = 0.01;
  options.integrator.method = OdeMethod::kImplicit;
  options.integrator.relative_tolerance = 1e-10;
  options.integrator.absolute_tolerance = 1e-13;
  Simulate(system, options, y, [&](double, const VectorXd& sample, const VectorXd&) { y = sample; });
  const double sinkage = kHalfExtents.z() - y(2), expected = kMass * kG / (4.0 * kStiffness);
  std::printf("compliant box: sunk %.9e m against m g / (4 k) = %.9e m (%.2e), carried %.9f N, speed %.2e m/s\n",
              sinkage, expected, sinkage / expected - 1.0, floor->NormalForce(system, y), y.segment<6>(7).norm());
  EXPECT_NEAR(sinkage / expected, 1.0, 5e-12);                   // measured 4.6e-13
  EXPECT_NEAR(floor->NormalForce(system, y), kMass * kG, 1.5e-9);  // measured 1.4e-10 (spring and damper)
  ASSERT_EQ(floor->ContactLoads(1.0, system, y).size(), 4u);  // the bottom corners
}

}  // namespace
}  // namespace flexmbs::mbs
