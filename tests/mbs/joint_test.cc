// Joints: satisfied along the motions they allow; their Jacobian G and g_t are the derivatives
// of g, and gamma the part of g's second derivative without u' (finite differences along
// random motions, on and off the constraint manifold).
#include "mbs/joint.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "mbs/multibody_system.h"
#include "mbs/rigid_body.h"
#include "rigid_test_support.h"
#include "tests/input_error.h"

namespace flexmbs::mbs {
namespace {

using testing::MoveAlong;
using testing::PoseFromMarker;
using testing::PositionRate;
using testing::RandomRigidBody;
using testing::RandomRotation;
using testing::RandomVector;
using testing::RigidPositions;

// g of an assembled joint: round-off of products of unit-size poses.
constexpr double kAssembled = 1e-14;
// First derivatives: central differences, step 1e-6 (truncation ~1e-12 |g'''|, round-off
// ~1e-16 / 1e-6).
constexpr double kFirstStep = 1e-6;
constexpr double kFirstTolerance = 1e-8;
// Second derivatives: the five-point stencil with step 1e-3 (truncation ~1e-12 |g^(6)|,
// round-off ~1e-16 / 1e-6).
constexpr double kSecondStep = 1e-3;
constexpr double kSecondTolerance = 1e-7;

struct JointCase {
  std::string label;
  JointType type;
  bool ground_i = false;
  TimeFunctionPtr driver;
};

std::vector<JointCase> Cases() {
  return {{"fixed", JointType::kFixed, false, nullptr},
          {"revolute", JointType::kRevolute, false, nullptr},
          {"revolute to ground", JointType::kRevolute, true, nullptr},
          {"prismatic", JointType::kPrismatic, false, nullptr},
          {"cylindrical", JointType::kCylindrical, false, nullptr},
          {"spherical", JointType::kSpherical, false, nullptr},
          {"universal", JointType::kUniversal, false, nullptr},
          {"fixed to ground", JointType::kFixed, true, nullptr},
          {"driven revolute", JointType::kRevolute, false, MakeHarmonic(0.8, 3.0, 0.2, 0.1)},
          {"driven revolute to ground", JointType::kRevolute, true, MakePolynomial({0.3, 2.0, -1.5})},
          {"driven prismatic", JointType::kPrismatic, false, MakeHarmonic(0.2, 5.0, -0.4, 0.3)}};
}

Eigen::Matrix3d Rotation(const Eigen::Vector3d& axis, double angle) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

// A relative pose of J in I (R_IJ, p_IJ_I) that the joint allows, with the driven coordinate at
// `driven` and the free ones random.
struct RelativePose {
  Eigen::Matrix3d R_IJ;
  Eigen::Vector3d p_IJ_I;
};

RelativePose AllowedPose(JointType type, std::mt19937& rng, double driven) {
  std::uniform_real_distribution<double> angle(-3.0, 3.0), offset(-0.5, 0.5);
  const Eigen::Vector3d x = Eigen::Vector3d::UnitX(), y = Eigen::Vector3d::UnitY(), z = Eigen::Vector3d::UnitZ();
  switch (type) {
    case JointType::kFixed:
      return {Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()};
    case JointType::kRevolute:
      return {Rotation(z, std::isnan(driven) ? angle(rng) : driven), Eigen::Vector3d::Zero()};
    case JointType::kPrismatic:
      return {Eigen::Matrix3d::Identity(), (std::isnan(driven) ? offset(rng) : driven) * z};
    case JointType::kCylindrical:
      return {Rotation(z, angle(rng)), offset(rng) * z};
    case JointType::kSpherical:
      return {RandomRotation(rng), Eigen::Vector3d::Zero()};
    case JointType::kUniversal: {
      const double about_x = angle(rng);  // drawn first: the operands of * are evaluated in either order
      return {Rotation(x, about_x) * Rotation(y, angle(rng)), Eigen::Vector3d::Zero()};
    }
  }
  return {};
}

// Two random bodies (or the ground and one) and the joint of `c`, assembled at time t with its
// free coordinates random.
struct Fixture {
  MultibodySystem system;
  Eigen::VectorXd y;
  const RigidBody* body_j = nullptr;

  Fixture(const JointCase& c, std::mt19937& rng, double t) : system(Eigen::Vector3d(0.0, 0.0, -9.81)) {
    MarkerRef I;
    if (c.ground_i) {
      const Eigen::Vector3d p_WI_W = RandomVector(rng);
      I = MarkerRef::Ground(p_WI_W, RandomRotation(rng));
    } else {
      I = MarkerRef::OnBody(system.AddBody(RandomRigidBody(rng, "i")), 0);
    }
    const int j = system.AddBody(RandomRigidBody(rng, "j"));
    body_j = &dynamic_cast<const RigidBody&>(system.body(j));
    system.AddJoint(Joint("joint", c.type, I, MarkerRef::OnBody(j, 1), c.driver));
    y = system.NeutralState();
    if (!c.ground_i) {
      const Eigen::Vector3d p_WBo_W = RandomVector(rng);
      system.SetBodyState(0, RigidPositions(p_WBo_W, RandomRotation(rng)), Eigen::VectorXd::Zero(6), y);
    }
    Assemble(c, rng, t);
    // Random velocities: not consistent with the joint, which the derivatives must not need.
    for (Eigen::Index k = system.num_positions(); k < y.size(); ++k) y(k) = std::uniform_real_distribution<double>(-2.0, 2.0)(rng);
  }

  // Puts body j where the joint allows it relative to marker I.
  void Assemble(const JointCase& c, std::mt19937& rng, double t) {
    const double driven = c.driver ? c.driver->Evaluate(t).value : std::nan("");
    const RelativePose pose = AllowedPose(c.type, rng, driven);
    const MarkerKinematics I = system.MarkerState(system.joint(0).marker_i(), y);
    const Eigen::VectorXd x_j = PoseFromMarker(body_j->markers()[1], I.p_WM_W + I.R_WM * pose.p_IJ_I, I.R_WM * pose.R_IJ);
    y.segment(system.position_offset(system.num_bodies() - 1), 7) = x_j;
  }

  Eigen::VectorXd g(const Eigen::VectorXd& state, double t) const { return system.Constraints(t, state).g; }
};

TEST(Joint, IsSatisfiedAlongTheMotionsItAllows) {
  std::mt19937 rng(21);
  const double t = 0.37;
  for (const JointCase& c : Cases()) {
    Fixture f(c, rng, t);
    for (int sample = 0; sample < 5; ++sample) {
      f.Assemble(c, rng, t);
      EXPECT_LE(f.g(f.y, t).cwiseAbs().maxCoeff(), kAssembled) << c.label;
    }
  }
}

TEST(Joint, JacobianAndTimeDerivativeAreThoseOfG) {
  std::mt19937 rng(22);
  const double t = 0.37;
  for (const JointCase& c : Cases()) {
    for (const bool off_manifold : {false, true}) {
      Fixture f(c, rng, t);
      if (off_manifold) f.y.head(f.system.num_positions()) += 0.05 * PositionRate(f.system, f.y);
      const SystemConstraints at = f.system.Constraints(t, f.y);
      Eigen::VectorXd y_dot = Eigen::VectorXd::Zero(f.y.size());
      y_dot.head(f.system.num_positions()) = PositionRate(f.system, f.y);
      const double s = kFirstStep;
      const Eigen::VectorXd fd = (f.g(f.y + s * y_dot, t + s) - f.g(f.y - s * y_dot, t - s)) / (2 * s);
      const Eigen::VectorXd u = f.y.tail(f.system.num_velocities());
      EXPECT_LE((fd - (at.G * u + at.g_t)).cwiseAbs().maxCoeff(), kFirstTolerance) << c.label << " off " << off_manifold;
      const Eigen::VectorXd fd_t = (f.g(f.y, t + s) - f.g(f.y, t - s)) / (2 * s);
      EXPECT_LE((fd_t - at.g_t).cwiseAbs().maxCoeff(), kFirstTolerance) << c.label;
    }
  }
}

TEST(Joint, GammaIsTheSecondDerivativeWithoutTheAccelerations) {
  std::mt19937 rng(23);
  const double t = 0.37;
  for (const JointCase& c : Cases()) {
    for (const bool off_manifold : {false, true}) {
      Fixture f(c, rng, t);
      if (off_manifold) f.y.head(f.system.num_positions()) += 0.05 * PositionRate(f.system, f.y);
      Eigen::VectorXd u_dot(f.system.num_velocities());
      for (Eigen::Index k = 0; k < u_dot.size(); ++k) u_dot(k) = std::uniform_real_distribution<double>(-3.0, 3.0)(rng);
      const SystemConstraints at = f.system.Constraints(t, f.y);
      const double s = kSecondStep;
      const auto c_of = [&](double k) { return f.g(MoveAlong(f.system, f.y, u_dot, k * s), t + k * s); };
      const Eigen::VectorXd second = (-c_of(2) + 16 * c_of(1) - 30 * c_of(0) + 16 * c_of(-1) - c_of(-2)) / (12 * s * s);
      const Eigen::VectorXd expected = at.G * u_dot - at.gamma;
      EXPECT_LE((second - expected).cwiseAbs().maxCoeff(), kSecondTolerance * (1.0 + expected.cwiseAbs().maxCoeff()))
          << c.label << " off " << off_manifold;
    }
  }
}

TEST(Joint, DriverRowIsTheSineOfTheAngleError) {
  std::mt19937 rng(24);
  const JointCase c{"driven revolute", JointType::kRevolute, false, MakeConstant(0.4)};
  Fixture f(c, rng, 0.0);
  // Turn J by 0.1 rad more about I's z: the driver's equation reads sin(0.1), the others stay 0.
  const Eigen::Index j = f.system.position_offset(1);
  const MarkerKinematics I = f.system.MarkerState(f.system.joint(0).marker_i(), f.y);
  const MarkerKinematics J = f.system.MarkerState(f.system.joint(0).marker_j(), f.y);
  f.y.segment(j, 7) = PoseFromMarker(f.body_j->markers()[1], J.p_WM_W, Rotation(I.R_WM.col(2), 0.1) * J.R_WM);
  const Eigen::VectorXd g = f.g(f.y, 0.0);
  EXPECT_LE(g.head(5).cwiseAbs().maxCoeff(), kAssembled);
  EXPECT_NEAR(g(5), std::sin(0.1), kAssembled);
}

TEST(Joint, RejectsDriversOnOtherTypesAndTwoMarkersOnOneBody) {
  EXPECT_NE(flexmbs::testing::InputErrorMessage([] {
              Joint("j", JointType::kSpherical, MarkerRef::Ground(Eigen::Vector3d::Zero()), MarkerRef::OnBody(0, 0),
                    MakeConstant(0.0));
            }).find("joint 'j': a driver needs a revolute or prismatic joint, not spherical"),
            std::string::npos);
  EXPECT_NE(flexmbs::testing::InputErrorMessage([] {
              Joint("j", JointType::kRevolute, MarkerRef::OnBody(0, 0), MarkerRef::OnBody(0, 1));
            }).find("joint 'j': both markers are on the same body"),
            std::string::npos);
  EXPECT_EQ(ParseJointType("cylindrical"), JointType::kCylindrical);
  EXPECT_NE(flexmbs::testing::InputErrorMessage([] { ParseJointType("hinge"); }).find("unknown joint type 'hinge'"),
            std::string::npos);
}

}  // namespace
}  // namespace flexmbs::mbs
