#pragma once

// Small dense linear algebra on bases in the M inner product, shared by the reductions.

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "eigensolvers/model_operators.h"

namespace flexmbs::reduction {

/// Rayleigh-Ritz on span(B): the eigenpairs of (B^T K B, B^T M B), as M-orthonormal Ritz
/// vectors, ascending. `transform` gives them in B's coordinates: vectors = B transform.
struct RitzResult {
  Eigen::VectorXd values;     ///< Ritz values [rad^2/s^2], ascending
  Eigen::MatrixXd vectors;    ///< M-orthonormal
  Eigen::MatrixXd transform;  ///< vectors = B transform
};
/// B must have independent columns (checked: InternalError otherwise). Columns are scaled to
/// unit M-norm first, then orthonormalised by two Cholesky-QR passes in the M inner product.
/// Each Ritz vector's sign makes its largest coordinate in that orthonormal basis positive, so a
/// vector that is mostly one column of B keeps that column's sign, whatever the round-off.
RitzResult RayleighRitz(const eigensolvers::SymmetricOperator& K, const eigensolvers::SymmetricOperator& M, const Eigen::MatrixXd& B);
/// The same with K and M held here (SparseOperator).
RitzResult RayleighRitz(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M,
                        const Eigen::MatrixXd& B);

/// X -= Q (Q^T M X), twice (classical Gram-Schmidt with re-orthogonalisation): X becomes
/// M-orthogonal to the M-orthonormal columns of Q.
void MOrthogonalizeAgainst(const eigensolvers::SymmetricOperator& M, const Eigen::MatrixXd& Q, Eigen::MatrixXd* X);
/// The same with M held here (SparseOperator).
void MOrthogonalizeAgainst(const Eigen::SparseMatrix<double>& M, const Eigen::MatrixXd& Q, Eigen::MatrixXd* X);

/// An M-orthonormal basis of span(X) (independent columns, checked) by two Cholesky-QR passes.
Eigen::MatrixXd MOrthonormalized(const eigensolvers::SymmetricOperator& M, const Eigen::MatrixXd& X);
/// The same with M held here (SparseOperator).
Eigen::MatrixXd MOrthonormalized(const Eigen::SparseMatrix<double>& M, const Eigen::MatrixXd& X);

/// 0.5 (A + A^T).
Eigen::MatrixXd Symmetrized(const Eigen::MatrixXd& A);

}  // namespace flexmbs::reduction
