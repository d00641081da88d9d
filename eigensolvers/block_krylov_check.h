#pragma once

// The missed-mode check MissedModeCheck::kBlockKrylov of the serial eigensolver: block Lanczos
// with the shift-invert operator from random vectors, deflated against the modes found, and an a
// posteriori bound on how small a missed mode's component in those vectors would have to be
// (docs/reduction.md, "The block Krylov check").

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cstdint>
#include <vector>

#include "eigensolvers/model_operators.h"

namespace flexmbs::eigensolvers {

class ShiftedFactorization;

/// The mass matrix M [kg] on this process's rows of every vector: all rows serially, a row
/// block of each under MPI, where every call is collective and the small matrices of inner
/// products are summed over the processes (Sum). Every process then holds the same small
/// matrices and takes the same decisions.
class MassSpace {
 public:
  virtual ~MassSpace() = default;
  /// Rows of the vectors on this process, and in all.
  virtual Eigen::Index local_rows() const = 0;
  virtual Eigen::Index global_rows() const = 0;
  /// M X.
  virtual Eigen::MatrixXd Mass(const Eigen::MatrixXd& X) const = 0;
  /// diag(M) on this process's rows (positive).
  virtual Eigen::VectorXd MassDiagonal() const = 0;
  /// The sum over the processes of `local`, the same small matrix shape on each (this
  /// process's part of an inner product); itself serially.
  virtual Eigen::MatrixXd Sum(const Eigen::MatrixXd& local) const { return local; }
  /// A number that differs between the processes (their rank), so that each draws its own rows
  /// of a random block; 0 serially.
  virtual std::uint64_t stream() const { return 0; }
};

/// What the block check needs of K phi = lambda M phi: M, and the shift-invert solve.
class BlockKrylovSpace : public MassSpace {
 public:
  /// The shift sigma [rad^2/s^2] of ShiftInvert.
  virtual double sigma() const = 0;
  /// (K - sigma M)^{-1} B for all of B's columns at once (K - sigma M positive definite).
  virtual Eigen::MatrixXd ShiftInvert(const Eigen::MatrixXd& B) const = 0;
};

/// The serial space: a factorisation of K - sigma M and M held in this process. Both must
/// outlive it.
class FactorizationSpace final : public BlockKrylovSpace {
 public:
  /// `factor`: an ok() Cholesky factorisation of K - sigma M (positive definite); `M` [kg]
  /// (a MassOperator, eigensolvers/mass_operator.h, for M held here).
  FactorizationSpace(const ShiftedFactorization& factor, const SymmetricOperator& M);
  Eigen::Index local_rows() const override { return M_.rows(); }
  Eigen::Index global_rows() const override { return M_.rows(); }
  double sigma() const override;
  Eigen::MatrixXd ShiftInvert(const Eigen::MatrixXd& B) const override;
  Eigen::MatrixXd Mass(const Eigen::MatrixXd& X) const override { return M_.Times(X); }
  Eigen::VectorXd MassDiagonal() const override { return M_.Diagonal(); }

 private:
  const ShiftedFactorization& factor_;
  const SymmetricOperator& M_;
};

/// Block Lanczos on the deflated shift-invert operator T = P (K - sigma M)^{-1} M P, P = I - X X^T M
/// the M-orthogonal projector onto the complement of the found M-orthonormal modes X, in the M
/// inner product, with full reorthogonalisation. Its eigenvalues are mu = 1 / (lambda - sigma)
/// for the eigenpairs of K phi = lambda M phi not in span X (0 on span X). Each step is one
/// solve with all columns of the last block at once (CHOLMOD's multi-column supernodal solve,
/// or MUMPS's under MPI).
class DeflatedBlockLanczos {
 public:
  /// `space`: the operators; `found`: M-orthonormal columns (this process's rows); `start`: the
  /// start block (its components along span `found` are removed here). `space` and `found`
  /// must outlive the object.
  DeflatedBlockLanczos(const BlockKrylovSpace& space, const Eigen::MatrixXd& found, Eigen::MatrixXd start);
  /// `found` is kept by reference: a temporary would dangle.
  DeflatedBlockLanczos(const BlockKrylovSpace&, Eigen::MatrixXd&&, Eigen::MatrixXd) = delete;

  /// One block step: solves with the last block, orthogonalises, updates the Ritz pairs.
  /// Returns false (and does nothing) once the space is invariant (the next block vanished).
  bool Extend();

  int steps() const { return static_cast<int>(widths_.size()) - 1; }
  /// Right-hand sides solved so far (the columns of all solves).
  Eigen::Index columns_solved() const { return columns_solved_; }
  /// Dimension of the Krylov space the Ritz pairs come from (blocks solved so far).
  Eigen::Index dimension() const { return ritz_values_.size(); }
  /// The start block with its span-`found` part removed (the components along any eigenvector
  /// of the deflated operator are those of the start block given).
  const Eigen::MatrixXd& start() const { return start_; }

  /// Ritz values of T, mu = 1 / (lambda - sigma), descending (lowest lambda first).
  const Eigen::VectorXd& ritz_values() const { return ritz_values_; }
  /// ||T y - mu y||_M of each Ritz pair (unit M-norm y), in the order of ritz_values().
  Eigen::VectorXd RitzResiduals() const;
  /// The M-orthonormal Ritz vectors with the given positions in ritz_values() (this process's rows).
  Eigen::MatrixXd RitzVectors(const std::vector<Eigen::Index>& which) const;

  /// An upper bound on ||u^T M start()|| (2-norm of the row of components) for every unit
  /// eigenvector u of T with eigenvalue `mu` that is not a Ritz value: with T Q = Q H + Q_+ B E^T
  /// (block Lanczos relation), u^T M Q (mu - H) = u^T M Q_+ B E^T, so
  /// u^T M start = u^T M Q_+ B E^T (mu - H)^{-1} Q^T M start and the bound is
  /// ||B E^T (mu - H)^{-1} Q^T M start||_2 (exact up to round-off; Paige's identity for one
  /// vector). 0 if the space is invariant.
  double HiddenComponentBound(double mu) const;

 private:
  const BlockKrylovSpace& space_;
  const Eigen::MatrixXd& X_;
  Eigen::MatrixXd MX_;
  Eigen::MatrixXd start_;
  // Appends a new block Q_k and M Q_k to the stored columns (the capacity doubles as needed).
  void Append(const Eigen::MatrixXd& Q, const Eigen::MatrixXd& MQ);

  // The M-orthonormal blocks Q_0 .. Q_k side by side in the first `stored_` columns of Q_ (Q_k
  // not solved yet), and M Q_j in MQ_: one product with all of them per Gram-Schmidt pass.
  Eigen::MatrixXd Q_;
  Eigen::MatrixXd MQ_;
  Eigen::Index stored_ = 0;
  std::vector<Eigen::Index> widths_;        // columns of Q_0 .. Q_k
  Eigen::MatrixXd H_;                       // Q^T M T Q over the solved blocks (upper block part filled)
  Eigen::MatrixXd next_coupling_;           // B: T Q_solved - Q_solved H = Q_k B E^T
  Eigen::MatrixXd start_coordinates_;       // Q_0^T M start
  Eigen::VectorXd ritz_values_;
  Eigen::MatrixXd ritz_coordinates_;        // eigenvectors of H, columns in the order of ritz_values_
  Eigen::Index columns_solved_ = 0;
};

/// The estimate of the smallest eigenvalue of D^{-1/2} M D^{-1/2} (D = diag M) the check uses:
/// the lowest Ritz value of `steps` Lanczos steps from a Gaussian vector (an upper bound of the
/// eigenvalue; 6.5 % above it after 20 steps on the tet10 bench bar), halved. For a lumped
/// (diagonal) M it is 0.5 (the eigenvalue is 1).
double ScaledMassFloorEstimate(const MassSpace& space, int steps, std::uint64_t seed);
/// The same for M held in this process.
double ScaledMassFloorEstimate(const Eigen::SparseMatrix<double>& M, int steps, std::uint64_t seed);

/// What CheckForMissedModes concluded.
enum class BlockCheckVerdict {
  kNoneMissed,  ///< no eigenvalue below the cut outside span(found), to the failure probability asked for
  kMissed,      ///< eigenvalues below the cut outside span(found): their converged pairs are returned
  kUndecided,   ///< neither within max_steps: the caller needs another check
};

/// The seed of the backends' block checks (plus the number of the run being checked).
inline constexpr std::uint64_t kBlockCheckSeed = 0xb10c0000u;

struct BlockCheckOptions {
  Eigen::Index block_size = 8;
  /// Block steps before giving up (kUndecided).
  int max_steps = 16;
  /// kNoneMissed needs the failure probability bound (BlockCheckResult) at most this.
  double failure_probability = 1e-15;
  /// A missed pair is returned once ||T y - mu y||_M <= tolerance mu (Spectra's criterion).
  double tolerance = 1e-10;
  /// Lanczos steps of ScaledMassFloorEstimate.
  int scale_steps = 20;
  std::uint64_t seed = 0;
};

struct BlockCheckResult {
  BlockCheckVerdict verdict = BlockCheckVerdict::kUndecided;
  /// kMissed: the converged Ritz pairs below the cut, lambda [rad^2/s^2] ascending, M-orthonormal
  /// vectors M-orthogonal to `found`.
  Eigen::VectorXd missed_values;
  Eigen::MatrixXd missed_vectors;
  int steps = 0;                  ///< block solves
  Eigen::Index columns = 0;       ///< right-hand sides solved (the sum of the blocks' widths)
  /// The largest HiddenComponentBound over missed-mode eigenvalues (lambda in (sigma, cut)), at the end.
  double hidden_component_bound = 0.0;
  /// The component scale s: a missed mode's component along one start column is N(0, s_u^2) with
  /// s_u = ||D^{-1/2} M u|| >= sqrt(lambda_min(D^{-1/2} M D^{-1/2})); s = sqrt(ScaledMassFloorEstimate).
  double component_scale = 0.0;
  /// Bound on the probability that a mode below the cut is missed by the check:
  /// P(chi^2_p <= (epsilon / s)^2) <= (epsilon^2 / (2 s^2))^{p/2} / Gamma(p / 2 + 1).
  double failure_probability = 1.0;
};

/// Whether K phi = lambda M phi has an eigenvalue below `cut` [rad^2/s^2] outside span(found):
/// DeflatedBlockLanczos from a block of Gaussian vectors scaled by diag(M)^{-1/2}, extended
/// until (a) a Ritz value lies below the cut (an eigenvalue there, by interlacing) and every such
/// pair has converged (kMissed), or (b) none does and the probability that a mode below the cut
/// hides from the block, bounded through HiddenComponentBound, is at most
/// options.failure_probability (kNoneMissed), or (c) max_steps (kUndecided).
/// Preconditions: the space's shift-invert a positive definite K - sigma M with sigma < cut;
/// `found` M-orthonormal (this process's rows). On every process under MPI (collective); the
/// missed vectors are this process's rows.
BlockCheckResult CheckForMissedModes(const BlockKrylovSpace& space, const Eigen::MatrixXd& found, double cut,
                                     const BlockCheckOptions& options);
/// The same with the serial space of `factor` and `M`.
BlockCheckResult CheckForMissedModes(const ShiftedFactorization& factor, const Eigen::SparseMatrix<double>& M,
                                     const Eigen::MatrixXd& found, double cut, const BlockCheckOptions& options);

}  // namespace flexmbs::eigensolvers
