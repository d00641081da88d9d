#pragma once

#include <Eigen/Core>
#include <vector>

namespace flexmbs::sid {

/// A SID Taylor block: a matrix field expanded in the modal coordinates q (n of them),
///
///     X(q) = m0 + sum_j q_j m1[j] + sum_j sum_k q_j q_k m2[j n + k],
///
/// (Wallrapp 1994, "Standardization of flexible body modeling in multibody system codes").
/// Every m1[j] and m2[j n + k] has the shape of m0. Order 0: m1 and m2 empty; order 1: m2
/// empty; order 2 (only J's quadratic inertia term): all three.
struct TaylorMatrix {
  Eigen::MatrixXd m0;
  std::vector<Eigen::MatrixXd> m1;  ///< empty or one per modal coordinate
  std::vector<Eigen::MatrixXd> m2;  ///< empty or n x n, index j n + k

  /// 0, 1 or 2: the highest order present.
  int order() const { return !m2.empty() ? 2 : !m1.empty() ? 1 : 0; }

  /// X(q). Precondition: q has one entry per modal coordinate if order() > 0.
  Eigen::MatrixXd Evaluate(const Eigen::VectorXd& q) const;

  /// True if m1 (and m2) have the count and every block the shape the order requires for
  /// `num_modes` coordinates.
  bool IsConsistent(Eigen::Index num_modes) const;

  bool operator==(const TaylorMatrix&) const = default;
};

}  // namespace flexmbs::sid
