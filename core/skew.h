#pragma once

#include <Eigen/Core>

namespace flexmbs {

/// The skew-symmetric cross-product matrix x~ of x: Skew(x) y = x cross y.
inline Eigen::Matrix3d Skew(const Eigen::Vector3d& x) {
  Eigen::Matrix3d S;
  S << 0.0, -x.z(), x.y(), x.z(), 0.0, -x.x(), -x.y(), x.x(), 0.0;
  return S;
}

/// The axial vector of the skew-symmetric part of S: Axial(Skew(x)) = x.
inline Eigen::Vector3d Axial(const Eigen::Matrix3d& S) {
  return 0.5 * Eigen::Vector3d(S(2, 1) - S(1, 2), S(0, 2) - S(2, 0), S(1, 0) - S(0, 1));
}

}  // namespace flexmbs
