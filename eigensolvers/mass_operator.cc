#include "eigensolvers/mass_operator.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace flexmbs::eigensolvers {
namespace {

using Index = Eigen::Index;
using SparseMatrix = Eigen::SparseMatrix<double>;

// Y = (A_s (x) I_3) X, or (|A_s| (x) I_3) X with kAbs, for a symmetric A_s in full storage:
// row v of A_s is its column v, so each node's three rows are one gather over that column.
template <bool kAbs>
void KroneckerTimes(const SparseMatrix& A_s, const double* X, double* Y, Index cols) {
  const Index N = A_s.cols();
  const int* outer = A_s.outerIndexPtr();
  const int* inner = A_s.innerIndexPtr();
  const double* values = A_s.valuePtr();
  for (Index c = 0; c < cols; ++c) {
    const double* x = X + c * 3 * N;
    double* y = Y + c * 3 * N;
    for (Index v = 0; v < N; ++v) {
      double y0 = 0.0, y1 = 0.0, y2 = 0.0;
      for (int k = outer[v]; k < outer[v + 1]; ++k) {
        const double a = kAbs ? std::abs(values[k]) : values[k];
        const double* x_w = x + 3 * Index{inner[k]};
        y0 += a * x_w[0];
        y1 += a * x_w[1];
        y2 += a * x_w[2];
      }
      y[3 * v] = y0;
      y[3 * v + 1] = y1;
      y[3 * v + 2] = y2;
    }
  }
}

}  // namespace

std::optional<ScalarMassSplit> SplitScalarMass(const SparseMatrix& M) {
  if (M.rows() != M.cols() || M.rows() % 3 != 0) return std::nullopt;
  const Index N = M.rows() / 3;
  ScalarMassSplit split;
  // M_s from the x-axis entries (3 v, 3 w), column by column (rows are sorted within a column).
  split.M_s.resize(N, N);
  split.M_s.reserve(M.nonZeros() / 9 + N);
  for (Index w = 0; w < N; ++w) {
    split.M_s.startVec(w);
    for (SparseMatrix::InnerIterator it(M, 3 * w); it; ++it) {
      if (it.row() % 3 == 0) split.M_s.insertBack(it.row() / 3, w) = it.value();
    }
  }
  split.M_s.finalize();
  // Every column of M against the same column of M_s (x) I_3: a merge of the two sorted columns.
  double& max_deviation = split.max_deviation;
  for (Index column = 0; column < M.outerSize(); ++column) {
    const Index a = column % 3;
    SparseMatrix::InnerIterator expected(split.M_s, column / 3);
    for (SparseMatrix::InnerIterator it(M, column); it; ++it) {
      split.max_entry = std::max(split.max_entry, std::abs(it.value()));
      if (it.row() % 3 != a) {
        max_deviation = std::max(max_deviation, std::abs(it.value()));
        continue;
      }
      for (; expected && expected.row() < it.row() / 3; ++expected) {
        max_deviation = std::max(max_deviation, std::abs(expected.value()));
      }
      if (expected && expected.row() == it.row() / 3) {
        max_deviation = std::max(max_deviation, std::abs(it.value() - expected.value()));
        ++expected;
      } else {
        max_deviation = std::max(max_deviation, std::abs(it.value()));
      }
    }
    for (; expected; ++expected)
      max_deviation = std::max(max_deviation, std::abs(expected.value()));
  }
  return split;
}

MassOperator::MassOperator(const SparseMatrix& M) : M_(&M) {
  std::optional<ScalarMassSplit> split = SplitScalarMass(M);
  if (split && split->max_deviation == 0.0) M_s_ = std::move(split->M_s);
}

void MassOperator::Times(const double* X, double* Y, Index cols) const {
  if (M_s_) {
    KroneckerTimes<false>(*M_s_, X, Y, cols);
    return;
  }
  Eigen::Map<Eigen::MatrixXd>(Y, rows(), cols).noalias() =
      *M_ * Eigen::Map<const Eigen::MatrixXd>(X, rows(), cols);
}

Eigen::MatrixXd MassOperator::Times(const Eigen::MatrixXd& X) const {
  FLEXMBS_CHECK(X.rows() == rows(), "MassOperator: wrong vector length");
  Eigen::MatrixXd Y(X.rows(), X.cols());
  Times(X.data(), Y.data(), X.cols());
  return Y;
}

Eigen::MatrixXd MassOperator::AbsTimes(const Eigen::MatrixXd& X) const {
  FLEXMBS_CHECK(X.rows() == rows(), "MassOperator: wrong vector length");
  if (!M_s_) return SparseOperator(*M_).AbsTimes(X);
  Eigen::MatrixXd Y(X.rows(), X.cols());
  KroneckerTimes<true>(*M_s_, X.data(), Y.data(), X.cols());
  return Y;
}

}  // namespace flexmbs::eigensolvers
