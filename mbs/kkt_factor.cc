#include "mbs/kkt_factor.h"

namespace flexmbs::mbs {

bool KktFactor::Compute(const Eigen::MatrixXd& kkt) {
  const double density = static_cast<double>((kkt.array() != 0.0).count()) / static_cast<double>(kkt.size());
  if (kkt.rows() < kSparseKktFromSize || density > kSparseKktMaxDensity) {
    sparse_.reset();
    dense_.compute(kkt);
    return dense_.isInvertible();
  }
  const Eigen::SparseMatrix<double> matrix = kkt.sparseView();
  sparse_ = std::make_unique<Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>>>();
  sparse_->compute(matrix);
  if (sparse_->info() != Eigen::Success) return false;
  // Eigen's SparseLU factorises an exactly singular matrix through a round-off pivot: the probe
  // K x = K 1 must give x = 1.
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(kkt.rows());
  const Eigen::VectorXd x = sparse_->solve(matrix * ones);
  return (x - ones).lpNorm<Eigen::Infinity>() <= kSingularProbeTolerance;
}

Eigen::MatrixXd KktFactor::Solve(const Eigen::MatrixXd& rhs) const {
  if (!sparse_) return dense_.solve(rhs);
  return sparse_->solve(rhs);
}

}  // namespace flexmbs::mbs
