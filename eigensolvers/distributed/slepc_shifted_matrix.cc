#include "eigensolvers/distributed/slepc_shifted_matrix.h"

#include <algorithm>

#include "core/error.h"
#include "fem/petsc_check.h"
#include "eigensolvers/distributed/slepc_pair_measures.h"
#include "eigensolvers/distributed/slepc_solver.h"

namespace flexmbs::eigensolvers {

bool SamePattern(Mat A, Mat B) {
  const auto same_seq = [](Mat X, Mat Y) {
    PetscInt nx = 0, ny = 0;
    const PetscInt *ix = nullptr, *jx = nullptr, *iy = nullptr, *jy = nullptr;
    PetscBool done_x = PETSC_FALSE, done_y = PETSC_FALSE;
    FLEXMBS_PETSC(MatGetRowIJ(X, 0, PETSC_FALSE, PETSC_FALSE, &nx, &ix, &jx, &done_x));
    FLEXMBS_PETSC(MatGetRowIJ(Y, 0, PETSC_FALSE, PETSC_FALSE, &ny, &iy, &jy, &done_y));
    const bool same = done_x && done_y && nx == ny && std::equal(ix, ix + nx + 1, iy) &&
                      std::equal(jx, jx + ix[nx], jy);
    FLEXMBS_PETSC(MatRestoreRowIJ(X, 0, PETSC_FALSE, PETSC_FALSE, &nx, &ix, &jx, &done_x));
    FLEXMBS_PETSC(MatRestoreRowIJ(Y, 0, PETSC_FALSE, PETSC_FALSE, &ny, &iy, &jy, &done_y));
    return same;
  };
  PetscBool distributed = PETSC_FALSE;
  FLEXMBS_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(A), MATMPIAIJ, &distributed));
  int same = 0;
  if (distributed) {
    // Diagonal and off-diagonal blocks, the latter with compressed columns (colmap: global index).
    Mat A_diagonal, A_off, B_diagonal, B_off;
    const PetscInt *A_columns = nullptr, *B_columns = nullptr;
    FLEXMBS_PETSC(MatMPIAIJGetSeqAIJ(A, &A_diagonal, &A_off, &A_columns));
    FLEXMBS_PETSC(MatMPIAIJGetSeqAIJ(B, &B_diagonal, &B_off, &B_columns));
    PetscInt A_count = 0, B_count = 0;
    FLEXMBS_PETSC(MatGetSize(A_off, nullptr, &A_count));
    FLEXMBS_PETSC(MatGetSize(B_off, nullptr, &B_count));
    same = A_count == B_count && std::equal(A_columns, A_columns + A_count, B_columns) &&
           same_seq(A_diagonal, B_diagonal) && same_seq(A_off, B_off);
  } else {
    same = same_seq(A, B);
  }
  FLEXMBS_PETSC(MPI_Allreduce(MPI_IN_PLACE, &same, 1, MPI_INT, MPI_LAND,
                              PetscObjectComm(reinterpret_cast<PetscObject>(A))));
  return same != 0;
}

Mat ShiftedCopy(Mat K, Mat M, double sigma, bool same_pattern) {
  Mat A;
  FLEXMBS_PETSC(MatDuplicate(K, MAT_COPY_VALUES, &A));
  // Where M has entries K has not, A gets the union of the patterns (so M's is a subset).
  FLEXMBS_PETSC(
      MatAXPY(A, -sigma, M, same_pattern ? SAME_NONZERO_PATTERN : DIFFERENT_NONZERO_PATTERN));
  FLEXMBS_PETSC(MatSetOption(A, MAT_SYMMETRIC, PETSC_TRUE));
  FLEXMBS_PETSC(MatSetOption(A, MAT_SPD, PETSC_FALSE));
  return A;
}

ShiftedMatrix::ShiftedMatrix(Mat K, Mat M, double sigma)
    : M_(M),
      sigma_(sigma),
      same_pattern_(SamePattern(K, M)),
      A_(ShiftedCopy(K, M, sigma, same_pattern_)) {}

ShiftedMatrix::~ShiftedMatrix() { MatDestroy(&A_); }

void ShiftedMatrix::MoveShift(double shift) {
  FLEXMBS_PETSC(MatAXPY(A_, sigma_ - shift, M_,
                        same_pattern_ ? SAME_NONZERO_PATTERN : SUBSET_NONZERO_PATTERN));
  sigma_ = shift;
}

PetscInt EigenvaluesBelow(Mat K, Mat M, double cut) {
  OwnedMat shifted, factor;
  shifted.A = ShiftedCopy(K, M, cut, SamePattern(K, M));
  factor.A = MumpsCholesky(shifted.A, MumpsFactorization::kInertiaOnly, "flexmbs_sturm_");
  MatFactorError error = MAT_FACTOR_NOERROR;
  FLEXMBS_PETSC(MatFactorGetError(factor.A, &error));
  FLEXMBS_CHECK(error == MAT_FACTOR_NOERROR, "Sturm count: MUMPS failed to factorise K - cut M");
  PetscInt negative = 0;
  FLEXMBS_PETSC(MatGetInertia(factor.A, &negative, nullptr, nullptr));
  return negative;
}

namespace {

// Above this many interface rows the automatic choice stays with MUMPS: the substructured
// factor's dense interface matrix takes 8 n^2 bytes on every rank (twice that while summed).
constexpr std::int64_t kMaxAutoInterfaceRows = 12000;

}  // namespace

std::unique_ptr<SubstructuredFactor> MaybeSubstructured(Mat K, Mat M, bool held, double sigma,
                                                        DistributedFactorization choice) {
  if (choice == DistributedFactorization::kMumps) return nullptr;
  if (choice == DistributedFactorization::kAuto && SlepcSession::Size() < 2) return nullptr;
  OwnedMat shifted;
  if (!held) shifted.A = ShiftedCopy(K, M, sigma, SamePattern(K, M));
  const Mat A = held ? K : shifted.A;
  if (choice == DistributedFactorization::kAuto)
    return SubstructuredFactor::IfInterfaceAtMost(A, kMaxAutoInterfaceRows);
  return std::make_unique<SubstructuredFactor>(A);
}

}  // namespace flexmbs::eigensolvers
