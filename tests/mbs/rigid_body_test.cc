// RigidBody against an independent Newton-Euler derivation about the centre of mass, its
// energies, and its markers' kinematics against finite differences.
#include "mbs/rigid_body.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <random>

#include "core/rotation.h"
#include "core/skew.h"
#include "rigid_test_support.h"
#include "tests/input_error.h"

namespace flexmbs::mbs {
namespace {

using testing::RandomRigidBody;
using testing::RandomRotation;
using testing::RandomVector;
using testing::RigidPositions;

// Round-off of a few dozen products and a 6 x 6 solve of unit-size numbers.
constexpr double kRoundOff = 1e-12;
// Central differences with step 1e-5 on unit-size functions: truncation ~ 1e-10, round-off
// ~ 1e-16 / 1e-5.
constexpr double kDifferenceStep = 1e-5;
constexpr double kDifferenceTolerance = 1e-8;

struct RandomState {
  Eigen::VectorXd x, u;
};

RandomState MakeState(std::mt19937& rng) {
  RandomState s{RigidPositions(RandomVector(rng, 2.0), RandomRotation(rng)), Eigen::VectorXd(6)};
  s.u << RandomVector(rng, 2.0), RandomVector(rng, 3.0);
  return s;
}

TEST(RigidBody, AccelerationsSatisfyNewtonEulerAboutTheCentreOfMass) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 5; ++trial) {
    const auto body = RandomRigidBody(rng, "body", 1);
    const RandomState s = MakeState(rng);
    const Eigen::Vector3d g_W(0.3, -1.0, -9.81), F_W = RandomVector(rng, 5.0), T_W = RandomVector(rng, 5.0);
    Eigen::MatrixXd M(6, 6);
    Eigen::VectorXd h(6);
    body->MassMatrix(s.x, M);
    body->Forces(0.0, s.x, s.u, g_W, h);
    const Eigen::VectorXd u_dot = M.ldlt().solve(h + body->MarkerLoad(0, s.x, F_W, T_W));

    // Newton and Euler for the centre of mass C, written here from scratch:
    // m a_C = m g + F, J_C alpha + w x J_C w = sum of moments about C (all in B for Euler).
    const Eigen::Matrix3d R = RotationFromEulerParameters(s.x.segment<4>(3));
    const Eigen::Vector3d c = body->p_BoCm_B(), w = s.u.tail<3>(), alpha = u_dot.tail<3>();
    const Eigen::Vector3d a_C_W = u_dot.head<3>() + R * (alpha.cross(c) + w.cross(w.cross(c)));
    const double m = body->mass();
    EXPECT_LE((m * a_C_W - (m * g_W + F_W)).norm(), kRoundOff * (m * g_W + F_W).norm());
    const Eigen::Vector3d p_CM_B = body->markers()[0].p_BoM_B - c;
    const Eigen::Vector3d moment_C_B = R.transpose() * T_W + p_CM_B.cross(R.transpose() * F_W);
    const Eigen::Matrix3d& J = body->inertia_about_cm();
    EXPECT_LE((J * alpha + w.cross(J * w) - moment_C_B).norm(), kRoundOff * (1.0 + moment_C_B.norm() + (J * alpha).norm()));
  }
}

TEST(RigidBody, MassMatrixIsTheKineticEnergyOfTheCentreOfMassMotion) {
  std::mt19937 rng(12);
  const auto body = RandomRigidBody(rng, "body");
  const RandomState s = MakeState(rng);
  const Eigen::Matrix3d R = RotationFromEulerParameters(s.x.segment<4>(3));
  const Eigen::Vector3d w = s.u.tail<3>();
  const Eigen::Vector3d v_C = s.u.head<3>() + R * w.cross(body->p_BoCm_B());
  const double expected = 0.5 * body->mass() * v_C.squaredNorm() + 0.5 * w.dot(body->inertia_about_cm() * w);
  EXPECT_NEAR(body->KineticEnergy(s.x, s.u), expected, kRoundOff * expected);
  Eigen::MatrixXd M(6, 6);
  body->MassMatrix(s.x, M);
  EXPECT_LE((M - M.transpose()).norm(), kRoundOff * M.norm());
  EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(M).info(), Eigen::Success);
  // Parallel axes: J_Bo = J_C + m (c^T c 1 - c c^T).
  const Eigen::Vector3d c = body->p_BoCm_B();
  const Eigen::Matrix3d J_Bo = body->inertia_about_cm() + body->mass() * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  EXPECT_LE((body->inertia_about_origin() - J_Bo).norm(), kRoundOff * J_Bo.norm());
  const Eigen::Vector3d g_W(0.0, 0.0, -9.81);
  const Eigen::Vector3d p_C = s.x.head<3>() + R * c;
  const double potential = body->mass() * 9.81 * p_C.z();
  EXPECT_NEAR(body->PotentialEnergy(s.x, g_W), potential, kRoundOff * (1.0 + std::abs(potential)));
}

TEST(RigidBody, MarkerVelocityAndAccelerationAreDerivativesOfItsPose) {
  std::mt19937 rng(13);
  const auto body = RandomRigidBody(rng, "body");
  const RandomState s = MakeState(rng);
  Eigen::VectorXd u_dot(6);
  u_dot << RandomVector(rng, 2.0), RandomVector(rng, 2.0);
  Eigen::VectorXd x_dot(7);
  PositionDerivative(s.x, s.u, x_dot);
  for (int marker = 0; marker < 2; ++marker) {
    const MarkerKinematics k = body->Marker(marker, s.x, s.u);
    const double e = kDifferenceStep;
    const MarkerKinematics plus = body->Marker(marker, s.x + e * x_dot, s.u + e * u_dot);
    const MarkerKinematics minus = body->Marker(marker, s.x - e * x_dot, s.u - e * u_dot);
    // Velocities: d/dt p and (d/dt R) R^T = w~.
    const Eigen::Vector3d v_fd = (plus.p_WM_W - minus.p_WM_W) / (2 * e);
    const Eigen::Vector3d w_fd = Axial((plus.R_WM - minus.R_WM) / (2 * e) * k.R_WM.transpose());
    EXPECT_LE((v_fd - k.v_WM_W).norm(), kDifferenceTolerance);
    EXPECT_LE((w_fd - k.w_WM_W).norm(), kDifferenceTolerance);
    Eigen::Matrix<double, 6, 1> spatial;
    spatial << k.v_WM_W, k.w_WM_W;
    EXPECT_LE((k.jacobian * s.u - spatial).norm(), kRoundOff * 10.0);
    // Accelerations: d/dt of the velocities = jacobian u' + bias.
    Eigen::Matrix<double, 6, 1> a_fd;
    a_fd << (plus.v_WM_W - minus.v_WM_W) / (2 * e), (plus.w_WM_W - minus.w_WM_W) / (2 * e);
    EXPECT_LE((a_fd - (k.jacobian * u_dot + k.bias)).norm(), kDifferenceTolerance * 10.0);
  }
}

TEST(RigidBody, RejectsNonPhysicalMassPropertiesAndDuplicateMarkers) {
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  EXPECT_NE(flexmbs::testing::InputErrorMessage([&] { RigidBody("b", 0.0, Eigen::Vector3d::Zero(), I); })
                .find("rigid body 'b': mass 0 kg must be > 0"),
            std::string::npos);
  const Eigen::Matrix3d rod = Eigen::Vector3d(1.0, 1.0, 3.0).asDiagonal();
  EXPECT_NE(flexmbs::testing::InputErrorMessage([&] { RigidBody("b", 1.0, Eigen::Vector3d::Zero(), rod); })
                .find("triangle inequality"),
            std::string::npos);
  EXPECT_NE(flexmbs::testing::InputErrorMessage([&] {
              RigidBody("b", 1.0, Eigen::Vector3d::Zero(), I, {{"m", Eigen::Vector3d::Zero(), I}, {"m", Eigen::Vector3d::Zero(), I}});
            }).find("marker 'm' defined twice"),
            std::string::npos);
  // A thin plate meets the triangle inequality with equality and is accepted.
  EXPECT_NO_THROW(RigidBody("plate", 1.0, Eigen::Vector3d::Zero(), Eigen::Vector3d(1.0, 2.0, 3.0).asDiagonal()));
}

}  // namespace
}  // namespace flexmbs::mbs
