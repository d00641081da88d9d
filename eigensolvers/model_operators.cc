#include "eigensolvers/model_operators.h"

#include "core/error.h"

namespace flexmbs::eigensolvers {

namespace {

using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// A X = A^T X for a symmetric A through the row-major view A^T and X held row-major: one pass
// over A for all columns (Eigen's column-major product passes once per column). 25 columns of
// the 98 k tet10 K: 110 ms against 293 ms; |A| X without copying |A|: 199 against 406 ms.
template <typename SparseExpression>
Eigen::MatrixXd SymmetricTimes(const SparseExpression& A, const Eigen::MatrixXd& X) {
  if (X.cols() <= 1) return A * X;
  const RowMajorMatrix X_rows = X;
  RowMajorMatrix Y(A.rows(), X.cols());
  Y.noalias() = A.transpose() * X_rows;
  return Y;
}

}  // namespace

Eigen::MatrixXd SparseOperator::Times(const Eigen::MatrixXd& X) const { return SymmetricTimes(*A_, X); }

Eigen::MatrixXd SparseOperator::AbsTimes(const Eigen::MatrixXd& X) const { return SymmetricTimes(A_->cwiseAbs(), X); }

Eigen::VectorXd SparseOperator::Diagonal() const { return A_->diagonal(); }

fem::MassProperties MassPropertiesOf(const SymmetricOperator& M, const Eigen::Matrix3Xd& nodes) {
  FLEXMBS_CHECK(M.rows() == 3 * nodes.cols(), "M must be 3 n x 3 n");
  const Eigen::MatrixXd R = fem::RigidBodyModes(nodes);
  return fem::MassPropertiesFromRigidProjection(R.transpose() * M.Times(R));
}

}  // namespace flexmbs::eigensolvers
