#pragma once
// The eigensolver's contract as the eigensolver tests check it (tests/eigensolvers/): the bounds
// every returned pair meets, and when two eigenvalues of the exactly symmetric test meshes are
// one repeated eigenvalue.

#include <Eigen/Core>
#include <cmath>

#include "tests/support/test_problems.h"

namespace flexmbs::testing {

/// The contract (EigenOptions defaults): every pair's relative residual.
inline constexpr double kResidualBound = 1e-8;
/// The contract: max |Phi^T M Phi - I|.
inline constexpr double kOrthonormalityBound = 1e-10;
/// Eigenvalues closer than this (relative) are one cluster (a repeated eigenvalue): the
/// structured meshes of test_problems.h are exactly symmetric, so repeated eigenvalues split
/// only by round-off, ~1e-12 relative.
inline constexpr double kClusterTolerance = 1e-7;

/// Whether the dense eigenvalues a and b (b > 0) are one repeated eigenvalue (kClusterTolerance).
inline bool SameCluster(const DenseEigen& dense, Eigen::Index a, Eigen::Index b) {
  return std::abs(dense.values(a) - dense.values(b)) <= kClusterTolerance * dense.values(b);
}

}  // namespace flexmbs::testing
