#pragma once
// The SLEPc backend's shifted matrices K - sigma M on distributed PETSc matrices: the copy the
// shift-invert factorises, its Sturm counts by inertia, and the choice of the substructured
// factorisation on two or more ranks. Internal to reduction/ (includes PETSc).

#include <petscmat.h>

#include <memory>

#include "eigensolvers/eigensolver.h"
#include "eigensolvers/distributed/substructured_factor.h"

namespace flexmbs::eigensolvers {

/// A matrix destroyed with its owner unless released (also when an exception passes).
struct OwnedMat {
  Mat A = nullptr;
  OwnedMat() = default;
  OwnedMat(const OwnedMat&) = delete;
  OwnedMat& operator=(const OwnedMat&) = delete;
  ~OwnedMat() {
    if (A != nullptr) MatDestroy(&A);
  }
  /// Hands the matrix to the caller.
  Mat Release() {
    const Mat out = A;
    A = nullptr;
    return out;
  }
};

/// Whether A and B (AIJ, same layout) store the same sparsity pattern on every rank. Collective.
bool SamePattern(Mat A, Mat B);

/// K - sigma M as a new matrix (the caller destroys it), on the union of the patterns of K and M
/// (`same_pattern`: SamePattern(K, M)). Flagged symmetric, not positive definite, so that MUMPS
/// factorises it as a general symmetric matrix (SYM = 2: LDL^T with pivoting, the inertia known).
Mat ShiftedCopy(Mat K, Mat M, double sigma, bool same_pattern);

/// K - sigma M, owned: the matrix the shift-invert factorises, then moved to K - cut M in place
/// (same sparsity) for the Sturm count. Not flagged positive definite (ShiftedCopy), which keeps
/// the factorisation valid for the indefinite K - cut M in the same MUMPS instance.
class ShiftedMatrix {
 public:
  /// K and M [N/m, kg] must outlive the object; sigma [rad^2/s^2].
  ShiftedMatrix(Mat K, Mat M, double sigma);
  ShiftedMatrix(const ShiftedMatrix&) = delete;
  ShiftedMatrix& operator=(const ShiftedMatrix&) = delete;
  ~ShiftedMatrix();

  /// K - sigma M.
  Mat get() const { return A_; }
  /// A = K - sigma M becomes K - shift M, its sparsity unchanged.
  void MoveShift(double shift);

 private:
  Mat M_;
  double sigma_;
  bool same_pattern_;
  Mat A_ = nullptr;
};

/// The number of eigenvalues of K phi = lambda M phi below `cut`: the negative inertia of
/// K - cut M (Sylvester), from a MUMPS instance of its own that keeps no factors
/// (MumpsFactorization::kInertiaOnly). K - cut M is formed and freed here. Collective.
PetscInt EigenvaluesBelow(Mat K, Mat M, double cut);

/// K - sigma M (K itself when `held`) factorised by substructuring where `choice` asks for it,
/// or, for kAuto, on more than one rank when its interface has at most 12 000 rows (the dense S
/// takes 8 n^2 bytes on every rank); else null (the ST's MUMPS factorises). K - sigma M must be
/// positive definite but for round-off (the factor tells). Collective.
std::unique_ptr<SubstructuredFactor> MaybeSubstructured(Mat K, Mat M, bool held, double sigma,
                                                        DistributedFactorization choice);

}  // namespace flexmbs::eigensolvers
