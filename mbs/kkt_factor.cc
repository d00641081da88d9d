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
  return sparse_->info() == Eigen::Success;
}

Eigen::MatrixXd KktFactor::Solve(const Eigen::MatrixXd& rhs) const {
  if (!sparse_) return dense_.solve(rhs);
  return sparse_->solve(rhs);
}

}  // namespace flexmbs::mbs
