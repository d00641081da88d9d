#include "eigensolvers/tall_products.h"

#include <gtest/gtest.h>

namespace flexmbs::eigensolvers {
namespace {

using Eigen::MatrixXd;

// BLAS's dgemm and Eigen's product differ in summation order only.
constexpr double kRoundOff = 1e-14;

TEST(TallProducts, EqualEigensProductsOnBlocksOfLargerMatrices) {
  const MatrixXd A = MatrixXd::Random(1000, 12);
  const MatrixXd B = MatrixXd::Random(1000, 5);
  // Leading columns of a wider matrix: column stride = rows, as the Lanczos blocks are held.
  const MatrixXd C = TransposeTimes(A.leftCols(7), B);
  const MatrixXd expected = A.leftCols(7).transpose() * B;
  EXPECT_LE((C - expected).norm(), kRoundOff * expected.norm());

  MatrixXd W = B;
  SubtractProduct(A.leftCols(7), C, W);
  const MatrixXd expected_W = B - A.leftCols(7) * C;
  EXPECT_LE((W - expected_W).norm(), kRoundOff * (B.norm() + (A.leftCols(7) * C).norm()));
}

TEST(TallProducts, EmptyOperandsGiveEmptyOrUnchangedResults) {
  const MatrixXd A(1000, 0);
  const MatrixXd B = MatrixXd::Random(1000, 3);
  EXPECT_EQ(TransposeTimes(A, B).rows(), 0);
  EXPECT_EQ(TransposeTimes(A, B).cols(), 3);
  MatrixXd W = B;
  SubtractProduct(A, MatrixXd(0, 3), W);
  EXPECT_EQ(W, B);
  // No rows (a rank without rows of the vectors): A^T B is a zero matrix.
  EXPECT_EQ(TransposeTimes(MatrixXd(0, 2), MatrixXd(0, 3)), MatrixXd::Zero(2, 3));
}

}  // namespace
}  // namespace flexmbs::eigensolvers
