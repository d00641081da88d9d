#include "reduction/basis_algebra.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace flexmbs::reduction {
namespace {

// One Cholesky-QR pass: Q = X L^-T with L L^T = X^T M X; returns L^-T (Q = X L^-T).
Eigen::MatrixXd CholeskyQrStep(const eigensolvers::SymmetricOperator& M, Eigen::MatrixXd* X) {
  const Eigen::MatrixXd G = Symmetrized(X->transpose() * M.Times(*X));
  const Eigen::LLT<Eigen::MatrixXd> llt(G);
  FLEXMBS_CHECK(llt.info() == Eigen::Success, "M-orthonormalisation: the basis columns are dependent");
  const Eigen::MatrixXd U_inv =
      llt.matrixU().solve(Eigen::MatrixXd::Identity(G.rows(), G.cols()));  // L^-T = U^-1
  *X = *X * U_inv;
  return U_inv;
}

// V with each column's sign chosen so that its entry of largest magnitude is positive: a Ritz
// vector then keeps the sign of the basis vector it mostly is, not the one LAPACK's round-off
// happened to give.
Eigen::MatrixXd WithLargestEntryPositive(Eigen::MatrixXd V) {
  for (Eigen::Index j = 0; j < V.cols(); ++j) {
    Eigen::Index largest = 0;
    V.col(j).cwiseAbs().maxCoeff(&largest);
    if (V(largest, j) < 0.0) V.col(j) *= -1.0;
  }
  return V;
}

}  // namespace

Eigen::MatrixXd Symmetrized(const Eigen::MatrixXd& A) { return 0.5 * (A + A.transpose()); }

RitzResult RayleighRitz(const eigensolvers::SymmetricOperator& K, const eigensolvers::SymmetricOperator& M, const Eigen::MatrixXd& B) {
  RitzResult ritz;
  const Eigen::Index n = B.cols();
  if (n == 0) {
    ritz.vectors = B;
    ritz.transform.resize(0, 0);
    return ritz;
  }
  // Unit M-norm columns first: correction and constraint modes differ in scale by many decades.
  const Eigen::MatrixXd MB = M.Times(B);
  Eigen::VectorXd scale(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const double norm = std::sqrt(std::max(B.col(j).dot(MB.col(j)), 0.0));
    FLEXMBS_CHECK(norm > 0.0 && std::isfinite(norm), "Rayleigh-Ritz: zero or non-finite basis vector");
    scale(j) = 1.0 / norm;
  }
  Eigen::MatrixXd Q = B * scale.asDiagonal();
  Eigen::MatrixXd T = scale.asDiagonal();
  for (int pass = 0; pass < 2; ++pass) T = T * CholeskyQrStep(M, &Q);
  const Eigen::MatrixXd Kr = Symmetrized(Q.transpose() * K.Times(Q));
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(Kr);
  FLEXMBS_CHECK(eigen.info() == Eigen::Success, "Rayleigh-Ritz: reduced eigenproblem failed");
  ritz.values = eigen.eigenvalues();
  const Eigen::MatrixXd V = WithLargestEntryPositive(eigen.eigenvectors());
  ritz.vectors = Q * V;
  ritz.transform = T * V;
  return ritz;
}

RitzResult RayleighRitz(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M,
                        const Eigen::MatrixXd& B) {
  return RayleighRitz(eigensolvers::SparseOperator(K), eigensolvers::SparseOperator(M), B);
}

void MOrthogonalizeAgainst(const eigensolvers::SymmetricOperator& M, const Eigen::MatrixXd& Q, Eigen::MatrixXd* X) {
  if (Q.cols() == 0 || X->cols() == 0) return;
  const Eigen::MatrixXd MQ = M.Times(Q);
  for (int pass = 0; pass < 2; ++pass) *X -= Q * (MQ.transpose() * *X);
}

void MOrthogonalizeAgainst(const Eigen::SparseMatrix<double>& M, const Eigen::MatrixXd& Q, Eigen::MatrixXd* X) {
  MOrthogonalizeAgainst(eigensolvers::SparseOperator(M), Q, X);
}

Eigen::MatrixXd MOrthonormalized(const eigensolvers::SymmetricOperator& M, const Eigen::MatrixXd& X) {
  if (X.cols() == 0) return X;
  const Eigen::MatrixXd MX = M.Times(X);
  Eigen::VectorXd scale(X.cols());
  for (Eigen::Index j = 0; j < X.cols(); ++j) {
    const double norm = std::sqrt(std::max(X.col(j).dot(MX.col(j)), 0.0));
    FLEXMBS_CHECK(norm > 0.0 && std::isfinite(norm), "M-orthonormalisation: zero or non-finite vector");
    scale(j) = 1.0 / norm;
  }
  Eigen::MatrixXd Q = X * scale.asDiagonal();
  for (int pass = 0; pass < 2; ++pass) CholeskyQrStep(M, &Q);
  return Q;
}

Eigen::MatrixXd MOrthonormalized(const Eigen::SparseMatrix<double>& M, const Eigen::MatrixXd& X) {
  return MOrthonormalized(eigensolvers::SparseOperator(M), X);
}

}  // namespace flexmbs::reduction
