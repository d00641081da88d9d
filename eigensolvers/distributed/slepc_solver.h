#pragma once

#include <memory>
#include <vector>

#include "eigensolvers/eigensolver.h"
#include "eigensolvers/distributed/substructured_factor.h"

// PETSc's matrix type (`Mat` is a pointer to it), declared here so that no PETSc header
// appears in this public header.
struct _p_Mat;

namespace flexmbs::eigensolvers {

/// Keeps SLEPc (and with it PETSc and MPI) initialised while it lives. Initialises only if
/// nobody has yet, and then finalises on destruction; nests safely. Does not read the command
/// line (flexmbs has its own).
class SlepcSession {
 public:
  SlepcSession();
  ~SlepcSession();
  SlepcSession(const SlepcSession&) = delete;
  SlepcSession& operator=(const SlepcSession&) = delete;

  /// This process's rank and the number of ranks in PETSC_COMM_WORLD.
  static int Rank();
  static int Size();

 private:
  bool owns_ = false;
};

/// Where SolveDistributedEigenproblem gathers the mode shapes.
enum class ModesOn {
  kEveryRank,  ///< full length on every rank
  kRankZero,   ///< full length on rank 0; the other ranks get 0 rows (eigenvalues and residuals everywhere)
};

/// Collective on PETSC_COMM_WORLD: eigenpairs of the distributed K phi = lambda M phi, as
/// `options` asks (the lowest num_modes, or all below max_frequency_hz: their number counted
/// first, by the inertia of K - lambda_max M, then found as the lowest modes), by SLEPc
/// Krylov-Schur with shift-and-invert, K - sigma M factorised by MUMPS Cholesky.
/// sigma = ShiftFromHz(*options.shift_hz), or -1e-6 trace(K)/trace(M) when unset (below every
/// eigenvalue, also of free bodies). `fixed_dofs` (global DOF numbers, the same list on every
/// rank) are removed by zeroing their rows and columns (K diagonal 1, M diagonal 0), which
/// moves their eigenvalues to infinity; K and M are modified in place. The modes are gathered
/// as `modes_on` says, in the matrices' row order; residuals and round-off floors are those of
/// EigenSolution, computed with distributed products (K x, M x, |K| |x|, |M| |x|); where a
/// Krylov-Schur pair misses its bound (options.residual_tolerance), one step of subspace
/// iteration with Rayleigh-Ritz refines the pairs with the same factorisation first
/// (refinement_steps; slepc_refinement.h);
/// `gather_seconds` (if given) receives the time of the gather [s]. The lowest modes are
/// checked by a Sturm count after the wanted ones (kSturmCount): the shift-invert's MUMPS
/// instance refactorises K - cut M numerically with its analysis kept, the cut placed by the
/// Krylov-Schur run's last Ritz values; for a whole band the cut is its end, counted before.
/// Fills EigenSolution's work counts and times: factorization_seconds (EPSSetUp: K - sigma M),
/// krylov_seconds (EPSSolve, the eigenvectors, their residuals and refinement), sturm_seconds,
/// factorizations (numeric), operator_applications (solves, the refinement's columns included),
/// krylov_runs, restarts (Krylov-Schur iterations), refinement_steps. Throws
/// InputError if fewer pairs converge than asked, a mode was missed twice or a pair misses its
/// residual bound, InternalError for a PETSc/SLEPc failure.
///
/// With `K_factor`, for a held body (options.shift_hz unset or 0): the shift is sigma = 0 and K
/// itself is factorised, as positive definite (MUMPS SYM = 1, no pivoting), and that
/// factorisation is not freed but handed to *K_factor (a factored PETSc matrix for MatSolve;
/// the caller destroys it, collectively) for the static solves after the solve. Sturm counts
/// (a band's, or the cut after the wanted modes) are then made in a MUMPS instance of their own,
/// which discards the factors as it makes them (ICNTL(31)): K - cut M is indefinite, so it needs
/// an LDL^T factorisation with pivoting, and only its inertia is wanted. If a mode was missed,
/// the second Krylov-Schur run factorises K again. If K proves not positive definite (the
/// factorisation fails or meets a negative pivot, or the lowest eigenvalue is zero to
/// round-off), it solves as without `K_factor` (the attempt's work counted) and leaves
/// *K_factor null; likewise for another shift. Where K was factorised by substructuring
/// (options.distributed_factorization) that factor goes to *K_substructured instead, if given
/// (*K_factor stays null).
EigenSolution SolveDistributedEigenproblem(_p_Mat* K, _p_Mat* M, const std::vector<int>& fixed_dofs,
                                           const EigenOptions& options, ModesOn modes_on = ModesOn::kEveryRank,
                                           double* gather_seconds = nullptr, _p_Mat** K_factor = nullptr,
                                           std::unique_ptr<SubstructuredFactor>* K_substructured = nullptr);

/// The backend "slepc" behind the serial interface: every rank passes the same K and M, each
/// copies its block of rows into PETSc matrices and SolveDistributedEigenproblem runs on them.
/// Under `mpirun -n N` the factorisation and the Krylov iteration are distributed.
std::unique_ptr<Eigensolver> MakeSlepcEigensolver();

}  // namespace flexmbs::eigensolvers
