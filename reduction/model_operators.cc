#include "reduction/model_operators.h"

#include "core/error.h"

namespace flexmbs::reduction {

Eigen::MatrixXd SparseOperator::Times(const Eigen::MatrixXd& X) const { return *A_ * X; }

Eigen::MatrixXd SparseOperator::AbsTimes(const Eigen::MatrixXd& X) const {
  return Eigen::SparseMatrix<double>(A_->cwiseAbs()) * X;
}

Eigen::VectorXd SparseOperator::Diagonal() const { return A_->diagonal(); }

fem::MassProperties MassPropertiesOf(const SymmetricOperator& M, const Eigen::Matrix3Xd& nodes) {
  FLEXMBS_CHECK(M.rows() == 3 * nodes.cols(), "M must be 3 n x 3 n");
  const Eigen::MatrixXd R = fem::RigidBodyModes(nodes);
  return fem::MassPropertiesFromRigidProjection(R.transpose() * M.Times(R));
}

}  // namespace flexmbs::reduction
