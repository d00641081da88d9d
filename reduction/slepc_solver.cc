#include "reduction/slepc_solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <numeric>
#include <slepceps.h>

#include "core/error.h"

namespace flexmbs::reduction {
namespace {

void Check(PetscErrorCode code, const char* call) {
  if (code != 0) {
    throw InternalError(fmt::format("PETSc/SLEPc call {} failed with error {}", call, static_cast<int>(code)));
  }
}
#define FLEXMBS_PETSC(call) Check((call), #call)

// Copies a distributed vector into a full-length Eigen vector on every rank, or on rank 0 only
// (the other ranks get an empty vector).
Eigen::VectorXd Gather(Vec x, ModesOn modes_on) {
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

// |A|: a copy of the AIJ matrix A with the absolute values of its entries.
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

// The norm of the distributed vector x, squared.
double SquaredNorm(Vec x) {
  PetscReal norm = 0.0;
  FLEXMBS_PETSC(VecNorm(x, NORM_2, &norm));
  return norm * norm;
}

// Fills residuals, round-off floors and the M-orthonormality error of the pairs (lambda, x),
// x distributed: the products with K, M, |K| and |M| run where the rows are.
void MeasurePairs(Mat K, Mat M, const std::vector<Vec>& x, EigenSolution* solution) {
  const Eigen::VectorXd& lambda = solution->eigenvalues;
  const auto n = static_cast<Eigen::Index>(x.size());
  Mat abs_K = AbsoluteCopy(K), abs_M = AbsoluteCopy(M);
  Vec kx, mx, abs_x, abs_kx, abs_mx;
  FLEXMBS_PETSC(MatCreateVecs(K, &abs_x, &kx));
  for (Vec* v : {&mx, &abs_kx, &abs_mx}) FLEXMBS_PETSC(VecDuplicate(kx, v));
  Eigen::MatrixXd sums(4, n), gram(n, n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const Vec xj = x[static_cast<std::size_t>(j)];
    FLEXMBS_PETSC(MatMult(K, xj, kx));
    FLEXMBS_PETSC(MatMult(M, xj, mx));
    FLEXMBS_PETSC(VecMDot(mx, static_cast<PetscInt>(n), x.data(), gram.col(j).data()));
    FLEXMBS_PETSC(VecCopy(xj, abs_x));
    FLEXMBS_PETSC(VecAbs(abs_x));
    FLEXMBS_PETSC(MatMult(abs_K, abs_x, abs_kx));
    FLEXMBS_PETSC(MatMult(abs_M, abs_x, abs_mx));
    sums(0, j) = SquaredNorm(kx);
    sums(1, j) = SquaredNorm(mx);
    FLEXMBS_PETSC(VecAXPY(kx, -lambda(j), mx));
    sums(2, j) = SquaredNorm(kx);
    FLEXMBS_PETSC(VecAXPY(abs_kx, std::abs(lambda(j)), abs_mx));
    sums(3, j) = SquaredNorm(abs_kx);
  }
  for (Vec* v : {&kx, &mx, &abs_x, &abs_kx, &abs_mx}) FLEXMBS_PETSC(VecDestroy(v));
  FLEXMBS_PETSC(MatDestroy(&abs_K));
  FLEXMBS_PETSC(MatDestroy(&abs_M));
  PetscScalar trace_k = 0.0, trace_m = 0.0;
  FLEXMBS_PETSC(MatGetTrace(K, &trace_k));
  FLEXMBS_PETSC(MatGetTrace(M, &trace_m));
  const PairResiduals residuals =
      ResidualsFromSums(sums, lambda, solution->shift, kZeroEigenvalue * trace_k / trace_m);
  solution->relative_residuals = residuals.relative;
  solution->residual_floors = residuals.floor;
  solution->orthonormality_error = (gram - Eigen::MatrixXd::Identity(n, n)).cwiseAbs().maxCoeff();
}

// Configures `eps` for K, M: Krylov-Schur, shift-and-invert at sigma, MUMPS Cholesky, `nev`
// pairs (not a band). Purification (one more solve per pair, removing components in M's null
// space) only where fixed DOF make M singular: with M positive definite the shift-inverted
// operator has no such components to remove.
void Configure(EPS eps, Mat K, Mat M, double sigma, const EigenOptions& options, PetscInt nev, bool singular_mass) {
  ST st;
  KSP ksp;
  PC pc;
  FLEXMBS_PETSC(EPSSetOperators(eps, K, M));
  FLEXMBS_PETSC(EPSSetProblemType(eps, EPS_GHEP));
  FLEXMBS_PETSC(EPSSetType(eps, EPSKRYLOVSCHUR));
  FLEXMBS_PETSC(EPSSetTolerances(eps, options.tolerance, options.max_iterations));
  FLEXMBS_PETSC(EPSSetPurify(eps, singular_mass ? PETSC_TRUE : PETSC_FALSE));
  if (options.max_frequency_hz > 0.0) {
    // Spectrum slicing: every eigenvalue in [sigma, lambda_max], counted by the inertia of the
    // MUMPS factorisations (which needs ICNTL(13) = 1 in parallel; the ST prefixes its factor).
    FLEXMBS_PETSC(PetscOptionsSetValue(nullptr, "-st_mat_mumps_icntl_13", "1"));
    FLEXMBS_PETSC(EPSSetInterval(eps, sigma, ShiftFromHz(options.max_frequency_hz)));
    FLEXMBS_PETSC(EPSSetWhichEigenpairs(eps, EPS_ALL));
  } else {
    FLEXMBS_PETSC(EPSSetDimensions(eps, nev, PETSC_DEFAULT, PETSC_DEFAULT));
    FLEXMBS_PETSC(EPSSetTarget(eps, sigma));
    FLEXMBS_PETSC(EPSSetWhichEigenpairs(eps, EPS_TARGET_MAGNITUDE));
  }
  FLEXMBS_PETSC(EPSGetST(eps, &st));
  FLEXMBS_PETSC(STSetType(st, STSINVERT));
  FLEXMBS_PETSC(STGetKSP(st, &ksp));
  FLEXMBS_PETSC(KSPSetType(ksp, KSPPREONLY));
  FLEXMBS_PETSC(KSPGetPC(ksp, &pc));
  FLEXMBS_PETSC(PCSetType(pc, PCCHOLESKY));
  FLEXMBS_PETSC(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
}

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

// The converged pairs of `eps`, lowest first, at most `limit` (0 = all), M-normalised: the
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

// Distributed vectors destroyed with their owner (also when an exception passes).
struct OwnedVectors {
  std::vector<Vec> v;
  OwnedVectors() = default;
  OwnedVectors(const OwnedVectors&) = delete;
  OwnedVectors& operator=(const OwnedVectors&) = delete;
  ~OwnedVectors() { Clear(); }
  void Clear() {
    for (Vec& x : v) VecDestroy(&x);
    v.clear();
  }
  // Keeps the first `count` vectors.
  void Truncate(std::size_t count) {
    for (std::size_t j = count; j < v.size(); ++j) VecDestroy(&v[j]);
    v.resize(std::min(count, v.size()));
  }
};

// The number of eigenvalues of K phi = lambda M phi below `cut`: the negative inertia of
// K - cut M (Sylvester; M positive semi-definite, fixed DOF have K = 1, M = 0 and count as
// positive) from a MUMPS LDL^T factorisation. ICNTL(13) = 1 keeps the root node off ScaLAPACK,
// which would not report the inertia on more than one rank.
PetscInt EigenvaluesBelow(Mat K, Mat M, double cut) {
  Mat A;
  FLEXMBS_PETSC(MatDuplicate(K, MAT_COPY_VALUES, &A));
  FLEXMBS_PETSC(MatAXPY(A, -cut, M, DIFFERENT_NONZERO_PATTERN));
  FLEXMBS_PETSC(MatSetOption(A, MAT_SYMMETRIC, PETSC_TRUE));
  KSP ksp;
  PC pc;
  Mat factor;
  FLEXMBS_PETSC(KSPCreate(PETSC_COMM_WORLD, &ksp));
  FLEXMBS_PETSC(KSPSetOperators(ksp, A, A));
  FLEXMBS_PETSC(KSPSetType(ksp, KSPPREONLY));
  FLEXMBS_PETSC(KSPGetPC(ksp, &pc));
  FLEXMBS_PETSC(PCSetType(pc, PCCHOLESKY));
  FLEXMBS_PETSC(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  FLEXMBS_PETSC(PCFactorSetUpMatSolverType(pc));
  FLEXMBS_PETSC(PCFactorGetMatrix(pc, &factor));
  FLEXMBS_PETSC(MatMumpsSetIcntl(factor, 13, 1));
  FLEXMBS_PETSC(KSPSetUp(ksp));
  PetscInt negative = 0;  // zero and positive counts would need null-pivot detection (ICNTL(24))
  FLEXMBS_PETSC(MatGetInertia(factor, &negative, nullptr, nullptr));
  FLEXMBS_PETSC(KSPDestroy(&ksp));
  FLEXMBS_PETSC(MatDestroy(&A));
  return negative;
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

}  // namespace

SlepcSession::SlepcSession() {
  PetscBool initialized = PETSC_FALSE;
  FLEXMBS_PETSC(SlepcInitialized(&initialized));
  if (!initialized) {
    FLEXMBS_PETSC(SlepcInitializeNoArguments());
    owns_ = true;
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
                                           double* gather_seconds) {
  const auto start = std::chrono::steady_clock::now();
  RemoveFixedDofs(K, M, fixed_dofs);
  EigenSolution solution;
  solution.backend = "slepc";
  if (options.shift_hz) {
    solution.shift = ShiftFromHz(*options.shift_hz);
  } else {
    PetscScalar trace_k = 0.0, trace_m = 0.0;
    FLEXMBS_PETSC(MatGetTrace(K, &trace_k));
    FLEXMBS_PETSC(MatGetTrace(M, &trace_m));
    solution.shift = -1e-6 * trace_k / trace_m;
  }
  const bool band = options.max_frequency_hz > 0.0;
  // Lowest modes: a few guard pairs beyond the wanted ones show the gap where the Sturm cut goes.
  PetscInt nev = band ? 0 : options.num_modes + static_cast<PetscInt>(GuardPairs(options.num_modes));
  OwnedVectors x;
  for (int attempt = 0;; ++attempt) {
    x.Clear();
    EPS eps;
    FLEXMBS_PETSC(EPSCreate(PETSC_COMM_WORLD, &eps));
    try {
      Configure(eps, K, M, solution.shift, options, nev, !fixed_dofs.empty());
      FLEXMBS_PETSC(EPSSolve(eps));
      PetscInt converged = 0, iterations = 0;
      FLEXMBS_PETSC(EPSGetConverged(eps, &converged));
      FLEXMBS_PETSC(EPSGetIterationNumber(eps, &iterations));
      solution.restarts += static_cast<int>(iterations);
      ++solution.factorizations;
      if (band && converged == 0) {
        throw InputError(fmt::format("eigenproblem: no mode below {:g} Hz", options.max_frequency_hz));
      }
      if (!band && converged < options.num_modes) {
        throw InputError(fmt::format("eigenproblem: SLEPc converged {} of {} modes in {} iterations",
                                     converged, options.num_modes, iterations));
      }
      ExtractPairs(eps, K, M, band ? options.num_modes : 0, &solution, &x.v);
      FLEXMBS_PETSC(EPSDestroy(&eps));
    } catch (...) {
      EPSDestroy(&eps);
      throw;
    }
    if (band) {
      // Spectrum slicing counts the interval's eigenvalues by the inertia itself.
      solution.checked_cut = ShiftFromHz(options.max_frequency_hz);
      break;
    }
    // Sturm check: every eigenvalue below the cut after the wanted ones must have been found.
    const double cut = SturmCutAfter(solution.eigenvalues, options.num_modes, solution.shift);
    const auto found = static_cast<PetscInt>((solution.eigenvalues.array() < cut).count());
    const PetscInt count = EigenvaluesBelow(K, M, cut);
    ++solution.factorizations;
    solution.sturm_count = static_cast<int>(count);
    solution.sturm_cut = cut;
    solution.checked_cut = cut;
    if (count == found) {
      solution.eigenvalues.conservativeResize(options.num_modes);
      x.Truncate(static_cast<std::size_t>(options.num_modes));
      break;
    }
    if (count < found || attempt > 0) {
      throw InputError(fmt::format("eigenproblem: SLEPc found {} modes below {:.6g} Hz but the Sturm count is {}",
                                   found, FrequenciesHz(Eigen::VectorXd::Constant(1, cut))(0), count));
    }
    nev = count + static_cast<PetscInt>(GuardPairs(count));  // SLEPc missed modes: once more, wider
  }
  MeasurePairs(K, M, x.v, &solution);
  const auto gather_start = std::chrono::steady_clock::now();
  for (std::size_t j = 0; j < x.v.size(); ++j) {
    Eigen::VectorXd mode = Gather(x.v[j], modes_on);
    if (j == 0) solution.modes.resize(mode.size(), static_cast<Eigen::Index>(x.v.size()));
    solution.modes.col(static_cast<Eigen::Index>(j)) = mode;
  }
  x.Clear();
  if (gather_seconds) {
    *gather_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - gather_start).count();
  }
  const PairResiduals residuals{solution.relative_residuals, solution.residual_floors};
  Eigen::Index worst = 0;
  if (!residuals.Accepted(options.residual_tolerance, &worst)) {
    throw InputError(fmt::format("eigenproblem: mode {} ({:.6g} Hz) has relative residual {:.3g} above "
                                 "max({:g}, {:g} x its round-off floor {:.3g})",
                                 worst, FrequenciesHz(solution.eigenvalues)(worst),
                                 solution.relative_residuals(worst), options.residual_tolerance,
                                 kResidualFloorFactor, solution.residual_floors(worst)));
  }
  solution.missed_mode_check = MissedModeCheck::kSturmCount;
  solution.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return solution;
}

std::unique_ptr<Eigensolver> MakeSlepcEigensolver() { return std::make_unique<SlepcEigensolver>(); }

}  // namespace flexmbs::reduction
