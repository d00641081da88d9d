#pragma once
// The linear algebra of the constraints (docs/mbs.md): the block-diagonal mass matrix M
// factorised body by body, and the Schur complement S = G M^-1 G^T of the saddle-point system
// [M G^T; G 0], scaled to unit diagonal and factorised by a pivoted LDL^T whose smallest pivot
// reveals rank deficiency. Shared by the accelerations and the projections.

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <string>
#include <vector>

#include "mbs/multibody_system.h"

namespace flexmbs::mbs {

/// M and S of one state, factorised.
class ConstraintSolver {
 public:
  /// Factorises M(y) and S for the system's constraint Jacobian G (m x n_u, m may be 0). Throws
  /// SimulationError at time t naming the body if a body's mass matrix is not positive definite.
  ConstraintSolver(const MultibodySystem& system, double t, const ConstVectorRef& y, const Eigen::MatrixXd& G);

  /// M^-1 r (r of size n_u).
  Eigen::VectorXd SolveMass(const ConstVectorRef& r) const;
  /// S^-1 r (r of size m). Precondition: not rank deficient.
  Eigen::VectorXd SolveSchur(const ConstVectorRef& r) const;
  /// M^-1 G^T (n_u x m).
  const Eigen::MatrixXd& mass_inverse_G_transpose() const { return Minv_GT_; }

  /// The smallest pivot of the unit-diagonal S (1 without constraints; 0 for a zero row of G).
  double smallest_relative_pivot() const { return smallest_pivot_; }
  /// The joints carrying the near-null vectors of the scaled S (eigenvalues below `pivot`, and
  /// at least the smallest): the joints that are redundant or in a singular configuration.
  std::vector<int> DependentJoints(double pivot) const;
  /// One line for a rank-deficient S: the time, the smallest pivot and the joints involved.
  std::string DescribeRankDeficiency(double t, double pivot) const;
  /// Throws SimulationError(t, DescribeRankDeficiency) if the smallest pivot is below `pivot`.
  void RequireFullRank(double t, double pivot) const;

 private:
  const MultibodySystem& system_;
  std::vector<Eigen::LLT<Eigen::MatrixXd>> mass_factors_;
  Eigen::MatrixXd Minv_GT_;
  Eigen::VectorXd scale_;  // S = diag(scale) S_scaled diag(scale)
  Eigen::MatrixXd S_scaled_;
  Eigen::LDLT<Eigen::MatrixXd> schur_factor_;
  double smallest_pivot_ = 1.0;
};

}  // namespace flexmbs::mbs
