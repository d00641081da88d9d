#pragma once
// What the SLEPc backend measures on distributed eigenpairs: the residuals, their round-off
// floors and the M-orthonormality (as defined in EigenSolution), with the products run where
// the rows are; the gather of a distributed mode; and the MUMPS factorisations made outside
// SLEPc (static solves, Sturm counts beside a kept factor). Internal to the PETSc code of this
// module: it names PETSc types, so only .cc files include it (slepc_solver.cc,
// distributed_reduction.cc, distributed_model.cc), never a header other modules see.

#include <petscmat.h>

#include <Eigen/Core>
#include <vector>

#include "eigensolvers/eigensolver.h"
#include "eigensolvers/distributed/slepc_solver.h"

namespace flexmbs::eigensolvers {

/// |A|: a copy of the AIJ matrix A (sequential or distributed) with the absolute values of its
/// entries; the caller destroys it. Collective.
Mat AbsoluteCopy(Mat A);

/// Copies a distributed vector into a full-length Eigen vector on every rank, or on rank 0 only
/// (the other ranks get an empty vector). Collective.
Eigen::VectorXd GatherVector(Vec x, ModesOn modes_on);

/// Fills solution's relative_residuals, residual_floors and orthonormality_error for the pairs
/// (solution->eigenvalues(j), x[j]) of K, M (distributed AIJ, same layout as x), with the shift
/// solution->shift: one per vector, for the first x.size() eigenvalues. Collective.
void MeasurePairs(Mat K, Mat M, const std::vector<Vec>& x, EigenSolution* solution);

/// What a MUMPS Cholesky factorisation is for.
enum class MumpsFactorization {
  /// Solves with a positive definite matrix: SYM = 1, L D L^T without pivoting.
  kPositiveDefinite,
  /// The inertia of a symmetric indefinite matrix only: SYM = 2 (L D L^T with pivoting), the
  /// inertia counted on every rank (ICNTL(13) = 1), the factors discarded as they are made
  /// (ICNTL(31) = 1: MatGetInertia works, MatSolve does not), so that it takes the active
  /// memory of the factorisation only (measured at 97 659 DOF: 119 MB against 595 MB).
  kInertiaOnly,
};

/// Factorises the symmetric AIJ matrix A (sequential or distributed) by MUMPS Cholesky, analysis
/// and numeric phase, as `kind` says (A's MAT_SPD flag is set accordingly); `prefix` names its
/// options (-<prefix>mat_mumps_icntl_...). Returns the factored matrix (the caller destroys it)
/// also if MUMPS reported a failure (MatFactorGetError, FactoredPositiveDefinite). Collective.
Mat MumpsCholesky(Mat A, MumpsFactorization kind, const char* prefix);

/// Whether the MUMPS factorisation `factor` of a matrix factorised as positive definite (SYM = 1)
/// succeeded and met no negative pivot (INFOG(12); on more than one rank without those of
/// ScaLAPACK's root node unless ICNTL(13) = 1): else the matrix is not positive definite to
/// working precision. MUMPS's global counts: every rank gets the same answer.
bool FactoredPositiveDefinite(Mat factor);

}  // namespace flexmbs::eigensolvers
