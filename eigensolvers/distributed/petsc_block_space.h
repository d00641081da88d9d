#pragma once
// The block Krylov missed-mode check's space (eigensolvers/block_krylov_check.h) on distributed
// PETSc matrices: each rank holds its rows of every vector, solves go through a MUMPS
// factorisation (MatMatSolve) or a substructured one with all columns at once, inner products
// are summed over the ranks. Used by the SLEPc backend instead of a Sturm count's factorisation.

#include <petscmat.h>

#include <vector>

#include "eigensolvers/block_krylov_check.h"
#include "eigensolvers/distributed/substructured_factor.h"

namespace flexmbs::eigensolvers {

/// K - sigma M's factorisation and M, row-distributed alike; both must outlive the object.
/// Every method is collective over M's communicator.
class PetscBlockSpace final : public BlockKrylovSpace {
 public:
  /// `factor`: a factored (MUMPS) K - sigma M, positive definite; `M` [kg]; `sigma` [rad^2/s^2].
  PetscBlockSpace(Mat factor, Mat M, double sigma);
  /// The same with K - sigma M factorised by substructuring (`factor` positive definite).
  PetscBlockSpace(const SubstructuredFactor& factor, Mat M, double sigma);

  Eigen::Index local_rows() const override { return local_rows_; }
  Eigen::Index global_rows() const override { return global_rows_; }
  double sigma() const override { return sigma_; }
  Eigen::MatrixXd ShiftInvert(const Eigen::MatrixXd& B) const override;
  Eigen::MatrixXd Mass(const Eigen::MatrixXd& X) const override;
  Eigen::VectorXd MassDiagonal() const override;
  Eigen::MatrixXd Sum(const Eigen::MatrixXd& local) const override;
  std::uint64_t stream() const override { return static_cast<std::uint64_t>(rank_); }

 private:
  Mat factor_ = nullptr;
  const SubstructuredFactor* substructured_ = nullptr;
  Mat M_;
  double sigma_;
  MPI_Comm comm_;
  PetscMPIInt rank_ = 0;
  Eigen::Index local_rows_ = 0, global_rows_ = 0;
};

/// This rank's rows of the distributed vectors `x` (one column each).
Eigen::MatrixXd LocalRows(const std::vector<Vec>& x, Eigen::Index local_rows);

}  // namespace flexmbs::eigensolvers
