#pragma once
// The factorisation of a Moreau-Jean step's KKT matrix [A G^T; G 0] (mbs/moreau_jean.h): a dense
// full-pivot LU for small or dense matrices, a sparse LU (COLAMD ordering) for larger sparse ones
// (many bodies: A is block diagonal over the bodies up to the force elements' couplings), where
// the dense O(n^3) factorisation per step dominates (docs/contact.md, "Moreau-Jean time
// stepping").

#include <Eigen/Core>
#include <Eigen/LU>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <memory>

namespace flexmbs::mbs {

/// KktFactor factorises sparsely from this many rows on (measured on bouncing balls, 6 x 6 mass
/// blocks: dense faster at 12 rows, sparse 1.6x faster at 30, 2.4x at 60, 36x at 600) ...
inline constexpr Eigen::Index kSparseKktFromSize = 24;
/// ... where at most this fraction of the entries is non-zero (one flexible body's dense 38 x 38
/// block: sparse 15 % slower).
inline constexpr double kSparseKktMaxDensity = 0.25;

/// The sparse path's singularity probe: K x = K 1 solved must give x = 1 within this (20 bodies
/// with 5 joint rows: 3e-15; the same with a joint row given twice, which SparseLU factorises
/// without complaint: 1.5e18).
inline constexpr double kSingularProbeTolerance = 1e-6;

/// A factorised square KKT matrix.
class KktFactor {
 public:
  /// Factorises `kkt` (square), sparsely if it has kSparseKktFromSize rows or more and at most
  /// kSparseKktMaxDensity of its entries are non-zero; returns false if it is singular (dense: by
  /// the full-pivot LU's rank, sparse: by kSingularProbeTolerance).
  bool Compute(const Eigen::MatrixXd& kkt);
  /// kkt^-1 rhs.
  Eigen::MatrixXd Solve(const Eigen::MatrixXd& rhs) const;
  /// The rank the dense LU found, or -1 after a sparse factorisation.
  Eigen::Index rank() const { return sparse_ ? -1 : dense_.rank(); }

 private:
  Eigen::FullPivLU<Eigen::MatrixXd> dense_;
  std::unique_ptr<Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>>> sparse_;
};

}  // namespace flexmbs::mbs
