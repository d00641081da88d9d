#include "eigensolvers/distributed/petsc_block_space.h"

#include <vector>

#include "fem/petsc_check.h"

namespace flexmbs::eigensolvers {

using Matrix = Eigen::MatrixXd;

PetscBlockSpace::PetscBlockSpace(Mat factor, Mat M, double sigma) : factor_(factor), M_(M), sigma_(sigma) {
  FLEXMBS_PETSC(PetscObjectGetComm(reinterpret_cast<PetscObject>(M), &comm_));
  FLEXMBS_PETSC(MPI_Comm_rank(comm_, &rank_));
  PetscInt local = 0, global = 0;
  FLEXMBS_PETSC(MatGetLocalSize(M, &local, nullptr));
  FLEXMBS_PETSC(MatGetSize(M, &global, nullptr));
  local_rows_ = local;
  global_rows_ = global;
}

PetscBlockSpace::PetscBlockSpace(const SubstructuredFactor& factor, Mat M, double sigma)
    : PetscBlockSpace(static_cast<Mat>(nullptr), M, sigma) {
  substructured_ = &factor;
}

Matrix PetscBlockSpace::ShiftInvert(const Matrix& B) const {
  FLEXMBS_CHECK(B.rows() == local_rows_, "PetscBlockSpace: a block of another row count");
  Matrix X(local_rows_, B.cols());
  if (B.cols() == 0) return X;
  if (substructured_) {
    substructured_->SolveColumns(B.data(), X.data(), static_cast<int>(B.cols()));
    return X;
  }
  // Dense PETSc matrices on the blocks' own storage (column-major, leading dimension = local
  // rows, as Eigen's): MUMPS solves all columns in one pass over its factors.
  Mat rhs = nullptr, solution = nullptr;
  const auto columns = static_cast<PetscInt>(B.cols());
  FLEXMBS_PETSC(MatCreateDense(comm_, static_cast<PetscInt>(local_rows_), PETSC_DECIDE,
                               static_cast<PetscInt>(global_rows_), columns, const_cast<double*>(B.data()), &rhs));
  FLEXMBS_PETSC(MatCreateDense(comm_, static_cast<PetscInt>(local_rows_), PETSC_DECIDE,
                               static_cast<PetscInt>(global_rows_), columns, X.data(), &solution));
  const PetscErrorCode error = MatMatSolve(factor_, rhs, solution);
  MatDestroy(&rhs);
  MatDestroy(&solution);
  FLEXMBS_PETSC(error);
  return X;
}

Matrix PetscBlockSpace::Mass(const Matrix& X) const {
  FLEXMBS_CHECK(X.rows() == local_rows_, "PetscBlockSpace: a block of another row count");
  Matrix Y(local_rows_, X.cols());
  if (X.cols() == 0) return Y;
  // One sparse-times-dense product for all columns: one pass over M, not one per column.
  Mat x = nullptr, y = nullptr;
  FLEXMBS_PETSC(MatCreateDense(comm_, static_cast<PetscInt>(local_rows_), PETSC_DECIDE,
                               static_cast<PetscInt>(global_rows_), static_cast<PetscInt>(X.cols()),
                               const_cast<double*>(X.data()), &x));
  PetscErrorCode error = MatMatMult(M_, x, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &y);
  const PetscScalar* values = nullptr;
  PetscInt leading = 0;
  if (error == 0) error = MatDenseGetLDA(y, &leading);
  if (error == 0) error = MatDenseGetArrayRead(y, &values);
  if (error == 0) {
    for (Eigen::Index j = 0; j < X.cols(); ++j) {
      Y.col(j) = Eigen::Map<const Eigen::VectorXd>(values + j * leading, local_rows_);
    }
    error = MatDenseRestoreArrayRead(y, &values);
  }
  MatDestroy(&x);
  MatDestroy(&y);
  FLEXMBS_PETSC(error);
  return Y;
}

Eigen::VectorXd PetscBlockSpace::MassDiagonal() const {
  Vec d = nullptr;
  FLEXMBS_PETSC(MatCreateVecs(M_, &d, nullptr));
  Eigen::VectorXd diagonal(local_rows_);
  PetscErrorCode error = MatGetDiagonal(M_, d);
  const PetscScalar* values = nullptr;
  if (error == 0) error = VecGetArrayRead(d, &values);
  if (error == 0) {
    for (Eigen::Index i = 0; i < local_rows_; ++i) diagonal(i) = values[i];
    error = VecRestoreArrayRead(d, &values);
  }
  VecDestroy(&d);
  FLEXMBS_PETSC(error);
  return diagonal;
}

Matrix PetscBlockSpace::Sum(const Matrix& local) const {
  Matrix sum = local;
  FLEXMBS_PETSC(MPI_Allreduce(MPI_IN_PLACE, sum.data(), static_cast<int>(sum.size()), MPI_DOUBLE, MPI_SUM, comm_));
  return sum;
}

Matrix LocalRows(const std::vector<Vec>& x, Eigen::Index local_rows) {
  Matrix rows(local_rows, static_cast<Eigen::Index>(x.size()));
  for (std::size_t j = 0; j < x.size(); ++j) {
    const PetscScalar* values = nullptr;
    FLEXMBS_PETSC(VecGetArrayRead(x[j], &values));
    for (Eigen::Index i = 0; i < local_rows; ++i) rows(i, static_cast<Eigen::Index>(j)) = values[i];
    FLEXMBS_PETSC(VecRestoreArrayRead(x[j], &values));
  }
  return rows;
}

}  // namespace flexmbs::eigensolvers
