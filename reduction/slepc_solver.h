#pragma once

#include <Eigen/Core>
#include <vector>

// PETSc's matrix type (`Mat` is a pointer to it), declared here so that no PETSc header
// appears in this public header.
struct _p_Mat;

namespace flexmbs::reduction {

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

/// Options of the distributed generalized eigen-solve.
struct DistributedEigenOptions {
  int num_modes = 10;
  double shift = 0.0;  ///< sigma [rad^2/s^2]: modes nearest it are found (negative for free bodies)
  double tolerance = 1e-10;  ///< SLEPc's relative convergence tolerance
  int max_iterations = 1000;
};

/// Lowest eigenpairs of a distributed problem, gathered on every rank.
struct DistributedEigenResult {
  Eigen::VectorXd eigenvalues;  ///< lambda = omega^2 [rad^2/s^2], ascending
  Eigen::MatrixXd modes;        ///< full-length, M-orthonormal columns (zero on fixed DOF)
  Eigen::VectorXd relative_residuals;  ///< ||K phi - lambda M phi|| / max(||K phi||, ||lambda M phi||)
  int iterations = 0;
};

/// Collective on PETSC_COMM_WORLD: the `options.num_modes` eigenpairs of K phi = lambda M phi
/// nearest `options.shift`, by SLEPc Krylov-Schur with shift-and-invert, the shifted matrix
/// factorised by MUMPS Cholesky. `fixed_dofs` (global DOF numbers, the same list on every rank)
/// are removed by zeroing their rows and columns (K diagonal 1, M diagonal 0), which moves
/// their eigenvalues to infinity. K and M are modified in place. Throws InputError if fewer
/// pairs converge than asked, InternalError for a PETSc/SLEPc failure.
DistributedEigenResult SolveDistributedEigenproblem(_p_Mat* K, _p_Mat* M,
                                                    const std::vector<int>& fixed_dofs,
                                                    const DistributedEigenOptions& options);

}  // namespace flexmbs::reduction
