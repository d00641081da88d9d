#include "sid/taylor.h"

#include "core/error.h"

namespace flexmbs::sid {

Eigen::MatrixXd TaylorMatrix::Evaluate(const Eigen::VectorXd& q) const {
  Eigen::MatrixXd value = m0;
  if (m1.empty()) return value;
  const auto n = static_cast<std::size_t>(q.size());
  FLEXMBS_CHECK(m1.size() == n, "Taylor block: one modal coordinate per order-1 block");
  for (std::size_t j = 0; j < n; ++j) value += q(static_cast<Eigen::Index>(j)) * m1[j];
  if (m2.empty()) return value;
  FLEXMBS_CHECK(m2.size() == n * n, "Taylor block: n x n order-2 blocks");
  for (std::size_t j = 0; j < n; ++j) {
    for (std::size_t k = 0; k < n; ++k) {
      value += q(static_cast<Eigen::Index>(j)) * q(static_cast<Eigen::Index>(k)) * m2[j * n + k];
    }
  }
  return value;
}

bool TaylorMatrix::IsConsistent(Eigen::Index num_modes) const {
  const auto n = static_cast<std::size_t>(num_modes);
  if (!m1.empty() && m1.size() != n) return false;
  if (!m2.empty() && (m1.empty() || m2.size() != n * n)) return false;
  auto same_shape = [&](const Eigen::MatrixXd& block) {
    return block.rows() == m0.rows() && block.cols() == m0.cols();
  };
  for (const Eigen::MatrixXd& block : m1) {
    if (!same_shape(block)) return false;
  }
  for (const Eigen::MatrixXd& block : m2) {
    if (!same_shape(block)) return false;
  }
  return true;
}

}  // namespace flexmbs::sid
