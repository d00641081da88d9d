#pragma once

// The Krylov runs of the serial eigensolver (eigensolvers/serial/spectra_eigensolver.h), each for the
// eigenvalues of K phi = lambda M phi nearest the shift outside the span of the pairs found:
// Spectra's implicitly restarted Lanczos, or block Lanczos (eigensolvers/serial/block_lanczos_run.h).
// lanczos_runs.cc is the only translation unit that includes Spectra (~25 s to compile).

#include <Eigen/Core>

#include "eigensolvers/eigensolver.h"

namespace flexmbs::eigensolvers {

class MassOperator;

/// The converged Ritz vectors of one run.
struct KrylovRun {
  Eigen::MatrixXd vectors;  ///< M-orthonormal, M-orthogonal to the pairs found
  int restarts = 0;         ///< Spectra's implicit restarts (0 for a block run)
};

/// One implicitly restarted Lanczos run (Spectra, shift-invert with `factor`, M inner product)
/// for the `nev` eigenvalues nearest sigma (largest 1 / (lambda - sigma)) outside span X (X
/// M-orthonormal); start vector from `seed`. Adds its solves to `*solves`. Empty vectors if
/// nothing converged within options.max_iterations restarts.
KrylovRun RunLanczos(const ShiftedFactorization& factor, const MassOperator& M,
                     const Eigen::MatrixXd& X, Eigen::Index nev, const EigenOptions& options,
                     unsigned seed, int* solves);

/// The Krylov dimension at which a block run for `nev` pairs stops, with `available` directions
/// outside the pairs found and blocks of `block` columns.
Eigen::Index BlockRunDimension(Eigen::Index available, Eigen::Index nev, Eigen::Index block);

/// The same with block Lanczos, blocks of `block` columns (RunBlockLanczos), stopped at
/// BlockRunDimension; `lowest_found` is the lowest eigenvalue among X (NaN if X is empty), which
/// sets ||T||. Empty vectors if nothing converged by then.
KrylovRun RunBlock(const ShiftedFactorization& factor, const MassOperator& M,
                   const Eigen::MatrixXd& X, double lowest_found, Eigen::Index nev,
                   const EigenOptions& options, Eigen::Index block, unsigned seed, int* solves);

}  // namespace flexmbs::eigensolvers
