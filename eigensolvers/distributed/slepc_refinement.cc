#include "eigensolvers/distributed/slepc_refinement.h"

#include <Eigen/Eigenvalues>
#include <cmath>

#include "core/error.h"
#include "eigensolvers/distributed/petsc_block_space.h"
#include "fem/petsc_check.h"

namespace flexmbs::eigensolvers {
namespace {

// Writes the columns of `rows` (this rank's rows) into the distributed vectors x.
void SetLocalRows(const Eigen::MatrixXd& rows, std::vector<Vec>* x) {
  for (std::size_t j = 0; j < x->size(); ++j) {
    PetscScalar* values = nullptr;
    FLEXMBS_PETSC(VecGetArray((*x)[j], &values));
    Eigen::Map<Eigen::VectorXd>(values, rows.rows()) = rows.col(static_cast<Eigen::Index>(j));
    FLEXMBS_PETSC(VecRestoreArray((*x)[j], &values));
  }
}

}  // namespace

void RefineBySubspaceIteration(const BlockKrylovSpace& space, std::vector<Vec>* x, Eigen::VectorXd* eigenvalues) {
  FLEXMBS_CHECK(static_cast<Eigen::Index>(x->size()) == eigenvalues->size(),
                "RefineBySubspaceIteration: one eigenvalue per vector");
  if (x->empty()) return;
  const Eigen::MatrixXd X = LocalRows(*x, space.local_rows());
  const Eigen::MatrixXd MX = space.Mass(X);
  const Eigen::MatrixXd Y = space.ShiftInvert(MX);
  const Eigen::MatrixXd MY = space.Mass(Y);
  Eigen::MatrixXd gram_m = space.Sum(Y.transpose() * MY);
  Eigen::MatrixXd gram_k = space.Sum(Y.transpose() * MX) + space.sigma() * gram_m;
  // Y's columns are about x_j / (lambda_j - sigma): scaled to unit M norm the problem is near
  // diagonal with near-unit B, whatever the spread of the eigenvalues.
  const Eigen::VectorXd scale = gram_m.diagonal().cwiseSqrt().cwiseInverse();
  gram_m = scale.asDiagonal() * gram_m * scale.asDiagonal();
  gram_k = scale.asDiagonal() * gram_k * scale.asDiagonal();
  // The sums of products are symmetric but for round-off.
  const Eigen::MatrixXd A = 0.5 * (gram_k + gram_k.transpose());
  const Eigen::MatrixXd B = 0.5 * (gram_m + gram_m.transpose());
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ritz(A, B);
  FLEXMBS_CHECK(ritz.info() == Eigen::Success, "RefineBySubspaceIteration: Rayleigh-Ritz failed");
  SetLocalRows(Y * (scale.asDiagonal() * ritz.eigenvectors()), x);
  *eigenvalues = ritz.eigenvalues();
}

}  // namespace flexmbs::eigensolvers
