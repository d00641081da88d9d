#include "reduction/slepc_solver.h"

#include <algorithm>
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

// Copies a distributed vector into a full-length Eigen vector on every rank.
Eigen::VectorXd GatherToAll(Vec x) {
  VecScatter scatter;
  Vec all;
  FLEXMBS_PETSC(VecScatterCreateToAll(x, &scatter, &all));
  FLEXMBS_PETSC(VecScatterBegin(scatter, x, all, INSERT_VALUES, SCATTER_FORWARD));
  FLEXMBS_PETSC(VecScatterEnd(scatter, x, all, INSERT_VALUES, SCATTER_FORWARD));
  PetscInt n = 0;
  FLEXMBS_PETSC(VecGetSize(all, &n));
  const PetscScalar* values = nullptr;
  FLEXMBS_PETSC(VecGetArrayRead(all, &values));
  Eigen::VectorXd out = Eigen::Map<const Eigen::VectorXd>(values, n);
  FLEXMBS_PETSC(VecRestoreArrayRead(all, &values));
  FLEXMBS_PETSC(VecScatterDestroy(&scatter));
  FLEXMBS_PETSC(VecDestroy(&all));
  return out;
}

// ||K x - lambda M x|| / max(||K x||, |lambda| ||M x||), and x^T M x.
std::pair<double, double> ResidualAndMassNorm(Mat K, Mat M, Vec x, double lambda) {
  Vec kx, mx;
  FLEXMBS_PETSC(MatCreateVecs(K, nullptr, &kx));
  FLEXMBS_PETSC(MatCreateVecs(K, nullptr, &mx));
  FLEXMBS_PETSC(MatMult(K, x, kx));
  FLEXMBS_PETSC(MatMult(M, x, mx));
  PetscReal norm_kx = 0.0, norm_mx = 0.0, residual = 0.0;
  PetscScalar xmx = 0.0;
  FLEXMBS_PETSC(VecNorm(kx, NORM_2, &norm_kx));
  FLEXMBS_PETSC(VecNorm(mx, NORM_2, &norm_mx));
  FLEXMBS_PETSC(VecDot(x, mx, &xmx));
  FLEXMBS_PETSC(VecAXPY(kx, -lambda, mx));
  FLEXMBS_PETSC(VecNorm(kx, NORM_2, &residual));
  FLEXMBS_PETSC(VecDestroy(&kx));
  FLEXMBS_PETSC(VecDestroy(&mx));
  const double scale = std::max({norm_kx, std::abs(lambda) * norm_mx, 1e-300});
  return {residual / scale, xmx};
}

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

DistributedEigenResult SolveDistributedEigenproblem(Mat K, Mat M, const std::vector<int>& fixed_dofs,
                                                    const DistributedEigenOptions& options) {
  // Each rank zeroes the fixed rows it owns; columns are zeroed collectively.
  PetscInt row_begin = 0, row_end = 0;
  FLEXMBS_PETSC(MatGetOwnershipRange(K, &row_begin, &row_end));
  std::vector<PetscInt> owned_fixed;
  for (int dof : fixed_dofs) {
    if (dof >= row_begin && dof < row_end) owned_fixed.push_back(dof);
  }
  const auto num_fixed = static_cast<PetscInt>(owned_fixed.size());
  FLEXMBS_PETSC(MatZeroRowsColumns(K, num_fixed, owned_fixed.data(), 1.0, nullptr, nullptr));
  FLEXMBS_PETSC(MatZeroRowsColumns(M, num_fixed, owned_fixed.data(), 0.0, nullptr, nullptr));
  for (Mat A : {K, M}) {
    FLEXMBS_PETSC(MatSetOption(A, MAT_SYMMETRIC, PETSC_TRUE));
    FLEXMBS_PETSC(MatSetOption(A, MAT_SPD, PETSC_FALSE));
  }

  EPS eps;
  ST st;
  KSP ksp;
  PC pc;
  FLEXMBS_PETSC(EPSCreate(PETSC_COMM_WORLD, &eps));
  FLEXMBS_PETSC(EPSSetOperators(eps, K, M));
  FLEXMBS_PETSC(EPSSetProblemType(eps, EPS_GHEP));
  FLEXMBS_PETSC(EPSSetType(eps, EPSKRYLOVSCHUR));
  FLEXMBS_PETSC(EPSSetDimensions(eps, options.num_modes, PETSC_DEFAULT, PETSC_DEFAULT));
  FLEXMBS_PETSC(EPSSetTolerances(eps, options.tolerance, options.max_iterations));
  FLEXMBS_PETSC(EPSSetTarget(eps, options.shift));
  FLEXMBS_PETSC(EPSSetWhichEigenpairs(eps, EPS_TARGET_MAGNITUDE));
  FLEXMBS_PETSC(EPSGetST(eps, &st));
  FLEXMBS_PETSC(STSetType(st, STSINVERT));
  FLEXMBS_PETSC(STGetKSP(st, &ksp));
  FLEXMBS_PETSC(KSPSetType(ksp, KSPPREONLY));
  FLEXMBS_PETSC(KSPGetPC(ksp, &pc));
  FLEXMBS_PETSC(PCSetType(pc, PCCHOLESKY));
  FLEXMBS_PETSC(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  FLEXMBS_PETSC(EPSSolve(eps));

  PetscInt converged = 0, iterations = 0;
  FLEXMBS_PETSC(EPSGetConverged(eps, &converged));
  FLEXMBS_PETSC(EPSGetIterationNumber(eps, &iterations));
  if (converged < options.num_modes) {
    EPSDestroy(&eps);
    throw InputError(fmt::format("SLEPc converged {} of {} modes in {} iterations (raise max_iterations or lower the mode count)",
                                 converged, options.num_modes, iterations));
  }

  Vec x;
  FLEXMBS_PETSC(MatCreateVecs(K, &x, nullptr));
  DistributedEigenResult result;
  result.iterations = static_cast<int>(iterations);
  std::vector<double> lambdas(static_cast<std::size_t>(options.num_modes));
  std::vector<Eigen::VectorXd> vectors(lambdas.size());
  std::vector<double> residuals(lambdas.size());
  for (PetscInt i = 0; i < options.num_modes; ++i) {
    PetscScalar lambda = 0.0;
    FLEXMBS_PETSC(EPSGetEigenpair(eps, i, &lambda, nullptr, x, nullptr));
    const auto [residual, xmx] = ResidualAndMassNorm(K, M, x, lambda);
    FLEXMBS_PETSC(VecScale(x, 1.0 / std::sqrt(xmx)));
    const auto k = static_cast<std::size_t>(i);
    lambdas[k] = lambda;
    residuals[k] = residual;
    vectors[k] = GatherToAll(x);
  }
  FLEXMBS_PETSC(VecDestroy(&x));
  FLEXMBS_PETSC(EPSDestroy(&eps));

  std::vector<std::size_t> order(lambdas.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return lambdas[a] < lambdas[b]; });
  const auto n = static_cast<Eigen::Index>(lambdas.size());
  result.eigenvalues.resize(n);
  result.relative_residuals.resize(n);
  result.modes.resize(vectors.empty() ? 0 : vectors[0].size(), n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const std::size_t k = order[static_cast<std::size_t>(j)];
    result.eigenvalues(j) = lambdas[k];
    result.relative_residuals(j) = residuals[k];
    result.modes.col(j) = vectors[k];
  }
  return result;
}

}  // namespace flexmbs::reduction
