#pragma once
// A body's K and M known by their products, wherever they are held: assembled in this process
// (SparseOperator), or distributed over the MPI ranks, where no rank holds them whole
// (distributed_model.h, the distributed path of `flexmbs reduce`). The basis builders, the
// static solves and the SID data take them through FeModel (modal_basis.h).

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <span>

#include "fem/mass_properties.h"

namespace flexmbs::eigensolvers {

/// A symmetric matrix A (n x n) known by its products.
class SymmetricOperator {
 public:
  virtual ~SymmetricOperator() = default;
  /// n.
  virtual Eigen::Index rows() const = 0;
  /// A X (X: n x k).
  virtual Eigen::MatrixXd Times(const Eigen::MatrixXd& X) const = 0;
  /// |A| X, |A| the matrix of the absolute values of A's entries (for round-off floors).
  virtual Eigen::MatrixXd AbsTimes(const Eigen::MatrixXd& X) const = 0;
  /// The diagonal of A (n).
  virtual Eigen::VectorXd Diagonal() const = 0;
};

/// A held in this process (a view: A must outlive it; symmetric, full storage). Times is A X,
/// AbsTimes |A| X, Diagonal A.diagonal(); a block of columns is multiplied in one pass over A.
class SparseOperator final : public SymmetricOperator {
 public:
  explicit SparseOperator(const Eigen::SparseMatrix<double>& A) : A_(&A) {}
  Eigen::Index rows() const override { return A_->rows(); }
  Eigen::MatrixXd Times(const Eigen::MatrixXd& X) const override;
  Eigen::MatrixXd AbsTimes(const Eigen::MatrixXd& X) const override;
  Eigen::VectorXd Diagonal() const override;
  const Eigen::SparseMatrix<double>& matrix() const { return *A_; }

 private:
  const Eigen::SparseMatrix<double>* A_;
};

/// The rigid-body mass properties of a body with mass matrix M (DOF 3 node + axis) and nodes
/// p_BoN_B (3 x n) [m], from R^T (M R) (fem::MassPropertiesFromRigidProjection, R =
/// fem::RigidBodyModes): for M held here the same numbers as fem::MassPropertiesFromMassMatrix.
fem::MassProperties MassPropertiesOf(const SymmetricOperator& M, const Eigen::Matrix3Xd& nodes);

/// K [N/m] and M [kg] of a body (DOF 3 node + axis) that are not assembled in this process:
/// their products and static solves with K. The body may be held by clamped DOF (the
/// fixed-interface reduction); then `stiffness()` is the held body's: K with the clamped rows
/// and columns removed, defined only for vectors that vanish at the clamped DOF (the products
/// are K's at the other DOF and zero at the clamped ones), while its Diagonal() is the whole
/// K's. `mass()` is the whole M.
class ModelOperators {
 public:
  virtual ~ModelOperators() = default;
  virtual const SymmetricOperator& stiffness() const = 0;
  /// M of the mass matrix kind the modes were computed with.
  virtual const SymmetricOperator& mass() const = 0;
  /// The consistent mass matrix (the SID invariants'): mass() itself if that is consistent.
  virtual const SymmetricOperator& consistent_mass() const = 0;
  /// X (n x k) [m] with K_ff X_f = F_f on the DOF not in `fixed` and X = 0 at `fixed`, for
  /// F (n x k) [N]: the static responses of the body held at `fixed` (DOF numbers, distinct,
  /// every clamped DOF among them). K_ff must be positive definite (the caller has checked
  /// that `fixed` holds the body); else InternalError.
  virtual Eigen::MatrixXd SolveFixed(std::span<const Eigen::Index> fixed, const Eigen::MatrixXd& F) const = 0;
};

}  // namespace flexmbs::eigensolvers
