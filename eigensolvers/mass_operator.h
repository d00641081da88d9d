#pragma once

// The mass matrix of a body held in this process, multiplied through its scalar mass matrix.
// Every FE mass matrix of flexmbs (consistent or lumped, DOF 3 node + axis) is M = M_s (x) I_3,
// and so is its restriction to whole free nodes: M_s has 1/9 of M's stored entries (M keeps the
// pattern of K), and a product through it reads 1/9 of the bytes (10x faster than Eigen's
// M * X on the tet10 bench bar).

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <optional>

#include "eigensolvers/model_operators.h"

namespace flexmbs::eigensolvers {

/// M_s of a square M (3N x 3N, full storage) read as M_s (x) I_3, and how far M is from that.
struct ScalarMassSplit {
  /// N x N, from M's x-axis entries (rows and columns 3 v).
  Eigen::SparseMatrix<double> M_s;
  /// The largest |entry| of M - M_s (x) I_3 (cross-axis entries, unequal axes) and of M.
  double max_deviation = 0.0;
  double max_entry = 0.0;
};

/// Splits M (3N x 3N); std::nullopt if M's size is not a multiple of 3 or it is not square.
/// O(nnz(M)).
std::optional<ScalarMassSplit> SplitScalarMass(const Eigen::SparseMatrix<double>& M);

/// M [kg] (symmetric, full storage) held in this process, a view (M must outlive it). Its
/// products go through M_s when M = M_s (x) I_3 exactly (bit-equal axes, cross-axis entries
/// zero: what fem::AssembleSystem produces), else through M itself; both give M X to round-off.
class MassOperator final : public SymmetricOperator {
 public:
  explicit MassOperator(const Eigen::SparseMatrix<double>& M);
  Eigen::Index rows() const override { return M_->rows(); }
  Eigen::MatrixXd Times(const Eigen::MatrixXd& X) const override;
  Eigen::MatrixXd AbsTimes(const Eigen::MatrixXd& X) const override;
  Eigen::VectorXd Diagonal() const override { return M_->diagonal(); }
  /// Y = M X for `cols` column-major columns of length rows() (Y must not alias X).
  void Times(const double* X, double* Y, Eigen::Index cols) const;
  /// Whether the products go through M_s.
  bool uses_scalar_mass() const { return M_s_.has_value(); }

 private:
  const Eigen::SparseMatrix<double>* M_;
  std::optional<Eigen::SparseMatrix<double>> M_s_;
};

}  // namespace flexmbs::eigensolvers
