#include "eigensolvers/distributed/slepc_solver.h"

#include <algorithm>
#include <chrono>
#include <fmt/format.h>
#include <slepceps.h>

#include "core/error.h"
#include "fem/petsc_check.h"
#include "eigensolvers/blas_threads.h"
#include "eigensolvers/distributed/slepc_attempt.h"
#include "eigensolvers/distributed/slepc_pair_measures.h"
#include "eigensolvers/distributed/slepc_shifted_matrix.h"
#include "eigensolvers/distributed/substructured_factor.h"

namespace flexmbs::eigensolvers {
namespace {

// Zeroes the rows and columns of `fixed_dofs` (K diagonal 1, M diagonal 0).
void RemoveFixedDofs(Mat K, Mat M, const std::vector<int>& fixed_dofs) {
  PetscInt begin = 0, end = 0;
  FLEXMBS_PETSC(MatGetOwnershipRange(K, &begin, &end));
  std::vector<PetscInt> owned;
  for (int dof : fixed_dofs) {
    if (dof >= begin && dof < end) owned.push_back(dof);
  }
  const auto count = static_cast<PetscInt>(owned.size());
  FLEXMBS_PETSC(MatZeroRowsColumns(K, count, owned.data(), 1.0, nullptr, nullptr));
  FLEXMBS_PETSC(MatZeroRowsColumns(M, count, owned.data(), 0.0, nullptr, nullptr));
  for (Mat A : {K, M}) FLEXMBS_PETSC(MatSetOption(A, MAT_SYMMETRIC, PETSC_TRUE));
}

// Copies this rank's block of rows of the full matrix A into a new PETSc AIJ matrix.
Mat ToPetsc(const Eigen::SparseMatrix<double>& A) {
  const Eigen::SparseMatrix<double, Eigen::RowMajor> rows = A;
  Mat out;
  FLEXMBS_PETSC(MatCreate(PETSC_COMM_WORLD, &out));
  FLEXMBS_PETSC(MatSetSizes(out, PETSC_DECIDE, PETSC_DECIDE, static_cast<PetscInt>(A.rows()),
                            static_cast<PetscInt>(A.cols())));
  FLEXMBS_PETSC(MatSetType(out, MATAIJ));
  FLEXMBS_PETSC(MatSetUp(out));
  PetscInt begin = 0, end = 0;
  FLEXMBS_PETSC(MatGetOwnershipRange(out, &begin, &end));
  // Exact preallocation from the row counts of the owned block.
  std::vector<PetscInt> diagonal(static_cast<std::size_t>(end - begin), 0), off(diagonal.size(), 0);
  for (PetscInt r = begin; r < end; ++r) {
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(rows, r); it; ++it) {
      const bool in_block = it.col() >= begin && it.col() < end;
      ++(in_block ? diagonal : off)[static_cast<std::size_t>(r - begin)];
    }
  }
  FLEXMBS_PETSC(MatXAIJSetPreallocation(out, 1, diagonal.data(), off.data(), nullptr, nullptr));
  for (PetscInt r = begin; r < end; ++r) {
    const auto start = rows.outerIndexPtr()[r];
    const auto count = static_cast<PetscInt>(rows.outerIndexPtr()[r + 1] - start);
    std::vector<PetscInt> cols(rows.innerIndexPtr() + start, rows.innerIndexPtr() + start + count);
    FLEXMBS_PETSC(MatSetValues(out, 1, &r, count, cols.data(), rows.valuePtr() + start, INSERT_VALUES));
  }
  FLEXMBS_PETSC(MatAssemblyBegin(out, MAT_FINAL_ASSEMBLY));
  FLEXMBS_PETSC(MatAssemblyEnd(out, MAT_FINAL_ASSEMBLY));
  return out;
}

class SlepcEigensolver final : public Eigensolver {
 public:
  std::string_view name() const override { return "slepc"; }

  EigenSolution Solve(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M,
                      const EigenOptions& options) const override {
    ValidateEigenInputs(K, M, options);
    // PETSc (and MPI) can be initialised once per process: keep it for the process lifetime
    // (a session the caller opened first owns it instead).
    static const SlepcSession session;
    Mat K_petsc = ToPetsc(K);
    Mat M_petsc = ToPetsc(M);
    try {
      EigenSolution solution = SolveDistributedEigenproblem(K_petsc, M_petsc, {}, options);
      MatDestroy(&K_petsc);
      MatDestroy(&M_petsc);
      return solution;
    } catch (...) {
      MatDestroy(&K_petsc);
      MatDestroy(&M_petsc);
      throw;
    }
  }
};

// The band's size and what is wanted of it (BandWanted), counted by the inertia of K - top M
// before any run; everything wanted (num_modes) when no band is asked for. Throws InputError
// for an empty band.
BandWanted CountBand(Mat K, Mat M, const EigenOptions& options, double top, EigenSolution* solution) {
  BandWanted band{options.num_modes, -1};
  if (!(options.max_frequency_hz > 0.0)) return band;
  auto phase = std::chrono::steady_clock::now();
  const PetscInt in_band = eigensolvers::EigenvaluesBelow(K, M, top);
  ++solution->factorizations;
  solution->sturm_seconds += SecondsSince(&phase);
  if (in_band == 0) throw InputError(fmt::format("eigenproblem: no mode below {:g} Hz", options.max_frequency_hz));
  band.wanted = options.num_modes > 0 ? std::min<PetscInt>(options.num_modes, in_band) : in_band;
  if (band.wanted == in_band) band.band_count = in_band;
  return band;
}

// On more than one rank K - sigma M may be factorised once by substructuring (every attempt's
// solves use it); it must be positive definite: K itself when held (`keep`), else sigma < 0.
// Null where MUMPS factorises; `*not_positive_definite` if a held K is not.
std::unique_ptr<SubstructuredFactor> FactorSubstructured(Mat K, Mat M, bool keep, const EigenOptions& options,
                                                         EigenSolution* solution, bool* not_positive_definite) {
  if (!keep && !(solution->shift < 0.0)) return nullptr;
  auto phase = std::chrono::steady_clock::now();
  std::unique_ptr<SubstructuredFactor> substructured =
      MaybeSubstructured(K, M, keep, solution->shift, options.distributed_factorization);
  if (!substructured) return nullptr;
  ++solution->factorizations;
  solution->factorization_seconds += SecondsSince(&phase);
  solution->factorization = "substructured";
  if (keep && !substructured->positive_definite()) *not_positive_definite = true;
  if (!keep && !substructured->positive_definite()) {
    solution->factorization = "mumps";
    return nullptr;  // MUMPS's LDL^T decides
  }
  return substructured;
}

// The modes, gathered as `modes_on` says, into solution->modes; the time into *gather_seconds.
void GatherModes(OwnedVectors* x, ModesOn modes_on, EigenSolution* solution, double* gather_seconds) {
  const auto gather_start = std::chrono::steady_clock::now();
  for (std::size_t j = 0; j < x->v.size(); ++j) {
    Eigen::VectorXd mode = GatherVector(x->v[j], modes_on);
    if (j == 0) solution->modes.resize(mode.size(), static_cast<Eigen::Index>(x->v.size()));
    solution->modes.col(static_cast<Eigen::Index>(j)) = mode;
  }
  x->Clear();
  if (gather_seconds) {
    *gather_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - gather_start).count();
  }
}

// Throws InputError naming the worst pair unless every residual meets its acceptance bound.
void CheckResiduals(const EigenSolution& solution, const EigenOptions& options) {
  const PairResiduals residuals{solution.relative_residuals, solution.residual_floors};
  Eigen::Index worst = 0;
  if (!residuals.Accepted(options.residual_tolerance, &worst)) {
    throw InputError(fmt::format("eigenproblem: mode {} ({:.6g} Hz) has relative residual {:.3g} above "
                                 "max({:g}, {:g} x its round-off floor {:.3g})",
                                 worst, FrequenciesHz(solution.eigenvalues)(worst),
                                 solution.relative_residuals(worst), options.residual_tolerance,
                                 kResidualFloorFactor, solution.residual_floors(worst)));
  }
}

// `before` added to its counts; `start` is when the whole solve began.
EigenSolution AddAbandonedWork(EigenSolution again, const EigenSolution& before,
                               std::chrono::steady_clock::time_point start) {
  again.factorizations += before.factorizations;
  again.factorization_seconds += before.factorization_seconds;
  again.operator_applications += before.operator_applications;
  again.krylov_runs += before.krylov_runs;
  again.restarts += before.restarts;
  again.krylov_seconds += before.krylov_seconds;
  again.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return again;
}

}  // namespace

SlepcSession::SlepcSession() {
  PetscBool initialized = PETSC_FALSE;
  FLEXMBS_PETSC(SlepcInitialized(&initialized));
  if (!initialized) {
    FLEXMBS_PETSC(SlepcInitializeNoArguments());
    owns_ = true;
    ShareBlasThreadsAmongRanks();
  }
}

SlepcSession::~SlepcSession() {
  if (owns_) SlepcFinalize();
}

int SlepcSession::Rank() {
  PetscMPIInt rank = 0;
  FLEXMBS_PETSC(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  return rank;
}

int SlepcSession::Size() {
  PetscMPIInt size = 1;
  FLEXMBS_PETSC(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  return size;
}

EigenSolution SolveDistributedEigenproblem(Mat K, Mat M, const std::vector<int>& fixed_dofs,
                                           const EigenOptions& options, ModesOn modes_on,
                                           double* gather_seconds, Mat* K_factor,
                                           std::unique_ptr<SubstructuredFactor>* K_substructured) {
  const auto start = std::chrono::steady_clock::now();
  RemoveFixedDofs(K, M, fixed_dofs);
  PetscScalar trace_k = 0.0, trace_m = 0.0;
  FLEXMBS_PETSC(MatGetTrace(K, &trace_k));
  FLEXMBS_PETSC(MatGetTrace(M, &trace_m));
  // A held body for a caller that keeps the factorisation: K itself at sigma = 0, factorised as
  // positive definite, later serves the caller's static solves.
  const bool keep = K_factor != nullptr && (!options.shift_hz || *options.shift_hz == 0.0);
  if (K_factor) *K_factor = nullptr;
  EigenSolution solution;
  solution.backend = "slepc";
  solution.factorization = "mumps";
  solution.shift = keep ? 0.0 : options.shift_hz ? ShiftFromHz(*options.shift_hz) : -1e-6 * trace_k / trace_m;
  // A band: its size, the number of eigenvalues below its upper end, is counted first (the inertia
  // of K - top M); then the lowest `wanted` modes are found as for num_modes, and when that is the
  // whole band, the count at its end is their Sturm check. (Not SLEPc's spectrum slicing: it ran
  // Krylov-Schur at the band's upper end, and the modes near zero, a free body's rigid modes, came
  // out with errors of about tolerance x top: residuals up to 6e-6 of their shift's scale.)
  const double top = options.max_frequency_hz > 0.0 ? ShiftFromHz(options.max_frequency_hz) : 0.0;
  const BandWanted band = CountBand(K, M, options, top, &solution);
  // Exactly the wanted pairs; the Ritz values beyond them locate the gap where the Sturm cut goes
  // (see RitzLowerBounds).
  PetscInt nev = band.wanted;
  OwnedVectors x;
  bool not_positive_definite = false;
  OwnedMat held_factor;  // kept: the factor of K (sigma = 0)
  std::unique_ptr<SubstructuredFactor> substructured =
      FactorSubstructured(K, M, keep, options, &solution, &not_positive_definite);
  const AttemptContext context{K, M, options, !fixed_dofs.empty(), keep, substructured.get(), band, top,
                               kZeroEigenvalue * trace_k / trace_m};
  for (int attempt = 0; !not_positive_definite; ++attempt) {
    const AttemptEnd end = RunAttempt(context, attempt, &nev, &x, &held_factor, &solution);
    if (end == AttemptEnd::kFound) break;
    if (end == AttemptEnd::kNotPositiveDefinite) not_positive_definite = true;
  }
  if (not_positive_definite) {
    // K is not positive definite (a body the conditions do not hold): the usual negative shift,
    // no factorisation kept; this attempt's work counted.
    x.Clear();
    FLEXMBS_PETSC(MatSetOption(K, MAT_SPD, PETSC_FALSE));
    return AddAbandonedWork(SolveDistributedEigenproblem(K, M, fixed_dofs, options, modes_on, gather_seconds),
                            solution, start);
  }
  GatherModes(&x, modes_on, &solution, gather_seconds);
  CheckResiduals(solution, options);
  if (keep) *K_factor = held_factor.Release();
  if (keep && substructured && K_substructured) *K_substructured = std::move(substructured);
  solution.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return solution;
}

std::unique_ptr<Eigensolver> MakeSlepcEigensolver() { return std::make_unique<SlepcEigensolver>(); }

}  // namespace flexmbs::eigensolvers
