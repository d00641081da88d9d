#pragma once
// The SLEPc backend's refinement of its pairs: one step of subspace iteration with Rayleigh-Ritz,
// made when a wanted pair misses its residual bound (EigenOptions::residual_tolerance), as the
// serial backend does. Why it is needed: Krylov-Schur's convergence test bounds the residual of
// the shift-inverted operator in the M norm, ||T x - theta x||_M <= tol theta; the residual of
// the pencil, ||K x - lambda M x||, weighs what the basis's round-off left in each mode phi_j of x
// with lambda_j, and SLEPc's Ritz vectors keep that round-off whatever the tolerance (the case-01
// beam at sigma = 0: 40 floors for its 4th bending pair; docs/building.md, "SLEPc pairs above
// their residual bound"). Internal: names PETSc types, so only .cc files include it.

#include <petscvec.h>

#include <Eigen/Core>
#include <vector>

#include "eigensolvers/block_krylov_check.h"

namespace flexmbs::eigensolvers {

/// One step of subspace iteration with Rayleigh-Ritz on the pairs (eigenvalues(j), x[j]): Y = T X
/// with T = (K - sigma M)^-1 M by `space` (all columns in one solve), then the Ritz pairs of
/// K, M on span Y, whose small matrices need no product with K: (K - sigma M) Y = M X gives
/// Y^T K Y = Y^T M X + sigma Y^T M Y. The new pairs replace the old, ascending and M-orthonormal.
/// The step scales x's components along phi_j, relative to the pair's own, by
/// (lambda - sigma) / (lambda_j - sigma), and Rayleigh-Ritz takes out what that raised of the
/// lower pairs. x: distributed like `space`'s rows, M-orthonormal. Collective.
void RefineBySubspaceIteration(const BlockKrylovSpace& space, std::vector<Vec>* x, Eigen::VectorXd* eigenvalues);

}  // namespace flexmbs::eigensolvers
