// Rayleigh-Ritz's sign convention: a Ritz vector that is mostly one input column keeps that
// column's sign, so two runs whose round-off differs (serial products against distributed ones,
// another BLAS) give the same basis, not one with some modes flipped.
#include "reduction/basis_algebra.h"

#include <gtest/gtest.h>

#include <Eigen/SparseCore>
#include <random>

namespace flexmbs::reduction {
namespace {

// K = diag(1..n) [rad^2/s^2], M = I: the eigenvectors are the unit vectors.
struct DiagonalProblem {
  explicit DiagonalProblem(int n) : K(n, n), M(n, n) {
    for (int i = 0; i < n; ++i) {
      K.insert(i, i) = 1.0 + i;
      M.insert(i, i) = 1.0;
    }
  }
  Eigen::SparseMatrix<double> K, M;
};

TEST(RayleighRitz, RitzVectorsKeepTheSignsOfTheColumnsTheyAreMostly) {
  constexpr int kDofs = 12;
  constexpr int kColumns = 5;
  const DiagonalProblem problem(kDofs);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  // Columns: +-e_j, each with a perturbation of 1e-3 in every entry, so that the reduced
  // eigenvectors are not the unit vectors and their sign is LAPACK's choice before the convention.
  Eigen::MatrixXd B = 1e-3 * Eigen::MatrixXd::NullaryExpr(kDofs, kColumns, [&] { return uniform(rng); });
  const double signs[kColumns] = {1.0, -1.0, -1.0, 1.0, -1.0};
  for (int j = 0; j < kColumns; ++j) B(j, j) += signs[j];

  for (const double flip : {1.0, -1.0}) {
    // The same problem with every input column negated: the Ritz vectors negate with them.
    const RitzResult ritz = RayleighRitz(problem.K, problem.M, flip * B);
    ASSERT_EQ(ritz.vectors.cols(), kColumns);
    for (int j = 0; j < kColumns; ++j) {
      // Second order in the perturbation: at most (1e-3)^2 kDofs max(K) = 1.4e-4.
      EXPECT_NEAR(ritz.values(j), 1.0 + j, 1e-6 * kDofs * kDofs) << "Ritz value " << j;
      EXPECT_GT(flip * signs[j] * ritz.vectors(j, j), 0.99) << "Ritz vector " << j << ", input sign " << flip * signs[j];
    }
    // vectors = B transform, whatever the signs.
    EXPECT_LT((flip * B * ritz.transform - ritz.vectors).norm(), 1e-12);
  }
}

}  // namespace
}  // namespace flexmbs::reduction
