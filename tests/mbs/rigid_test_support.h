#pragma once
// Helpers of the rigid multibody tests: random poses and bodies, body states, and the finite
// differences of functions of the state along a motion.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "core/rotation.h"
#include "mbs/body.h"
#include "mbs/multibody_system.h"
#include "mbs/rigid_body.h"
#include "tests/support/random_draws.h"

namespace flexmbs::mbs::testing {

/// A random rotation (uniform enough for tests).
inline Eigen::Matrix3d RandomRotation(std::mt19937& rng) {
  std::normal_distribution<double> normal;
  const double w = normal(rng);
  const Eigen::Vector3d xyz = flexmbs::testing::DrawVector3(normal, rng);
  return Eigen::Quaterniond(w, xyz.x(), xyz.y(), xyz.z()).normalized().toRotationMatrix();
}

/// A random vector with entries in [-scale, scale].
inline Eigen::Vector3d RandomVector(std::mt19937& rng, double scale = 1.0) {
  std::uniform_real_distribution<double> uniform(-scale, scale);
  return {uniform(rng), uniform(rng), uniform(rng)};
}

/// A random symmetric positive definite inertia tensor (principal moments in [1, 2] kg m^2 in
/// random axes: the triangle inequality holds).
inline Eigen::Matrix3d RandomInertia(std::mt19937& rng) {
  std::uniform_real_distribution<double> moment(1.0, 2.0);
  const Eigen::Matrix3d R = RandomRotation(rng);
  return R * flexmbs::testing::DrawVector3(moment, rng).asDiagonal() * R.transpose();
}

/// A rigid body with random mass properties and markers "m0".."m{count-1}" at random poses.
inline std::unique_ptr<RigidBody> RandomRigidBody(std::mt19937& rng, const std::string& name, int markers = 2) {
  std::vector<RigidBodyMarker> list;
  for (int k = 0; k < markers; ++k) {
    std::string marker_name = "m";
    marker_name += std::to_string(k);
    list.push_back({marker_name, RandomVector(rng, 0.5), RandomRotation(rng)});
  }
  std::uniform_real_distribution<double> mass(1.0, 3.0);
  const double m = mass(rng);
  const Eigen::Vector3d p_BoCm_B = RandomVector(rng, 0.3);
  const Eigen::Matrix3d inertia = RandomInertia(rng);
  return std::make_unique<RigidBody>(name, m, p_BoCm_B, inertia, std::move(list));
}

/// x = [p_WBo_W, e] of a pose.
inline Eigen::VectorXd RigidPositions(const Eigen::Vector3d& p_WBo_W, const Eigen::Matrix3d& R_WB) {
  Eigen::VectorXd x(7);
  x << p_WBo_W, EulerParametersFromRotation(R_WB);
  return x;
}

/// The body pose that puts marker frame M (p_BoM_B, R_BM) at (p_WM_W, R_WM).
inline Eigen::VectorXd PoseFromMarker(const RigidBodyMarker& marker, const Eigen::Vector3d& p_WM_W,
                                      const Eigen::Matrix3d& R_WM) {
  const Eigen::Matrix3d R_WB = R_WM * marker.R_BM.transpose();
  return RigidPositions(p_WM_W - R_WB * marker.p_BoM_B, R_WB);
}

/// The second time derivative of the positions of a system's state y = [x; u] for u' = u_dot:
/// p'' = v', e'' = 1/2 e' (x) (0, w) + 1/2 e (x) (0, w') (rigid bodies only).
inline Eigen::VectorXd PositionSecondDerivative(const MultibodySystem& system, const Eigen::VectorXd& y,
                                                const Eigen::VectorXd& u_dot) {
  Eigen::VectorXd x_ddot(system.num_positions());
  for (int b = 0; b < system.num_bodies(); ++b) {
    const Eigen::Index px = system.position_offset(b), pu = system.velocity_offset(b);
    const Eigen::VectorXd u = system.BodyVelocities(y, b);
    const Eigen::Vector4d e = y.segment<4>(px + 3);
    const Eigen::Vector4d e_dot = EulerParameterRate(e, u.segment<3>(3));
    x_ddot.segment<3>(px) = u_dot.segment<3>(pu);
    x_ddot.segment<4>(px + 3) = EulerParameterRate(e_dot, u.segment<3>(3)) + EulerParameterRate(e, u_dot.segment<3>(pu + 3));
  }
  return x_ddot;
}

/// The system's position derivative x' at y.
inline Eigen::VectorXd PositionRate(const MultibodySystem& system, const Eigen::VectorXd& y) {
  Eigen::VectorXd x_dot(system.num_positions());
  for (int b = 0; b < system.num_bodies(); ++b) {
    PositionDerivative(system.BodyPositions(y, b), system.BodyVelocities(y, b),
                       x_dot.segment(system.position_offset(b), system.body(b).num_positions()));
  }
  return x_dot;
}

/// y with its positions moved along the motion with velocities u and accelerations u_dot by
/// time s: x + s x' + s^2/2 x'' (exact to second order in s; velocities unchanged).
inline Eigen::VectorXd MoveAlong(const MultibodySystem& system, const Eigen::VectorXd& y, const Eigen::VectorXd& u_dot,
                                 double s) {
  Eigen::VectorXd moved = y;
  moved.head(system.num_positions()) +=
      s * PositionRate(system, y) + 0.5 * s * s * PositionSecondDerivative(system, y, u_dot);
  return moved;
}

/// y with its positions moved by dt along its velocities, x + dt x' by DisplacePositions (Euler
/// parameters renormalised); velocities unchanged.
inline Eigen::VectorXd Advance(const MultibodySystem& system, const Eigen::VectorXd& y, double dt) {
  Eigen::VectorXd moved = y;
  system.DisplacePositions(dt * y.tail(system.num_velocities()), moved);
  return moved;
}

}  // namespace flexmbs::mbs::testing
