#pragma once
// Rotations by Euler parameters (unit quaternions), scalar first: e = (e0, e1, e2, e3) with
// e0 = cos(theta/2) and (e1, e2, e3) = sin(theta/2) n for a rotation by theta about the unit
// axis n (Shabana, "Dynamics of Multibody Systems", 4th ed., ch. 2; no singularity).

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace flexmbs {

/// The rotation matrix R_WB of Euler parameters e (normalised here, so a slightly drifted e is
/// still a rotation).
inline Eigen::Matrix3d RotationFromEulerParameters(const Eigen::Ref<const Eigen::Vector4d>& e) {
  return Eigen::Quaterniond(e(0), e(1), e(2), e(3)).normalized().toRotationMatrix();
}

/// The Euler parameters of a rotation matrix (e0 >= 0).
inline Eigen::Vector4d EulerParametersFromRotation(const Eigen::Matrix3d& R) {
  Eigen::Quaterniond quaternion(R);
  if (quaternion.w() < 0.0) quaternion.coeffs() *= -1.0;
  return {quaternion.w(), quaternion.x(), quaternion.y(), quaternion.z()};
}

/// de/dt = 1/2 e (x) (0, w_B) for the angular velocity w_B in body components [rad/s].
inline Eigen::Vector4d EulerParameterRate(const Eigen::Ref<const Eigen::Vector4d>& e, const Eigen::Vector3d& w_B) {
  const Eigen::Quaterniond product =
      Eigen::Quaterniond(e(0), e(1), e(2), e(3)) * Eigen::Quaterniond(0.0, w_B.x(), w_B.y(), w_B.z());
  return 0.5 * Eigen::Vector4d(product.w(), product.x(), product.y(), product.z());
}

}  // namespace flexmbs
