#include "eigensolvers/serial/lanczos_runs.h"

#include <Spectra/SymGEigsShiftSolver.h>

#include <algorithm>
#include <cstdint>
#include <random>

#include "core/error.h"
#include "eigensolvers/block_krylov_check.h"
#include "eigensolvers/serial/block_lanczos_run.h"
#include "eigensolvers/mass_operator.h"
#include "eigensolvers/shifted_factorization.h"

namespace flexmbs::eigensolvers {
namespace {

using Index = Eigen::Index;

// Seeds of the block Lanczos runs (plus the number of the run).
constexpr std::uint64_t kBlockRunSeed = 0xb1a0000u;
// A block Lanczos run stops at this many Krylov vectors per pair sought, at least
// kMinBlockDimension (a verification run seeks 4 pairs above the 25 found and needs as many
// vectors as the first run) and at most kMaxBlockDimension (the run holds two vectors per
// dimension, 3.2 GB at 512 k DOF for 400), with what has converged; the rest is sought by the
// next, deflated, run. The 512 k DOF bench bar needed 7 per pair (176 for 25 pairs, blocks of 8).
constexpr Index kBlockDimensionPerPair = 10;
constexpr Index kMinBlockDimension = 200;
constexpr Index kMaxBlockDimension = 400;

// y = M x. Spectra's Lanczos step asks for M f twice for the same f (its norm, then its
// M-inner products with the basis), so the last product is remembered.
class MassProduct {
 public:
  using Scalar = double;
  explicit MassProduct(const MassOperator& M) : M_(M), last_x_(M.rows()), last_y_(M.rows()) {}
  Index rows() const { return M_.rows(); }
  Index cols() const { return M_.rows(); }
  void perform_op(const double* x_in, double* y_out) const {
    Eigen::Map<const Eigen::VectorXd> x(x_in, M_.rows());
    Eigen::Map<Eigen::VectorXd> y(y_out, M_.rows());
    if (!valid_ || x != last_x_) {
      last_x_ = x;
      M_.Times(last_x_.data(), last_y_.data(), 1);
      valid_ = true;
    }
    y = last_y_;
  }

 private:
  const MassOperator& M_;
  mutable Eigen::VectorXd last_x_;
  mutable Eigen::VectorXd last_y_;
  mutable bool valid_ = false;
};

// y = P (K - sigma M)^{-1} P^T z with P = I - X (M X)^T, the M-orthogonal projector onto the
// complement of the locked M-orthonormal vectors X. Spectra applies it to z = M x, so that the
// Lanczos operator is P (K - sigma M)^{-1} M P: M-self-adjoint, zero on span X (deflation).
class DeflatedShiftInvert {
 public:
  using Scalar = double;
  DeflatedShiftInvert(const ShiftedFactorization& factor, const Eigen::MatrixXd& X,
                      const Eigen::MatrixXd& MX, int* solves)
      : factor_(factor), X_(X), MX_(MX), solves_(solves), work_(factor.rows()) {}
  Index rows() const { return factor_.rows(); }
  Index cols() const { return factor_.rows(); }
  void set_shift(double sigma) {
    FLEXMBS_CHECK(sigma == factor_.sigma(),
                  "shift-invert operator: shift differs from the factorised one");
  }
  void perform_op(const double* z_in, double* y_out) const {
    ++*solves_;
    if (X_.cols() == 0) {
      factor_.Solve(z_in, y_out, 1);
      return;
    }
    Eigen::Map<const Eigen::VectorXd> z(z_in, rows());
    Eigen::Map<Eigen::VectorXd> y(y_out, rows());
    work_.noalias() = z - MX_ * (X_.transpose() * z);
    factor_.Solve(work_.data(), y_out, 1);
    y -= X_ * (MX_.transpose() * y);
  }

 private:
  const ShiftedFactorization& factor_;
  const Eigen::MatrixXd& X_;
  const Eigen::MatrixXd& MX_;
  int* solves_;
  mutable Eigen::VectorXd work_;
};

}  // namespace

KrylovRun RunLanczos(const ShiftedFactorization& factor, const MassOperator& M,
                     const Eigen::MatrixXd& X, Index nev, const EigenOptions& options,
                     unsigned seed, int* solves) {
  const Index n = M.rows();
  const Index available = n - X.cols();
  FLEXMBS_CHECK(nev >= 1 && nev < available, "Lanczos run: nev out of range");
  const Index ncv = std::min(available, std::max(2 * nev + 1, nev + 20));
  const Eigen::MatrixXd MX = M.Times(X);
  DeflatedShiftInvert op(factor, X, MX, solves);
  MassProduct mass(M);
  Spectra::SymGEigsShiftSolver<DeflatedShiftInvert, MassProduct, Spectra::GEigsMode::ShiftInvert>
      solver(op, mass, nev, ncv, factor.sigma());

  // Deterministic start vector, uniform in [-0.5, 0.5], M-orthogonal to the locked vectors.
  std::mt19937_64 rng(0x5eed0000u + seed);
  std::uniform_real_distribution<double> uniform(-0.5, 0.5);
  Eigen::VectorXd start(n);
  for (Index i = 0; i < n; ++i) start(i) = uniform(rng);
  if (X.cols() > 0) start -= X * (MX.transpose() * start);
  solver.init(start.data());
  solver.compute(Spectra::SortRule::LargestMagn, options.max_iterations, options.tolerance,
                 Spectra::SortRule::SmallestAlge);
  KrylovRun run;
  run.vectors = solver.eigenvectors();
  run.restarts = static_cast<int>(solver.num_iterations());
  return run;
}

Index BlockRunDimension(Index available, Index nev, Index block) {
  const Index wanted =
      std::min(kMaxBlockDimension, std::max(kBlockDimensionPerPair * nev, kMinBlockDimension));
  return std::min(available, std::max(wanted, nev + 4 * block));
}

KrylovRun RunBlock(const ShiftedFactorization& factor, const MassOperator& M,
                   const Eigen::MatrixXd& X, double lowest_found, Index nev,
                   const EigenOptions& options, Index block, unsigned seed, int* solves) {
  BlockRunOptions run_options;
  run_options.block_size = block;
  run_options.tolerance = options.tolerance;
  if (lowest_found > factor.sigma())
    run_options.operator_norm = 1.0 / (lowest_found - factor.sigma());
  run_options.seed = kBlockRunSeed + seed;
  run_options.max_dimension = BlockRunDimension(M.rows() - X.cols(), nev, block);
  BlockRunResult result = RunBlockLanczos(FactorizationSpace(factor, M), X, nev, run_options);
  *solves += static_cast<int>(result.columns);
  KrylovRun run;
  run.vectors = std::move(result.vectors);
  return run;
}

}  // namespace flexmbs::eigensolvers
