#pragma once
// What the Spectra eigensolver tests share (tests/eigensolvers/eigensolver_test.cc,
// eigensolver_input_errors_test.cc): the solver, the small FE problems and the checks of the
// eigensolver's contract against K and M and against dense solves.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>

#include "eigensolvers/eigensolver.h"
#include "fem/material.h"
#include "fem/mesh.h"
#include "reduction/dof_constraints.h"
#include "tests/support/test_problems.h"

namespace flexmbs::eigensolvers::spectra_test {

using SparseMatrix = Eigen::SparseMatrix<double>;

/// Subspace agreement (sine of the largest principal angle) of a cluster of eigenvalues with the
/// dense one. Davis-Kahan: sin theta <= residual / relative gap to the rest of the spectrum;
/// residuals <= 1e-8 and the gaps here are >= 1e-2.
inline constexpr double kSubspaceAgreement = 1e-6;

/// The serial backend, made once.
const std::unique_ptr<Eigensolver>& Spectra();

/// A meshed body with its consistent K [N/m] and M [kg].
struct Problem {
  fem::Mesh mesh;
  SparseMatrix K;
  SparseMatrix M;
};

/// `mesh` with its assembled consistent K and M.
Problem Assemble(fem::Mesh mesh);

/// A shift for the dense reference of a free-free body: -1e-6 of the mesh's stiffness-to-mass
/// scale, far below the first elastic eigenvalue and far above round-off.
double FreeFreeShift(const Problem& p);

/// Every returned pair meets the contract, computed in the test from K and M with Eigen's own
/// sparse products (not the solver's ComputeResiduals, MOrthonormalityError). `strict`: the
/// residual bound itself, not relaxed to the round-off floor (the floors of these compact meshes
/// are far below it, which is checked too).
void ExpectContract(const SparseMatrix& K, const SparseMatrix& M, const EigenSolution& s, bool strict = true);

/// The returned eigenvalues match the dense ones (relative to max(|lambda|, lambda_ref)), and
/// each complete cluster of (numerically) repeated eigenvalues spans the dense cluster's subspace.
void ExpectMatchesDense(const SparseMatrix& M, const EigenSolution& s, const flexmbs::testing::DenseEigen& dense,
                        double lambda_ref);

/// Prints a solution's figures as "[ numbers  ] ...".
void Report(const char* what, const EigenSolution& s);

/// A steel cantilever 0.6 m x 0.05 m x 0.04 m, 12 x 3 x 3 hex8 of two materials (split at
/// x = 0.3 m), clamped at x = 0: the full problem, the clamp's DOF map and the restricted K, M.
/// The section is not square, so bending in y and z do not give repeated eigenvalues.
struct Cantilever {
  Problem full;
  reduction::FreeDofMap map;
  SparseMatrix K;
  SparseMatrix M;
};
Cantilever MakeCantilever(const fem::IsotropicMaterial& left, const fem::IsotropicMaterial& right);

}  // namespace flexmbs::eigensolvers::spectra_test
