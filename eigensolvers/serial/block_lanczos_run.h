#pragma once

// The main Krylov run of the serial eigensolver on large bodies: block Lanczos with the
// shift-invert operator (DeflatedBlockLanczos, eigensolvers/block_krylov_check.h), without
// restarts, until the wanted Ritz pairs have converged. Each step solves a block of columns at
// once: CHOLMOD's supernodal solve costs 193 ms per column with 8 columns against 825 ms for one
// (the 512 k DOF bench bar, one core), so the block run needs more columns than Spectra's
// restarted single-vector Lanczos and still takes less time where the solves dominate.

#include <Eigen/Core>
#include <cstdint>

#include "eigensolvers/block_krylov_check.h"

namespace flexmbs::eigensolvers {

struct BlockRunOptions {
  /// Columns of each block.
  Eigen::Index block_size = 8;
  /// A Ritz pair has converged once ||T y - mu y||_M <= tolerance mu (Spectra's criterion) or
  /// <= 10 eps ||T|| (the round-off of applying T, which deep in the spectrum is larger).
  double tolerance = 1e-10;
  /// ||T||_M = 1 / (lambda_1 - sigma), if known from the pairs found (a deflated run's own Ritz
  /// values are smaller); 0: the run's largest Ritz value.
  double operator_norm = 0.0;
  /// The run stops at this Krylov dimension (the memory is two n x dimension blocks, the
  /// Lanczos vectors and their M products) with the pairs converged by then.
  Eigen::Index max_dimension = 0;
  std::uint64_t seed = 0;
};

struct BlockRunResult {
  /// The converged Ritz vectors among the `nev` of lowest lambda, M-orthonormal, M-orthogonal
  /// to `found`, in the order of their Ritz values (lowest lambda first). Fewer than `nev` if
  /// the run reached max_dimension first; empty if none converged.
  Eigen::MatrixXd vectors;
  int steps = 0;             ///< block solves
  Eigen::Index columns = 0;  ///< right-hand sides solved
};

/// The `nev` eigenpairs of lowest lambda of K phi = lambda M phi outside span(found), by block
/// Lanczos on the deflated shift-invert operator from a block of Gaussian random vectors
/// (`options.seed`). Preconditions: nev >= 1, the space's K - sigma M positive definite,
/// `found` M-orthonormal, options.block_size >= 1, options.max_dimension >= nev.
BlockRunResult RunBlockLanczos(const BlockKrylovSpace& space, const Eigen::MatrixXd& found,
                               Eigen::Index nev, const BlockRunOptions& options);

}  // namespace flexmbs::eigensolvers
