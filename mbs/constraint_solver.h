#pragma once
// The linear algebra of the constraints (docs/mbs.md, "Joints and constraints"): the
// block-diagonal mass matrix M factorised body by body, and the Schur complement S = G M^-1 G^T
// of the saddle-point system [M G^T; G 0] over the kept constraint rows
// (MultibodySystem::dropped_constraints are left out), scaled to unit diagonal and factorised by
// an LDL^T whose smallest pivot reveals rank deficiency. Shared by the accelerations, the
// projections, the model Jacobian and the redundancy search.
//
// A constraint row touches the velocities of at most two bodies (its joint's), so G and
// M^-1 G^T are kept sparse and formed body by body (M_b^-1 G_b^T over the rows at body b), and
// S = sum_b G_b M_b^-1 G_b^T has a nonzero (p, q) only where rows p and q share a body (block
// tridiagonal for a chain). S of more than kDenseSchurRows rows is factorised by a sparse LDL^T
// without pivoting, eliminating the joints farthest from the ground first (no fill for a chain
// or tree): the cost per evaluation grows linearly with the number of bodies. Smaller S, and any
// S whose sparse factor has a pivot below kPivotedCheckBelow (near a singular configuration),
// are factorised dense with diagonal pivoting (Eigen::LDLT), as before.

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <array>
#include <string>
#include <vector>

#include "mbs/multibody_system.h"

namespace flexmbs::mbs {

/// Which constraint rows a ConstraintSolver's S is formed from.
enum class SolverRows {
  kKept,  ///< every row but the system's dropped_constraints() (the equations of motion)
  kAll,   ///< every row (the redundancy search)
};

/// M and S of one state, factorised. In a planar scene (MultibodySystem::planar) M^-1 stands for
/// S M~^-1 S^T with S the kept velocity columns and M~ = M(s, s) per body (docs/mbs.md, "Planar
/// scenes"): the accelerations, projections and Delassus matrices of the guided, in-plane motion.
class ConstraintSolver {
 public:
  /// S with at most this many rows is factorised dense with pivoting: below about 30-50 rows the
  /// dense LDL^T is as fast as the sparse one or faster (measured on the chain of
  /// bench_mbs_speed, bench/README.md "Multibody solver speed").
  static constexpr Eigen::Index kDenseSchurRows = 40;
  /// A sparse LDL^T of the unit-diagonal S with a pivot below this is redone dense with diagonal
  /// pivoting, so that a rank decision against the limits in use (ConstraintSettings::
  /// singular_pivot, 1e-10 by default; the 1e-6 of a failure's diagnosis) is the pivoted LDL^T's.
  /// Any LDL^T's smallest pivot is at least S's smallest eigenvalue; measured
  /// (tests/mbs/constraint_solver_test.cc), the pivoted one is 3-9 times it, the sparse one up to
  /// 25 times for a near-null vector spread over a loop's rows: inside the factor 100 between this
  /// and 1e-6 (singular_pivot is assumed <= 1e-6).
  static constexpr double kPivotedCheckBelow = 1e-4;

  /// Factorises M(y) and S for the system's constraint Jacobian G = system.Constraints(t, y).G
  /// (m x n_u, all rows; m may be 0; nonzero only in the columns of the bodies of each row's
  /// joint) restricted to `rows`. Throws SimulationError at time t naming the body if a body's
  /// mass matrix is not positive definite.
  ConstraintSolver(const MultibodySystem& system, double t, const ConstVectorRef& y, const Eigen::MatrixXd& G,
                   SolverRows rows = SolverRows::kKept);

  /// M^-1 r (r of size n_u).
  Eigen::VectorXd SolveMass(const ConstVectorRef& r) const;
  /// M^-1 R (R of n_u rows), body by body and column by column, solving only where a body's
  /// part of a column is not zero (M^-1 of a force Jacobian, whose columns mostly touch one body).
  Eigen::MatrixXd SolveMassColumns(const Eigen::MatrixXd& R) const;
  /// S^-1 r on the solver's rows (r of size m, all rows): the result has size m, 0 on the rows
  /// left out. Precondition: not rank deficient.
  Eigen::VectorXd SolveSchur(const ConstVectorRef& r) const;
  /// G (m x n_u, all rows) with the blocks of the bodies each row touches; in a planar scene only
  /// their kept columns (u and u' are zero in the dropped ones, and M^-1 G^T is zero there).
  const Eigen::SparseMatrix<double, Eigen::RowMajor>& constraint_jacobian() const { return G_; }
  /// M^-1 G^T (n_u x m, all rows; column k nonzero in the bodies row k touches, in a planar scene
  /// in their kept columns).
  const Eigen::SparseMatrix<double>& mass_inverse_G_transpose() const { return Minv_GT_; }
  /// The stacked rows S is formed from, ascending.
  const std::vector<Eigen::Index>& rows() const { return rows_; }
  /// S over rows(), scaled to unit diagonal, dense (0 x 0 without rows); formed on each call.
  Eigen::MatrixXd scaled_schur() const;
  /// True if S is factorised dense with diagonal pivoting (small, or near rank deficient), false
  /// if by the sparse LDL^T.
  bool pivoted() const { return pivoted_; }

  /// The smallest pivot of the LDL^T of the unit-diagonal S (1 without constraints; 0 for a zero
  /// row of G): the pivoted one whenever it is below kPivotedCheckBelow (or S is small).
  double smallest_relative_pivot() const { return smallest_pivot_; }
  /// The joints carrying the near-null vectors of the scaled S (eigenvalues below `pivot`, and
  /// at least the smallest): the joints that are redundant or in a singular configuration.
  std::vector<int> DependentJoints(double pivot) const;
  /// One line for a rank-deficient S: the time, the smallest pivot and the joints involved.
  std::string DescribeRankDeficiency(double t, double pivot) const;
  /// Throws SimulationError(t, DescribeRankDeficiency) if the smallest pivot is below `pivot`.
  void RequireFullRank(double t, double pivot) const;

 private:
  /// The rows at each body, row_at_body_, and the patterns of G_ and Minv_GT_.
  void SetPattern();
  /// The values of G_ and Minv_GT_ and the bodies' blocks of S from G.
  void FormBodyBlocks(const Eigen::MatrixXd& G);
  /// Scales S to unit diagonal and factorises it (sparse, or dense with pivoting).
  void FactoriseSchur();
  /// out_b = M_b^-1 r_b for body b (a planar scene's body: S_b M_b(s, s)^-1 S_b^T r_b over its
  /// kept columns s, zero in the dropped ones).
  void SolveBodyMass(int b, const ConstVectorRef& r_b, Eigen::Ref<Eigen::VectorXd> out_b) const;
  /// The number of body b's columns in G_ and Minv_GT_: its kept ones in a planar scene, else all.
  Eigen::Index NumColumns(int b) const;
  /// Body b's G_b M_b^-1 G_b^T over its rows.
  Eigen::Map<const Eigen::MatrixXd> BodySchur(int b) const;
  /// The scaled S (lower triangle) as (i, j, value) with i >= j, positions in rows(), to `add`.
  template <typename Add>
  void ForEachScaledSchurEntry(Add add) const;
  /// The upper triangle of the scaled S in elimination_order_ (compressed columns).
  void EliminationOrderedScaledSchur(Eigen::SparseMatrix<double>& S) const;

  const MultibodySystem& system_;
  std::vector<Eigen::LLT<Eigen::MatrixXd>> mass_factors_;  // of M_b(s, s) in a planar scene
  std::vector<std::vector<Eigen::Index>> kept_;  // per body its kept columns s; empty: spatial
  std::vector<Eigen::Index> rows_;
  std::vector<Eigen::Index> position_in_rows_;  // per stacked row: its index in rows_, or -1
  // The stacked rows at each body (CSR: body b's are body_rows_[body_row_start_[b] ..
  // body_row_start_[b + 1]), ascending), and per body G_b M_b^-1 G_b^T over them (column-major
  // from schur_block_start_[b]).
  std::vector<Eigen::Index> body_row_start_, body_rows_, schur_block_start_;
  std::vector<double> schur_blocks_;
  /// Where a stacked row sits at one of its (up to two) bodies: the body (kGround: none) and the
  /// row's index among the body's rows.
  struct RowAtBody {
    int body = kGround;
    Eigen::Index index = 0;
  };
  std::vector<std::array<RowAtBody, 2>> row_at_body_;  // per stacked row
  // The sparse LDL^T's order: indices into rows_, the rows of the joints farthest from the
  // ground first.
  std::vector<Eigen::Index> elimination_order_;
  Eigen::SparseMatrix<double, Eigen::RowMajor> G_;
  Eigen::SparseMatrix<double> Minv_GT_;
  Eigen::VectorXd inverse_scale_;  // S_scaled = diag(inverse_scale) S diag(inverse_scale)
  bool pivoted_ = true;
  Eigen::LDLT<Eigen::MatrixXd> dense_factor_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Upper, Eigen::NaturalOrdering<int>> sparse_factor_;
  double smallest_pivot_ = 1.0;
};

}  // namespace flexmbs::mbs
