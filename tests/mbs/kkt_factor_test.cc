// mbs/kkt_factor.h: the sparse path gives Eigen's dense full-pivot LU solution of the same KKT
// matrix (block-diagonal masses of many bodies and joint rows), the dense path is taken for small
// or dense matrices, and a singular matrix is reported on both paths.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "mbs/kkt_factor.h"

namespace flexmbs::mbs {
namespace {

/// [A G^T; G 0] of `bodies` 6 x 6 symmetric positive definite mass blocks and `rows` joint rows
/// that each couple two neighbouring bodies.
Eigen::MatrixXd KktOfBodies(int bodies, int rows, std::mt19937& rng) {
  std::uniform_real_distribution<double> entry(-1.0, 1.0);
  const Eigen::Index nu = 6 * bodies;
  Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(nu + rows, nu + rows);
  for (int b = 0; b < bodies; ++b) {
    Eigen::MatrixXd B(6, 6);
    for (Eigen::Index i = 0; i < B.size(); ++i) B(i) = entry(rng);
    kkt.block(6 * b, 6 * b, 6, 6) = B * B.transpose() + 6.0 * Eigen::MatrixXd::Identity(6, 6);
  }
  for (int r = 0; r < rows; ++r) {
    const Eigen::Index body = r % (bodies - 1);
    for (Eigen::Index c = 0; c < 12; ++c) kkt(nu + r, 6 * body + c) = entry(rng);
    kkt.block(0, nu + r, nu, 1) = kkt.block(nu + r, 0, 1, nu).transpose();
  }
  return kkt;
}

TEST(KktFactor, SparsePathSolvesAsEigensDenseLu) {
  std::mt19937 rng(21);
  const Eigen::MatrixXd kkt = KktOfBodies(20, 5, rng);  // 125 rows, 0.07 of them non-zero
  const Eigen::MatrixXd rhs = Eigen::MatrixXd::Random(kkt.rows(), 3);
  KktFactor factor;
  ASSERT_TRUE(factor.Compute(kkt));
  EXPECT_EQ(factor.rank(), -1);  // the sparse path
  const Eigen::MatrixXd reference = kkt.fullPivLu().solve(rhs);
  const double difference = (factor.Solve(rhs) - reference).norm() / reference.norm();
  std::printf("KKT of 20 bodies and 5 joint rows: sparse against dense LU %.3e\n", difference);
  EXPECT_LT(difference, 3e-15);  // measured 2.8e-16
}

TEST(KktFactor, SmallOrDenseMatricesTakeTheDenseLu) {
  std::mt19937 rng(22);
  KktFactor factor;
  ASSERT_TRUE(factor.Compute(KktOfBodies(3, 2, rng)));  // 20 rows
  EXPECT_EQ(factor.rank(), 20);
  Eigen::MatrixXd dense = Eigen::MatrixXd::Random(40, 40);
  dense = dense * dense.transpose() + 40.0 * Eigen::MatrixXd::Identity(40, 40);
  ASSERT_TRUE(factor.Compute(dense));
  EXPECT_EQ(factor.rank(), 40);
}

TEST(KktFactor, SingularMatricesAreReportedOnBothPaths) {
  std::mt19937 rng(23);
  Eigen::MatrixXd sparse = KktOfBodies(20, 5, rng);
  sparse.row(sparse.rows() - 1) = sparse.row(sparse.rows() - 2);  // a joint row given twice
  sparse.col(sparse.cols() - 1) = sparse.col(sparse.cols() - 2);
  KktFactor factor;
  EXPECT_FALSE(factor.Compute(sparse));
  Eigen::MatrixXd small = KktOfBodies(3, 2, rng);
  small.row(small.rows() - 1) = small.row(small.rows() - 2);
  small.col(small.cols() - 1) = small.col(small.cols() - 2);
  EXPECT_FALSE(factor.Compute(small));
}

}  // namespace
}  // namespace flexmbs::mbs
