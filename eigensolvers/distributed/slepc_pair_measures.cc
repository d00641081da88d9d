#include "eigensolvers/distributed/slepc_pair_measures.h"

#include <cmath>

#include "core/error.h"
#include "fem/petsc_check.h"

namespace flexmbs::eigensolvers {
namespace {

// Replaces every stored value of a sequential AIJ matrix by its absolute value.
void AbsoluteValuesSeq(Mat A) {
  MatInfo info;
  FLEXMBS_PETSC(MatGetInfo(A, MAT_LOCAL, &info));
  PetscScalar* values = nullptr;
  FLEXMBS_PETSC(MatSeqAIJGetArray(A, &values));
  const auto count = static_cast<PetscInt>(info.nz_used);
  for (PetscInt k = 0; k < count; ++k) values[k] = std::abs(values[k]);
  FLEXMBS_PETSC(MatSeqAIJRestoreArray(A, &values));
}

}  // namespace

Mat AbsoluteCopy(Mat A) {
  Mat out;
  FLEXMBS_PETSC(MatDuplicate(A, MAT_COPY_VALUES, &out));
  PetscBool distributed = PETSC_FALSE;
  FLEXMBS_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(out), MATMPIAIJ, &distributed));
  if (distributed) {
    Mat diagonal_block, off_block;
    FLEXMBS_PETSC(MatMPIAIJGetSeqAIJ(out, &diagonal_block, &off_block, nullptr));
    AbsoluteValuesSeq(diagonal_block);
    AbsoluteValuesSeq(off_block);
  } else {
    AbsoluteValuesSeq(out);
  }
  return out;
}

namespace {

// The norm of the distributed vector x, squared.
double SquaredNorm(Vec x) {
  PetscReal norm = 0.0;
  FLEXMBS_PETSC(VecNorm(x, NORM_2, &norm));
  return norm * norm;
}

}  // namespace

// Copies a distributed vector into a full-length Eigen vector on every rank, or on rank 0 only
// (the other ranks get an empty vector).
Eigen::VectorXd GatherVector(Vec x, ModesOn modes_on) {
  VecScatter scatter;
  Vec all;
  if (modes_on == ModesOn::kEveryRank) {
    FLEXMBS_PETSC(VecScatterCreateToAll(x, &scatter, &all));
  } else {
    FLEXMBS_PETSC(VecScatterCreateToZero(x, &scatter, &all));
  }
  FLEXMBS_PETSC(VecScatterBegin(scatter, x, all, INSERT_VALUES, SCATTER_FORWARD));
  FLEXMBS_PETSC(VecScatterEnd(scatter, x, all, INSERT_VALUES, SCATTER_FORWARD));
  PetscInt n = 0;
  FLEXMBS_PETSC(VecGetLocalSize(all, &n));
  const PetscScalar* values = nullptr;
  FLEXMBS_PETSC(VecGetArrayRead(all, &values));
  Eigen::VectorXd out = Eigen::Map<const Eigen::VectorXd>(values, n);
  FLEXMBS_PETSC(VecRestoreArrayRead(all, &values));
  FLEXMBS_PETSC(VecScatterDestroy(&scatter));
  FLEXMBS_PETSC(VecDestroy(&all));
  return out;
}

// Fills residuals, round-off floors and the M-orthonormality error of the pairs (lambda, x),
// x distributed: the products with K, M, |K| and |M| run where the rows are. One copy with
// absolute values at a time (|K| with the products with K and M, then |M|), keeping |K| |x_j|:
// they are made while the factorisation of K - sigma M lives (RunAttempt).
void MeasurePairs(Mat K, Mat M, const std::vector<Vec>& x, EigenSolution* solution) {
  const auto n = static_cast<Eigen::Index>(x.size());
  FLEXMBS_CHECK(n <= solution->eigenvalues.size(), "MeasurePairs: more vectors than eigenvalues");
  const Eigen::VectorXd lambda = solution->eigenvalues.head(n);
  Vec kx, mx, abs_x, abs_mx;
  Vec* abs_kx = nullptr;
  FLEXMBS_PETSC(MatCreateVecs(K, &abs_x, &kx));
  for (Vec* v : {&mx, &abs_mx}) FLEXMBS_PETSC(VecDuplicate(kx, v));
  FLEXMBS_PETSC(VecDuplicateVecs(kx, static_cast<PetscInt>(n), &abs_kx));
  Eigen::MatrixXd sums(4, n), gram(n, n);
  Mat abs_A = AbsoluteCopy(K);
  for (Eigen::Index j = 0; j < n; ++j) {
    const Vec xj = x[static_cast<std::size_t>(j)];
    FLEXMBS_PETSC(MatMult(K, xj, kx));
    FLEXMBS_PETSC(MatMult(M, xj, mx));
    FLEXMBS_PETSC(VecMDot(mx, static_cast<PetscInt>(n), x.data(), gram.col(j).data()));
    FLEXMBS_PETSC(VecCopy(xj, abs_x));
    FLEXMBS_PETSC(VecAbs(abs_x));
    FLEXMBS_PETSC(MatMult(abs_A, abs_x, abs_kx[j]));
    sums(0, j) = SquaredNorm(kx);
    sums(1, j) = SquaredNorm(mx);
    FLEXMBS_PETSC(VecAXPY(kx, -lambda(j), mx));
    sums(2, j) = SquaredNorm(kx);
  }
  FLEXMBS_PETSC(MatDestroy(&abs_A));
  abs_A = AbsoluteCopy(M);
  for (Eigen::Index j = 0; j < n; ++j) {
    FLEXMBS_PETSC(VecCopy(x[static_cast<std::size_t>(j)], abs_x));
    FLEXMBS_PETSC(VecAbs(abs_x));
    FLEXMBS_PETSC(MatMult(abs_A, abs_x, abs_mx));
    FLEXMBS_PETSC(VecAXPY(abs_kx[j], std::abs(lambda(j)), abs_mx));
    sums(3, j) = SquaredNorm(abs_kx[j]);
  }
  FLEXMBS_PETSC(MatDestroy(&abs_A));
  FLEXMBS_PETSC(VecDestroyVecs(static_cast<PetscInt>(n), &abs_kx));
  for (Vec* v : {&kx, &mx, &abs_x, &abs_mx}) FLEXMBS_PETSC(VecDestroy(v));
  PetscScalar trace_k = 0.0, trace_m = 0.0;
  FLEXMBS_PETSC(MatGetTrace(K, &trace_k));
  FLEXMBS_PETSC(MatGetTrace(M, &trace_m));
  const PairResiduals residuals =
      ResidualsFromSums(sums, lambda, solution->shift, kZeroEigenvalue * trace_k / trace_m);
  solution->relative_residuals = residuals.relative;
  solution->residual_floors = residuals.floor;
  solution->orthonormality_error = (gram - Eigen::MatrixXd::Identity(n, n)).cwiseAbs().maxCoeff();
}

Mat MumpsCholesky(Mat A, MumpsFactorization kind, const char* prefix) {
  const bool positive_definite = kind == MumpsFactorization::kPositiveDefinite;
  FLEXMBS_PETSC(MatSetOption(A, MAT_SYMMETRIC, PETSC_TRUE));
  FLEXMBS_PETSC(MatSetOption(A, MAT_SPD, positive_definite ? PETSC_TRUE : PETSC_FALSE));
  Mat factor;
  FLEXMBS_PETSC(MatGetFactor(A, MATSOLVERMUMPS, MAT_FACTOR_CHOLESKY, &factor));
  FLEXMBS_PETSC(MatSetOptionsPrefix(factor, prefix));
  if (!positive_definite) {
    // Without ICNTL(13) = 1 (the root node on ScaLAPACK) MUMPS does not report the inertia on
    // more than one rank; ICNTL(31) = 1 discards the factors (only the inertia is wanted).
    FLEXMBS_PETSC(MatMumpsSetIcntl(factor, 13, 1));
    FLEXMBS_PETSC(MatMumpsSetIcntl(factor, 31, 1));
  }
  MatFactorInfo info;
  FLEXMBS_PETSC(MatFactorInfoInitialize(&info));
  // MUMPS orders the matrix itself (PETSc's "external" ordering: no permutation given).
  FLEXMBS_PETSC(MatCholeskyFactorSymbolic(factor, A, nullptr, &info));
  FLEXMBS_PETSC(MatCholeskyFactorNumeric(factor, A, &info));
  return factor;
}

bool FactoredPositiveDefinite(Mat factor) {
  MatFactorError error = MAT_FACTOR_NOERROR;
  FLEXMBS_PETSC(MatFactorGetError(factor, &error));
  if (error != MAT_FACTOR_NOERROR) return false;
  PetscInt negative = 0;
  FLEXMBS_PETSC(MatMumpsGetInfog(factor, 12, &negative));
  return negative == 0;
}

}  // namespace flexmbs::eigensolvers
