// The unilateral cylinder-plane contact (mbs/unilateral_contact.h, CylinderPlaneUnilateral;
// contact::CylinderSupportPoints): the support points against the closed-form lowest rim points;
// a solid cylinder on an incline rolls with a = 2/3 g sin(alpha) where friction holds it and
// slides with a = g (sin(alpha) - mu cos(alpha)) where it does not, event-driven and Moreau-Jean
// to round-off; standing on an end face it rests on its weight; bad sizes are one-line errors.
#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>

#include "contact/geometry/point_contact.h"
#include "core/error.h"
#include "core/rotation.h"
#include "mbs/rigid_body.h"
#include "mbs/scene.h"
#include "mbs/unilateral_contact.h"
#include "tests/input_error.h"
#include "tests/mbs/moreau_jean_support.h"

namespace flexmbs::mbs {
namespace {

using Eigen::AngleAxisd;
using Eigen::Matrix3d;
using Eigen::Vector3d;
using Eigen::VectorXd;
using testing::ContactScene;

constexpr double kMass = 2.0, kRadius = 0.05, kLength = 0.2, kG = 9.81;

TEST(CylinderSupportPoints, AreTheLowestRimPointsAndTheirThirds) {
  // Against a plane whose normal in C is n_C, the lowest point of a rim lies at r d, d = -(n_C's
  // part across the axis) normalised: its height along n_C is the smallest on the circle.
  const Vector3d n_C = Vector3d(0.3, -0.5, 0.8).normalized();
  const auto points = contact::CylinderSupportPoints(kRadius, 0.5 * kLength, n_C);
  for (int end = 0; end < 2; ++end) {
    const double z = end == 0 ? -0.5 * kLength : 0.5 * kLength;
    double lowest = 1e300;
    for (int k = 0; k < 3600; ++k) {  // the rim sampled every 0.1 degrees
      const double angle = 2.0 * std::numbers::pi * k / 3600.0;
      lowest = std::min(lowest, n_C.dot(Vector3d(kRadius * std::cos(angle), kRadius * std::sin(angle), z)));
    }
    const Vector3d& low = points[static_cast<std::size_t>(3 * end)];
    EXPECT_NEAR(low.z(), z, 1e-15);
    EXPECT_NEAR(low.head<2>().norm(), kRadius, 1e-15);
    EXPECT_LE(n_C.dot(low), lowest + 1e-15);  // no sampled rim point is lower
    EXPECT_GT(n_C.dot(low), lowest - 1e-7);   // and the sampling's 0.1 degrees bound it
    for (int k = 1; k < 3; ++k) {
      const Vector3d& other = points[static_cast<std::size_t>(3 * end + k)];
      EXPECT_NEAR((other - low).norm(), std::sqrt(3.0) * kRadius, 1e-15);  // 120 degrees on the rim
    }
  }
  // Along the axis the lowest direction is undefined: C's x axis and its thirds.
  const auto standing = contact::CylinderSupportPoints(kRadius, 0.5 * kLength, Vector3d::UnitZ());
  EXPECT_TRUE(standing[0].isApprox(Vector3d(kRadius, 0.0, -0.5 * kLength)));
}

/// A solid cylinder (mass 2 kg, r = 0.05 m, l = 0.2 m) on a plane through W's origin tilted by
/// `angle` about W's y axis (down the slope (cos a, 0, -sin a)), its axis along W's y, touching
/// 1e-12 m deep at rest; or, with `standing`, upright on an end face on the flat plane.
ContactScene CylinderOnPlane(double angle, double friction, bool standing = false) {
  ContactScene scene{std::make_unique<MultibodySystem>(Vector3d(0.0, 0.0, -kG)), VectorXd()};
  MultibodySystem& system = *scene.system;
  const double axial = 0.5 * kMass * kRadius * kRadius,
               across = kMass * (3.0 * kRadius * kRadius + kLength * kLength) / 12.0;
  // Body frame: its y axis the cylinder's axis (standing: its z axis); the marker's z axis is it.
  const Matrix3d R_BM = standing ? Matrix3d::Identity() : AngleAxisd(-std::numbers::pi / 2.0, Vector3d::UnitX()).matrix();
  const Vector3d inertia_diagonal = standing ? Vector3d(across, across, axial) : Vector3d(across, axial, across);
  const int body = system.AddBody(std::make_unique<RigidBody>(
      "cylinder", kMass, Vector3d::Zero(), Matrix3d(inertia_diagonal.asDiagonal()),
      std::vector<RigidBodyMarker>{{"centre", Vector3d::Zero(), R_BM}}));
  const Matrix3d R_WP = AngleAxisd(angle, Vector3d::UnitY()).matrix();
  system.AddUnilateralContact(std::make_unique<CylinderPlaneUnilateral>(
      "floor", system.Marker("cylinder", "centre"), kRadius, kLength, MarkerRef::Ground(Vector3d::Zero(), R_WP),
      UnilateralLaw{0.0, friction}));
  scene.y0 = system.NeutralState();
  constexpr double kPenetration = 1e-12;
  const double height = (standing ? 0.5 * kLength : kRadius) - kPenetration;
  VectorXd x(7);
  x << R_WP * Vector3d(0.0, 0.0, height), EulerParametersFromRotation(R_WP);
  system.SetBodyState(body, x, VectorXd::Zero(6), scene.y0);
  return scene;
}

/// Distance and speed down the slope, and the spin about the axis (W's y) [rad/s].
struct Rolling {
  double distance, speed, spin;
};
Rolling Motion(const ContactScene& scene, const VectorXd& y, double angle) {
  const Vector3d down(std::cos(angle), 0.0, -std::sin(angle));
  const MultibodySystem& system = *scene.system;
  const Vector3d p = system.BodyPositions(y, 0).head<3>(), p0 = system.BodyPositions(scene.y0, 0).head<3>();
  const Matrix3d R_WB = RotationFromEulerParameters(system.BodyPositions(y, 0).segment<4>(3));
  return {(p - p0).dot(down), system.BodyVelocities(y, 0).head<3>().dot(down),
          (R_WB * system.BodyVelocities(y, 0).segment<3>(3)).y()};
}

TEST(CylinderPlane, RollsWhereFrictionHoldsItAndSlidesWhereItDoesNotEventDrivenToRoundOff) {
  // Rolling (mu >= tan(a)/3): a = 2/3 g sin a, spin = v / r. Sliding: a = g (sin a - mu cos a),
  // spin' = 2 mu g cos a / r.
  constexpr double angle = 0.3, kTime = 0.5;
  for (const double mu : {0.5, 0.05}) {
    const bool rolls = mu >= std::tan(angle) / 3.0;
    ContactScene scene = CylinderOnPlane(angle, mu);
    const testing::EventRun run = testing::RunEventDriven(scene, kTime, 0.05, 1e-3);
    const Rolling motion = Motion(scene, run.y.back(), angle);
    const double a = rolls ? 2.0 / 3.0 * kG * std::sin(angle) : kG * (std::sin(angle) - mu * std::cos(angle));
    const double spin = rolls ? a * kTime / kRadius : 2.0 * mu * kG * std::cos(angle) * kTime / kRadius;
    std::printf("mu %.2f (%s): %.15f m (%.15f), %.15f m/s (%.15f), spin %.12f (%.12f) rad/s; %ld events\n", mu,
                rolls ? "rolls" : "slides", motion.distance, 0.5 * a * kTime * kTime, motion.speed, a * kTime,
                motion.spin, spin, run.statistics.event_driven.events);
    // Measured: rolling 3e-15 m, 2e-15 m/s, spin to the printed digits; sliding 1.7e-14 m,
    // 3.8e-14 m/s, 1e-12 rad/s.
    EXPECT_NEAR(motion.distance, 0.5 * a * kTime * kTime, 2e-13) << mu;
    EXPECT_NEAR(motion.speed, a * kTime, 4e-13) << mu;
    EXPECT_NEAR(motion.spin, spin, 1e-11) << mu;
  }
}

TEST(CylinderPlane, RollsDownAnInclineUnderMoreauJeanAtTheClosedFormAcceleration) {
  constexpr double angle = 0.3, mu = 0.5, kTime = 0.5;
  const double a = 2.0 / 3.0 * kG * std::sin(angle);
  for (const double h : {2e-3, 1e-3}) {
    ContactScene scene = CylinderOnPlane(angle, mu);
    const testing::StepHistory run = testing::RunMoreauJean(scene, h, kTime);
    const Rolling motion = Motion(scene, run.y.back(), angle);
    std::printf("h %.0e: speed %.15f (%.15f) m/s, spin r - speed %.3e m/s\n", h, motion.speed, a * kTime,
                motion.spin * kRadius - motion.speed);
    // Measured: the speed to 1e-15 at both steps (the impulses of a constant acceleration are
    // exact), the rolling condition spin r = v to 1.9e-15.
    EXPECT_NEAR(motion.speed, a * kTime, 1e-14) << h;
    EXPECT_NEAR(motion.spin * kRadius, motion.speed, 2e-14) << h;
  }
}

TEST(CylinderPlane, StandingOnAnEndFaceItRestsOnItsWeight) {
  ContactScene scene = CylinderOnPlane(0.0, 0.5, true);
  constexpr double h = 1e-3;
  const testing::StepHistory run = testing::RunMoreauJean(scene, h, 0.5);
  double largest_speed = 0.0;
  for (const VectorXd& y : run.y) largest_speed = std::max(largest_speed, y.tail(6).norm());
  const double impulse = run.steps.back().contacts[0].P_N;
  std::printf("standing: largest speed %.3e, last step's impulse %.15f N s (m g h %.15f)\n", largest_speed, impulse,
              kMass * kG * h);
  // Measured: speed 4.4e-12 m/s (the LCP's tolerance, 1e-10 of its scale g h); the impulse m g h
  // to the printed digits.
  EXPECT_LT(largest_speed, 5e-11);
  EXPECT_NEAR(impulse, kMass * kG * h, 1e-13);
  EXPECT_EQ(run.steps.back().contacts[0].active_points, 3);  // the three points of the bottom face
}

/// A scene of the solid cylinder on a 0.3 rad incline (cylinder_plane, Moreau-Jean), `radius`
/// and `length` as given.
std::string CylinderScene(const std::string& radius, const std::string& length) {
  return "gravity: [0, 0, -9.81]\n"
         "bodies:\n"
         "  cylinder:\n"
         "    rigid: {mass: 2, inertia: [[0.00791667, 0, 0], [0, 0.0025, 0], [0, 0, 0.00791667]]}\n"
         "    markers: {centre: {position: [0, 0, 0], rotation: {axis: [1, 0, 0], angle: -1.5707963267948966}}}\n"
         "    initial: {position: [0.014776010333066978, 0, 0.047766824456280305], rotation: {axis: [0, 1, 0], "
         "angle: 0.3}}\n"
         "contacts:\n"
         "  - {name: floor, type: cylinder_plane, cylinder: {body: cylinder, marker: centre}, radius: " +
         radius + ", length: " + length +
         ", plane: {body: ground, rotation: {axis: [0, 1, 0], angle: 0.3}}, friction: 0.5}\n"
         "simulation: {end_time: 0.5, output_interval: 0.05, method: moreau_jean, step: 0.001}\n";
}

TEST(CylinderPlane, ASceneEntryPlacesItOnThePlaneAndRefusesBadSizesInOneLocatedLine) {
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("flexmbs_cylinder_" + std::to_string(::getpid()) + ".yaml");
  std::ofstream(file) << CylinderScene("0.05", "0.2");
  Scene scene = LoadScene(file);
  ASSERT_EQ(scene.system->num_unilateral_contacts(), 1);
  EXPECT_EQ(scene.system->unilateral_contact(0).type(), "cylinder_plane");
  EXPECT_EQ(scene.system->unilateral_contact(0).num_points(), 6);
  // The scene's placement touches the plane: its two lowest points at g_N = 0 (to the digits of
  // the position written above), the others 1.5 r above.
  const auto points = scene.system->unilateral_contact(0).Evaluate(0.0, *scene.system, scene.initial_state);
  for (int k : {0, 3}) EXPECT_NEAR(points[static_cast<std::size_t>(k)].g_N, 0.0, 1e-16) << k;
  for (int k : {1, 2, 4, 5}) EXPECT_NEAR(points[static_cast<std::size_t>(k)].g_N, 1.5 * kRadius, 1e-15) << k;
  for (const auto& [radius, length, item] :
       {std::tuple{"0", "0.2", "radius"}, std::tuple{"0.05", "-1", "length"}}) {
    std::ofstream(file) << CylinderScene(radius, length);
    const std::string message = flexmbs::testing::InputErrorMessage([&] { LoadScene(file); });
    EXPECT_NE(message.find(".yaml:"), std::string::npos) << message;
    EXPECT_NE(message.find(std::string("contacts[0].") + item), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  std::filesystem::remove(file);
}

TEST(CylinderPlane, BadSizesAreOneLineErrors) {
  MultibodySystem system(Vector3d::Zero());
  system.AddBody(std::make_unique<RigidBody>("c", 1.0, Vector3d::Zero(), Matrix3d::Identity(),
                                             std::vector<RigidBodyMarker>{{"centre", Vector3d::Zero(), Matrix3d::Identity()}}));
  for (const auto& [radius, length] : {std::pair{0.0, 1.0}, std::pair{0.1, -1.0}, std::pair{std::nan(""), 1.0}}) {
    try {
      CylinderPlaneUnilateral("floor", system.Marker("c", "centre"), radius, length,
                              MarkerRef::Ground(Vector3d::Zero()), UnilateralLaw{});
      ADD_FAILURE() << radius << " " << length;
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find("contact 'floor': the cylinder's radius"), std::string::npos)
          << error.what();
    }
  }
}

}  // namespace
}  // namespace flexmbs::mbs
