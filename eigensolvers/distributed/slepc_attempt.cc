#include "eigensolvers/distributed/slepc_attempt.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numeric>
#include <optional>

#include "core/error.h"
#include "fem/petsc_check.h"
#include "eigensolvers/block_krylov_check.h"
#include "eigensolvers/distributed/petsc_block_space.h"
#include "eigensolvers/distributed/slepc_pair_measures.h"
#include "eigensolvers/distributed/slepc_refinement.h"
#include "eigensolvers/distributed/slepc_ritz_gap.h"

namespace flexmbs::eigensolvers {
namespace {

// The shell preconditioner's apply: x = (K - sigma M)^-1 b by the SubstructuredFactor in its
// context.
PetscErrorCode ApplySubstructured(PC pc, Vec b, Vec x) {
  void* context = nullptr;
  PetscErrorCode error = PCShellGetContext(pc, &context);
  if (error != 0) return error;
  try {
    static_cast<const SubstructuredFactor*>(context)->Solve(b, x);
  } catch (const std::exception&) {
    return PETSC_ERR_LIB;
  }
  return 0;
}

// Configures `eps` for K, M: Krylov-Schur, shift-and-invert at sigma, MUMPS Cholesky, the `nev`
// pairs nearest sigma. Purification (one more solve per pair, removing components in M's null
// space) only where fixed DOF make M singular: with M positive definite the shift-inverted
// operator has no such components to remove. The ST factorises `shifted` (K - sigma M, owned by
// the caller, who refactorises it for the Sturm count) instead of a copy of its own, or,
// `shifted` null at sigma = 0, K itself (no copy: SLEPc's ST_MATMODE_COPY uses K when the shift
// is 0). MUMPS gets ICNTL(13) = 1 before its analysis: without it (the root node on ScaLAPACK)
// it does not report the inertia on more than one rank (the ST prefixes its factor's options).
// With `substructured` (K - sigma M factorised by substructuring) the ST's solves are its solves
// instead (a shell preconditioner under KSPPREONLY) and `shifted` is not used.
void Configure(EPS eps, Mat K, Mat M, Mat shifted, double sigma, const EigenOptions& options, PetscInt nev,
               bool singular_mass, const SubstructuredFactor* substructured) {
  ST st;
  KSP ksp;
  PC pc;
  FLEXMBS_PETSC(EPSSetOperators(eps, K, M));
  FLEXMBS_PETSC(EPSSetProblemType(eps, EPS_GHEP));
  FLEXMBS_PETSC(EPSSetType(eps, EPSKRYLOVSCHUR));
  FLEXMBS_PETSC(EPSSetTolerances(eps, options.tolerance, options.max_iterations));
  FLEXMBS_PETSC(EPSSetPurify(eps, singular_mass ? PETSC_TRUE : PETSC_FALSE));
  FLEXMBS_PETSC(PetscOptionsSetValue(nullptr, "-st_mat_mumps_icntl_13", "1"));
  FLEXMBS_PETSC(EPSSetDimensions(eps, nev, PETSC_DEFAULT, PETSC_DEFAULT));
  FLEXMBS_PETSC(EPSSetTarget(eps, sigma));
  FLEXMBS_PETSC(EPSSetWhichEigenpairs(eps, EPS_TARGET_MAGNITUDE));
  FLEXMBS_PETSC(EPSGetST(eps, &st));
  FLEXMBS_PETSC(STSetType(st, STSINVERT));
  if (substructured) {
    FLEXMBS_PETSC(STSetMatMode(st, ST_MATMODE_SHELL));
    FLEXMBS_PETSC(STGetKSP(st, &ksp));
    FLEXMBS_PETSC(KSPSetType(ksp, KSPPREONLY));
    FLEXMBS_PETSC(KSPGetPC(ksp, &pc));
    FLEXMBS_PETSC(PCSetType(pc, PCSHELL));
    FLEXMBS_PETSC(PCShellSetContext(pc, const_cast<SubstructuredFactor*>(substructured)));
    FLEXMBS_PETSC(PCShellSetApply(pc, ApplySubstructured));
    return;
  }
  if (shifted) {
    FLEXMBS_PETSC(STSetPreconditionerMat(st, shifted));
    FLEXMBS_PETSC(STSetMatMode(st, ST_MATMODE_SHELL));
  }
  FLEXMBS_PETSC(STGetKSP(st, &ksp));
  FLEXMBS_PETSC(KSPSetType(ksp, KSPPREONLY));
  FLEXMBS_PETSC(KSPGetPC(ksp, &pc));
  FLEXMBS_PETSC(PCSetType(pc, PCCHOLESKY));
  FLEXMBS_PETSC(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
}

// eigenvalues into `solution`, the eigenvectors as distributed vectors into `x` (the caller
// owns them).
void ExtractPairs(EPS eps, Mat K, Mat M, int limit, EigenSolution* solution, std::vector<Vec>* x) {
  PetscInt converged = 0;
  FLEXMBS_PETSC(EPSGetConverged(eps, &converged));
  std::vector<double> lambdas(static_cast<std::size_t>(converged));
  for (PetscInt i = 0; i < converged; ++i) {
    FLEXMBS_PETSC(EPSGetEigenvalue(eps, i, &lambdas[static_cast<std::size_t>(i)], nullptr));
  }
  std::vector<PetscInt> order(lambdas.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](PetscInt a, PetscInt b) {
    return lambdas[static_cast<std::size_t>(a)] < lambdas[static_cast<std::size_t>(b)];
  });
  if (limit > 0 && static_cast<int>(order.size()) > limit) order.resize(static_cast<std::size_t>(limit));
  const auto count = static_cast<Eigen::Index>(order.size());
  solution->eigenvalues.resize(count);
  Vec mx;
  FLEXMBS_PETSC(MatCreateVecs(K, nullptr, &mx));
  for (Eigen::Index j = 0; j < count; ++j) {
    const PetscInt i = order[static_cast<std::size_t>(j)];
    Vec xj;
    FLEXMBS_PETSC(VecDuplicate(mx, &xj));
    x->push_back(xj);
    FLEXMBS_PETSC(EPSGetEigenvector(eps, i, xj, nullptr));
    PetscScalar xmx = 0.0;
    FLEXMBS_PETSC(MatMult(M, xj, mx));
    FLEXMBS_PETSC(VecDot(xj, mx, &xmx));
    FLEXMBS_PETSC(VecScale(xj, 1.0 / std::sqrt(xmx)));
    solution->eigenvalues(j) = lambdas[static_cast<std::size_t>(i)];
  }
  FLEXMBS_PETSC(VecDestroy(&mx));
}

// The factored matrix of the shift-and-invert's MUMPS instance (after EPSSetUp).
Mat ShiftInvertFactor(EPS eps) {
  ST st;
  KSP ksp;
  PC pc;
  Mat factor;
  FLEXMBS_PETSC(EPSGetST(eps, &st));
  FLEXMBS_PETSC(STGetKSP(st, &ksp));
  FLEXMBS_PETSC(KSPGetPC(ksp, &pc));
  FLEXMBS_PETSC(PCFactorGetMatrix(pc, &factor));
  return factor;
}

// The number of eigenvalues of K phi = lambda M phi below `cut`: the negative inertia of
// K - cut M (Sylvester; M positive semi-definite, fixed DOF have K = 1, M = 0 and count as
// positive), from the LDL^T factorisation of the shift-invert's own MUMPS instance. `shifted`
// (which the ST of `eps` factorised) becomes K - cut M and is refactorised numerically: MUMPS
// keeps its analysis (ordering, symbolic factorisation), which the same sparsity allows. The
// ST's factor is then that of K - cut M: call after the pairs are extracted.
PetscInt EigenvaluesBelow(EPS eps, ShiftedMatrix* shifted, double cut) {
  const Mat factor = ShiftInvertFactor(eps);
  shifted->MoveShift(cut);
  MatFactorInfo info;
  FLEXMBS_PETSC(MatFactorInfoInitialize(&info));
  FLEXMBS_PETSC(MatCholeskyFactorNumeric(factor, shifted->get(), &info));
  PetscInt negative = 0;  // zero and positive counts would need null-pivot detection (ICNTL(24))
  FLEXMBS_PETSC(MatGetInertia(factor, &negative, nullptr, nullptr));
  return negative;
}

// An EPS destroyed with its owner (also when an exception passes).
struct OwnedEps {
  EPS eps = nullptr;
  OwnedEps() { FLEXMBS_PETSC(EPSCreate(PETSC_COMM_WORLD, &eps)); }
  OwnedEps(const OwnedEps&) = delete;
  OwnedEps& operator=(const OwnedEps&) = delete;
  ~OwnedEps() { EPSDestroy(&eps); }
};

// Above this many flops of the shift-invert's factorisation (MUMPS RINFOG(3)) the automatic
// missed-mode check is the block Krylov check: the Sturm count's own factorisation costs about
// as much again, the check about 60 solved columns in blocks of 8 and 20 M products.
constexpr double kBlockCheckFromFlops = 1e10;

// The missed-mode check this backend makes: the block Krylov check (eigensolvers/block_krylov_check.h)
// where the factorisation that a Sturm count would add costs more than kBlockCheckFromFlops
// (`flops`: the shift-invert's, MUMPS's RINFOG(3) or the substructured factor's) or where asked,
// else the Sturm count. Not with `fixed_dofs` (their rows of M are zero, so diag(M) cannot
// scale the start block).
MissedModeCheck ChooseCheck(const EigenOptions& options, double flops, bool fixed_dofs) {
  if (fixed_dofs) return MissedModeCheck::kSturmCount;
  if (options.check_missed_modes == MissedModeCheck::kBlockKrylov) return MissedModeCheck::kBlockKrylov;
  if (options.check_missed_modes != MissedModeCheck::kAuto) return MissedModeCheck::kSturmCount;
  return flops > kBlockCheckFromFlops ? MissedModeCheck::kBlockKrylov : MissedModeCheck::kSturmCount;
}

// The flops of the shift-invert's factorisation: the substructured factor's, else MUMPS's.
double FactorizationFlops(EPS eps, const SubstructuredFactor* substructured) {
  if (substructured) return substructured->flops();
  PetscReal flops = 0.0;
  FLEXMBS_PETSC(MatMumpsGetRinfog(ShiftInvertFactor(eps), 3, &flops));
  return flops;
}

// The shift-invert's factorisation as a block space: `substructured`, else the MUMPS factor of
// `eps` (after EPSSetUp). Valid until the Sturm count refactorises that factor.
PetscBlockSpace ShiftInvertSpace(EPS eps, const SubstructuredFactor* substructured, Mat M, double sigma) {
  return substructured ? PetscBlockSpace(*substructured, M, sigma) : PetscBlockSpace(ShiftInvertFactor(eps), M, sigma);
}

// The number of eigenvalues below `cut` that the block Krylov check establishes for the pairs
// `x` (all converged, M-orthonormal) with the shift-invert factorisation (`substructured`, else
// that of `eps`): those found below the cut plus those it found missing; -1 if it could not
// decide (the caller counts).
PetscInt BlockCheckedCount(EPS eps, const SubstructuredFactor* substructured, Mat M, const std::vector<Vec>& x,
                           double cut, const EigenOptions& options, int attempt, EigenSolution* solution) {
  auto phase = std::chrono::steady_clock::now();
  const PetscBlockSpace space = ShiftInvertSpace(eps, substructured, M, solution->shift);
  const Eigen::MatrixXd found = LocalRows(x, space.local_rows());
  BlockCheckOptions block;
  block.tolerance = options.tolerance;
  block.seed = kBlockCheckSeed + static_cast<std::uint64_t>(attempt);
  const BlockCheckResult result = CheckForMissedModes(space, found, cut, block);
  solution->operator_applications += static_cast<int>(result.columns);
  ++solution->krylov_runs;
  solution->krylov_seconds += SecondsSince(&phase);
  const auto below = static_cast<PetscInt>((solution->eigenvalues.array() < cut).count());
  switch (result.verdict) {
    case BlockCheckVerdict::kNoneMissed:
      return below;
    case BlockCheckVerdict::kMissed:
      return below + static_cast<PetscInt>(result.missed_values.size());
    case BlockCheckVerdict::kUndecided:
      break;
  }
  return -1;
}

// The residuals of the `wanted` lowest pairs into *solution (MeasurePairs); where one misses its
// bound, one step of subspace iteration with Rayleigh-Ritz on every converged pair x with the
// shift-invert's factorisation (slepc_refinement.h), and the residuals again. Before the Sturm
// count, which refactorises the MUMPS factor.
void RefineAboveTheBound(EPS eps, const AttemptContext& c, PetscInt wanted, OwnedVectors* x, EigenSolution* solution) {
  const auto measure = [&] {
    const std::vector<Vec> lowest(x->v.begin(), x->v.begin() + wanted);
    MeasurePairs(c.K, c.M, lowest, solution);
  };
  measure();
  const PairResiduals residuals{solution->relative_residuals, solution->residual_floors};
  if (residuals.Accepted(c.options.residual_tolerance)) return;
  RefineBySubspaceIteration(ShiftInvertSpace(eps, c.substructured, c.M, solution->shift), &x->v,
                            &solution->eigenvalues);
  solution->operator_applications += static_cast<int>(x->v.size());
  ++solution->refinement_steps;
  measure();
}

// Solves with the shift-invert factorisation so far (KSPPREONLY: one per right-hand side),
// eigenvector purifications included.
int OperatorApplications(EPS eps) {
  ST st;
  KSP ksp;
  FLEXMBS_PETSC(EPSGetST(eps, &st));
  FLEXMBS_PETSC(STGetKSP(st, &ksp));
  PetscInt solves = 0;
  FLEXMBS_PETSC(KSPGetTotalIterations(ksp, &solves));
  return static_cast<int>(solves);
}

// The missed-mode check of one attempt: the cut after the wanted pairs (the band's end, counted
// before the run, when the whole band is wanted) and the number of eigenvalues below it, by the
// block Krylov check or a Sturm count.
struct CutCount {
  double cut = 0.0;
  PetscInt count = -1;
};
CutCount CountBelowCut(EPS eps, const SubstructuredFactor* substructured, ShiftedMatrix* shifted, Mat K, Mat M,
                       const std::vector<Vec>& x, const RitzLowerBounds& ritz, const BandWanted& band, double top,
                       const EigenOptions& options, bool fixed_dofs, int attempt, EigenSolution* solution) {
  if (band.band_count >= 0) {
    solution->missed_mode_check = MissedModeCheck::kSturmCount;
    solution->sturm_count = static_cast<int>(band.band_count);
    solution->sturm_cut = top;
    return {top, band.band_count};
  }
  CutCount result;
  result.cut = SturmCutAfter(ValuesForTheCut(solution->eigenvalues, ritz.lambda), band.wanted, solution->shift);
  FLEXMBS_CHECK(result.cut > solution->eigenvalues(band.wanted - 1), "Sturm cut below the last wanted mode");
  solution->missed_mode_check = ChooseCheck(options, FactorizationFlops(eps, substructured), fixed_dofs);
  if (solution->missed_mode_check == MissedModeCheck::kBlockKrylov) {
    result.count = BlockCheckedCount(eps, substructured, M, x, result.cut, options, attempt, solution);
  }
  if (result.count < 0) {
    auto phase = std::chrono::steady_clock::now();
    solution->missed_mode_check = MissedModeCheck::kSturmCount;
    result.count = shifted ? EigenvaluesBelow(eps, shifted, result.cut) : eigensolvers::EigenvaluesBelow(K, M, result.cut);
    ++solution->factorizations;
    solution->sturm_seconds += SecondsSince(&phase);
    solution->sturm_count = static_cast<int>(result.count);
    solution->sturm_cut = result.cut;
  }
  return result;
}

}  // namespace

// Seconds since *since, which moves to now.
double SecondsSince(std::chrono::steady_clock::time_point* since) {
  const auto now = std::chrono::steady_clock::now();
  const double seconds = std::chrono::duration<double>(now - *since).count();
  *since = now;
  return seconds;
}

// One attempt: Krylov-Schur for *nev pairs (MUMPS factorises K - sigma M unless substructured),
// the pairs into *x and *solution, their residuals (refined once where one misses its bound), and
// the missed-mode check below the cut. Throws InputError when
// SLEPc converges too few pairs or a second attempt still misses some.
AttemptEnd RunAttempt(const AttemptContext& c, int attempt, PetscInt* nev, OwnedVectors* x, OwnedMat* held_factor,
                      EigenSolution* solution) {
  x->Clear();
  auto phase = std::chrono::steady_clock::now();
  std::optional<ShiftedMatrix> shifted;
  if (!c.keep && !c.substructured) shifted.emplace(c.K, c.M, solution->shift);
  // At sigma = 0 the ST factorises K itself: as positive definite (MUMPS SYM = 1, no pivoting).
  if (c.keep) FLEXMBS_PETSC(MatSetOption(c.K, MAT_SPD, PETSC_TRUE));
  RitzLowerBounds ritz;
  OwnedEps eps;
  Configure(eps.eps, c.K, c.M, shifted ? shifted->get() : nullptr, solution->shift, c.options, *nev, c.fixed_dofs,
            c.substructured);
  FLEXMBS_PETSC(EPSGetST(eps.eps, &ritz.st));
  FLEXMBS_PETSC(EPSSetTrackAll(eps.eps, PETSC_TRUE));  // error estimates of every Ritz value
  FLEXMBS_PETSC(EPSMonitorSet(eps.eps, RecordRitzLowerBounds, &ritz, nullptr));
  FLEXMBS_PETSC(EPSSetUp(eps.eps));  // K - sigma M factorised
  solution->factorization_seconds += SecondsSince(&phase);
  if (c.keep && !c.substructured && !FactoredPositiveDefinite(ShiftInvertFactor(eps.eps))) {
    ++solution->factorizations;
    return AttemptEnd::kNotPositiveDefinite;
  }
  FLEXMBS_PETSC(EPSSolve(eps.eps));
  PetscInt converged = 0, iterations = 0;
  FLEXMBS_PETSC(EPSGetConverged(eps.eps, &converged));
  FLEXMBS_PETSC(EPSGetIterationNumber(eps.eps, &iterations));
  ++solution->krylov_runs;
  solution->restarts += static_cast<int>(iterations);
  if (!c.substructured) ++solution->factorizations;
  if (converged < *nev) {
    throw InputError(fmt::format("eigenproblem: SLEPc converged {} of {} modes in {} iterations", converged, *nev,
                                 iterations));
  }
  ExtractPairs(eps.eps, c.K, c.M, 0, solution, &x->v);
  solution->operator_applications += OperatorApplications(eps.eps);
  if (c.keep && !(solution->eigenvalues(0) > c.zero_eigenvalue)) {
    solution->krylov_seconds += SecondsSince(&phase);
    return AttemptEnd::kNotPositiveDefinite;  // singular to round-off: not held
  }
  RefineAboveTheBound(eps.eps, c, c.band.wanted, x, solution);  // wanted <= *nev <= converged
  solution->krylov_seconds += SecondsSince(&phase);
  // Every eigenvalue below the cut after the wanted ones must have been found.
  const CutCount checked = CountBelowCut(eps.eps, c.substructured, shifted ? &*shifted : nullptr, c.K, c.M, x->v,
                                         ritz, c.band, c.top, c.options, c.fixed_dofs, attempt, solution);
  const auto found = static_cast<PetscInt>((solution->eigenvalues.array() < checked.cut).count());
  solution->checked_cut = checked.cut;
  if (checked.count == found) {
    solution->eigenvalues.conservativeResize(c.band.wanted);
    x->Truncate(static_cast<std::size_t>(c.band.wanted));
    if (c.keep && !c.substructured) {
      // The factor of K outlives the EPS, which resets its solver at the end of this scope.
      held_factor->A = ShiftInvertFactor(eps.eps);
      FLEXMBS_PETSC(PetscObjectReference(reinterpret_cast<PetscObject>(held_factor->A)));
    }
    return AttemptEnd::kFound;
  }
  if (checked.count < found || attempt > 0) {
    throw InputError(fmt::format("eigenproblem: SLEPc found {} modes below {:.6g} Hz but the {} is {}", found,
                                 FrequenciesHz(Eigen::VectorXd::Constant(1, checked.cut))(0),
                                 solution->missed_mode_check == MissedModeCheck::kSturmCount
                                     ? "Sturm count"
                                     : "block Krylov check's count",
                                 checked.count));
  }
  // SLEPc missed modes: once more, every mode below the cut converged and GuardPairs more.
  *nev = checked.count + static_cast<PetscInt>(GuardPairs(checked.count));
  return AttemptEnd::kMissed;
}


}  // namespace flexmbs::eigensolvers
