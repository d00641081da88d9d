#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>

namespace flexmbs::eigensolvers {

/// A sparse factorisation of the symmetric matrix A = K - sigma M by CHOLMOD (the CHOLMOD
/// headers stay in the .cc). Used as the shift-invert operator of the eigensolver and for
/// Sturm counts; reusable wherever a symmetric sparse solve is needed.
class ShiftedFactorization {
 public:
  enum class Method {
    /// Supernodal Cholesky A = L L^T (BLAS-3): fast; A must be positive definite.
    kSupernodalCholesky,
    /// Simplicial A = L D L^T without pivoting: works for indefinite A (unless a pivot is
    /// exactly zero) and gives its inertia; slower.
    kSimplicialLdlt,
  };

  enum class Status {
    kOk,
    kNotPositiveDefinite,  ///< Cholesky met a pivot <= 0 (A indefinite or singular)
    kSingular,             ///< L D L^T met a zero pivot
  };

  ShiftedFactorization();
  ~ShiftedFactorization();
  ShiftedFactorization(ShiftedFactorization&&) noexcept;
  ShiftedFactorization& operator=(ShiftedFactorization&&) noexcept;
  ShiftedFactorization(const ShiftedFactorization&) = delete;
  ShiftedFactorization& operator=(const ShiftedFactorization&) = delete;

  /// Factorises A = K - sigma M (K, M: square, equal size, symmetric, full or upper storage;
  /// only the upper triangle is read). On a status other than kOk there is no valid factor.
  /// A new shift (or new values) on the same pattern and method reuses the fill-reducing
  /// ordering and symbolic analysis of the previous call.
  /// Note: a numerically singular A may factorise with small pivots; the pivot ratio does not
  /// tell it from a merely ill-conditioned one (a free-free K at sigma = 0 gave 8e-8, a
  /// clamped one with a stiffness ratio of 1e6 gave 4e-8), so callers judge singularity from
  /// the eigenvalues they compute.
  Status Factorize(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M,
                   double sigma, Method method);

  bool ok() const;
  Eigen::Index rows() const;
  double sigma() const;
  Method method() const;

  /// X = A^{-1} B for `num_rhs` column-major right-hand sides of length rows() (X may alias B).
  void Solve(const double* B, double* X, Eigen::Index num_rhs = 1) const;
  /// X = A^{-1} B.
  Eigen::MatrixXd Solve(const Eigen::MatrixXd& B) const;

  /// Number of negative pivots of L D L^T = number of eigenvalues of K phi = lambda M phi
  /// below sigma (Sylvester's law of inertia; M positive definite). 0 for a Cholesky factor.
  Eigen::Index NegativePivots() const;
  /// min |d| / max |d| over the pivots d (D of L D L^T, or the squared diagonal of L; for a
  /// Cholesky factor this is CHOLMOD's rcond estimate). >= 1 / cond(A) for a Cholesky factor.
  double PivotRatio() const;
  /// The pivot index (0-based, in the fill-reducing order) where a failed factorisation
  /// stopped; rows() if none.
  Eigen::Index FailedPivot() const;
  /// Number of nonzeros of the factor L.
  double FactorNonzeros() const;
  /// Floating-point operations of the numeric factorisation (CHOLMOD's analysis estimate).
  double FactorFlops() const;

  /// Numeric factorisations attempted by Factorize in this process so far, by every object and
  /// thread (successful or not). For tests and benchmarks that check that one factorisation is
  /// shared instead of repeated: compare the count before and after.
  static long NumericFactorizations();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace flexmbs::eigensolvers
