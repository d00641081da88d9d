#pragma once
// The centrifugal term w~ w~ of an angular velocity w written linearly in the six products of
// its components (docs/sid.md, "Equations of motion these invariants serve"): SID's Oe and
// K0omega are defined column by column on this basis, so the reduction (which computes them)
// and the solver (which multiplies them by w_q) share it.

#include <Eigen/Core>
#include <array>

namespace flexmbs {

/// W_1 .. W_6 with w~ w~ = sum_l w_q(l) W_l (AngularVelocityProducts): diag(0, -1, -1),
/// diag(-1, 0, -1), diag(-1, -1, 0), e1 e2^T + e2 e1^T, e2 e3^T + e3 e2^T, e3 e1^T + e1 e3^T.
inline const std::array<Eigen::Matrix3d, 6>& CentrifugalBasis() {
  static const std::array<Eigen::Matrix3d, 6> W = [] {
    std::array<Eigen::Matrix3d, 6> w;
    w[0] = Eigen::Vector3d(0.0, -1.0, -1.0).asDiagonal();
    w[1] = Eigen::Vector3d(-1.0, 0.0, -1.0).asDiagonal();
    w[2] = Eigen::Vector3d(-1.0, -1.0, 0.0).asDiagonal();
    for (int l = 0; l < 3; ++l) {
      const int a = l, b = (l + 1) % 3;  // (1, 2), (2, 3), (3, 1)
      Eigen::Matrix3d& W_l = w[static_cast<std::size_t>(3 + l)];
      W_l.setZero();
      W_l(a, b) = 1.0;
      W_l(b, a) = 1.0;
    }
    return w;
  }();
  return W;
}

/// w_q = [w1^2, w2^2, w3^2, w1 w2, w2 w3, w3 w1] [rad^2/s^2] of an angular velocity w [rad/s].
inline Eigen::Matrix<double, 6, 1> AngularVelocityProducts(const Eigen::Vector3d& w) {
  Eigen::Matrix<double, 6, 1> w_q;
  w_q << w(0) * w(0), w(1) * w(1), w(2) * w(2), w(0) * w(1), w(1) * w(2), w(2) * w(0);
  return w_q;
}

}  // namespace flexmbs
