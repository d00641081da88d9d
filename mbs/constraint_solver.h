#pragma once
// The linear algebra of the constraints (docs/mbs.md): the block-diagonal mass matrix M
// factorised body by body, and the Schur complement S = G M^-1 G^T of the saddle-point system
// [M G^T; G 0] over the kept constraint rows (MultibodySystem::dropped_constraints are left
// out), scaled to unit diagonal and factorised by a pivoted LDL^T whose smallest pivot reveals
// rank deficiency. Shared by the accelerations, the projections and the redundancy search.

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <string>
#include <vector>

#include "mbs/multibody_system.h"

namespace flexmbs::mbs {

/// Which constraint rows a ConstraintSolver's S is formed from.
enum class SolverRows {
  kKept,  ///< every row but the system's dropped_constraints() (the equations of motion)
  kAll,   ///< every row (the redundancy search)
};

/// M and S of one state, factorised.
class ConstraintSolver {
 public:
  /// Factorises M(y) and S for the system's constraint Jacobian G (m x n_u, all rows; m may be
  /// 0) restricted to `rows`. Throws SimulationError at time t naming the body if a body's mass
  /// matrix is not positive definite.
  ConstraintSolver(const MultibodySystem& system, double t, const ConstVectorRef& y, const Eigen::MatrixXd& G,
                   SolverRows rows = SolverRows::kKept);

  /// M^-1 r (r of size n_u).
  Eigen::VectorXd SolveMass(const ConstVectorRef& r) const;
  /// S^-1 r on the solver's rows (r of size m, all rows): the result has size m, 0 on the rows
  /// left out. Precondition: not rank deficient.
  Eigen::VectorXd SolveSchur(const ConstVectorRef& r) const;
  /// M^-1 G^T (n_u x m, all rows).
  const Eigen::MatrixXd& mass_inverse_G_transpose() const { return Minv_GT_; }
  /// The stacked rows S is formed from, ascending.
  const std::vector<Eigen::Index>& rows() const { return rows_; }
  /// S over rows(), scaled to unit diagonal (0 x 0 without rows).
  const Eigen::MatrixXd& scaled_schur() const { return S_scaled_; }

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
  std::vector<Eigen::Index> rows_;
  Eigen::MatrixXd Minv_GT_;
  Eigen::VectorXd scale_;  // S = diag(scale) S_scaled diag(scale)
  Eigen::MatrixXd S_scaled_;
  Eigen::LDLT<Eigen::MatrixXd> schur_factor_;
  double smallest_pivot_ = 1.0;
};

}  // namespace flexmbs::mbs
