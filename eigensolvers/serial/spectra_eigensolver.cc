// The "spectra" eigensolver backend: the driver of the Krylov runs (eigensolvers/serial/lanczos_runs.h),
// the missed-mode checks, Rayleigh-Ritz and refinement.
#include "eigensolvers/serial/spectra_eigensolver.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <numbers>
#include <optional>
#include <random>

#include "core/error.h"
#include "eigensolvers/block_krylov_check.h"
#include "eigensolvers/serial/lanczos_runs.h"
#include "eigensolvers/mass_operator.h"
#include "eigensolvers/serial/spectra_input_errors.h"
#include "eigensolvers/shifted_factorization.h"

namespace flexmbs::eigensolvers {
namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;
using Index = Eigen::Index;

// At most this many Lanczos runs: the first, then deflated ones to grow a band of unknown
// size, to find modes a check says were missed, and to verify.
constexpr int kMaxKrylovRuns = 12;
// Subspace-iteration steps refine the pairs until every residual is below kRefinementMargin
// times the tolerance or kRefinementFloorFactor times its round-off floor (margins below the
// acceptance bound, so that accepted pairs are not borderline), at most kMaxRefinementSteps
// times. Pairs limited by round-off sit at 0.5 .. 2 times their floor.
constexpr int kMaxRefinementSteps = 4;
constexpr double kRefinementMargin = 0.1;
constexpr double kRefinementFloorFactor = 2.0;
// Target of the final M-orthonormality, max |Phi^T M Phi - I|: a few hundred round-offs
// (the contract is 1e-10).
constexpr double kOrthonormalityTarget = 1e-13;
// Ritz vectors whose M-Gram eigenvalue is below this fraction of the largest are dependent
// (a deflated run re-found a locked direction) and dropped before Rayleigh-Ritz.
constexpr double kDependentDirection = 1e-10;
// kAuto makes the Sturm count (simplicial LDL^T, ~2 Gflop/s here, 5-20x slower than the
// supernodal Cholesky) only if the factorisation takes at most this many flops (~2 s).
constexpr double kAutoSturmMaxFlops = 5e9;
// Initial Lanczos size for a band of unknown size, and the growth step.
constexpr Index kInitialBandNev = 20;
// Pairs sought by a deflated verification run.
constexpr Index kVerificationNev = 4;
// Problems that need nev >= DOF - 1 cannot use Lanczos; they are solved densely up to this size.
constexpr Index kMaxDenseDofs = 4000;

double Seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

struct RitzPairs {
  Eigen::VectorXd values;   // ascending
  Eigen::MatrixXd vectors;  // M-orthonormal
};

// Rayleigh-Ritz for K phi = lambda M phi on span(B): an M-orthonormal basis Q of span(B)
// (dependent directions dropped), then the eigenpairs of Q^T K Q.
RitzPairs RayleighRitz(const SparseMatrix& K, const MassOperator& M, const Eigen::MatrixXd& B_in) {
  RitzPairs ritz;
  if (B_in.cols() == 0) {
    ritz.vectors = B_in;
    return ritz;
  }
  // Columns to unit M-norm first: after a shift-invert step their norms differ by the ratio of
  // 1 / (lambda - sigma) over the basis (1e15 with rigid-body modes), which would make the Gram
  // matrix useless.
  Eigen::MatrixXd B = B_in;
  Eigen::MatrixXd MB = M.Times(B);
  for (Index j = 0; j < B.cols(); ++j) {
    const double norm = std::sqrt(std::max(B.col(j).dot(MB.col(j)), 0.0));
    FLEXMBS_CHECK(norm > 0.0 && std::isfinite(norm), "Rayleigh-Ritz: zero or non-finite basis vector");
    B.col(j) /= norm;
    MB.col(j) /= norm;
  }
  Eigen::MatrixXd G = B.transpose() * MB;
  G = 0.5 * (G + G.transpose()).eval();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> gram(G);
  const Eigen::VectorXd& g = gram.eigenvalues();
  const double g_max = g.maxCoeff();
  Index first = 0;
  while (first < g.size() && g(first) <= kDependentDirection * g_max) ++first;
  const Index rank = g.size() - first;
  Eigen::MatrixXd Q = B * (gram.eigenvectors().rightCols(rank) *
                           g.tail(rank).cwiseSqrt().cwiseInverse().asDiagonal());
  // One Cholesky-QR pass in the M inner product to remove what round-off left.
  Eigen::MatrixXd G2 = Q.transpose() * M.Times(Q);
  G2 = 0.5 * (G2 + G2.transpose()).eval();
  Eigen::LLT<Eigen::MatrixXd> llt(G2);
  FLEXMBS_CHECK(llt.info() == Eigen::Success, "Rayleigh-Ritz: basis Gram matrix not positive definite");
  Q = llt.matrixU().solve<Eigen::OnTheRight>(Q);
  Eigen::MatrixXd Kr = Q.transpose() * SparseOperator(K).Times(Q);
  Kr = 0.5 * (Kr + Kr.transpose()).eval();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> reduced(Kr);
  ritz.values = reduced.eigenvalues();
  ritz.vectors = Q * reduced.eigenvectors();
  return ritz;
}

// Makes the columns of Phi M-orthonormal by Cholesky-QR in the M inner product.
void MOrthonormalize(const MassOperator& M, Eigen::MatrixXd& Phi) {
  Eigen::MatrixXd G = Phi.transpose() * M.Times(Phi);
  G = 0.5 * (G + G.transpose()).eval();
  Eigen::LLT<Eigen::MatrixXd> llt(G);
  FLEXMBS_CHECK(llt.info() == Eigen::Success, "M-orthonormalisation: Gram matrix not positive definite");
  Phi = llt.matrixU().solve<Eigen::OnTheRight>(Phi);
}

// Number of eigenvalues below `cut` (inertia of K - cut M by simplicial LDL^T).
struct SturmResult {
  Index count = 0;
  double cut = 0.0;
};
SturmResult SturmCount(const SparseMatrix& K, const SparseMatrix& M, double cut, EigenSolution* solution) {
  const auto start = std::chrono::steady_clock::now();
  struct AddTime {
    std::chrono::steady_clock::time_point start;
    double* seconds;
    ~AddTime() { *seconds += Seconds(start); }
  } add_time{start, &solution->sturm_seconds};
  ShiftedFactorization ldlt;
  for (int attempt = 0; attempt < 4; ++attempt) {
    ++solution->factorizations;
    // Only an exactly zero pivot fails: a cut at an eigenvalue; move it up a little.
    if (ldlt.Factorize(K, M, cut, ShiftedFactorization::Method::kSimplicialLdlt) ==
        ShiftedFactorization::Status::kOk) {
      return {ldlt.NegativePivots(), cut};
    }
    cut += 1e-9 * std::max(std::abs(cut), 1.0);
  }
  throw InputError(fmt::format("eigenproblem: K - lambda M has a zero pivot at every cut near lambda = {:g}: "
                               "cannot count the eigenvalues below it", cut));
}

// Whether K (factorised, sigma = 0) has an eigenvalue at zero to round-off: two steps of block
// inverse iteration from two random vectors, then Rayleigh-Ritz. A numerically singular K can
// pass Cholesky with round-off pivots; K^{-1} then amplifies its null space by ~1e8 or more,
// so the lowest Ritz value drops to round-off. For a positive definite K it stays >= lambda_1.
bool HasZeroEigenvalue(const ShiftedFactorization& factor, const SparseMatrix& K, const MassOperator& M,
                       double lambda_scale, int* solves) {
  constexpr Index kProbeVectors = 2;
  const Index n = K.rows();
  if (n < kProbeVectors) return false;
  std::mt19937_64 rng(0x9e3779b9u);
  std::uniform_real_distribution<double> uniform(-0.5, 0.5);
  Eigen::MatrixXd X(n, kProbeVectors);
  for (Index i = 0; i < X.size(); ++i) X.data()[i] = uniform(rng);
  for (int step = 0; step < 2; ++step) {
    const Eigen::MatrixXd MX = M.Times(X);
    factor.Solve(MX.data(), X.data(), kProbeVectors);
    *solves += static_cast<int>(kProbeVectors);
    X.colwise().normalize();
    if (!X.allFinite()) return true;
  }
  Eigen::MatrixXd Kr = X.transpose() * (K * X);
  Eigen::MatrixXd Mr = X.transpose() * M.Times(X);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ritz(0.5 * (Kr + Kr.transpose()), 0.5 * (Mr + Mr.transpose()),
                                                                 Eigen::EigenvaluesOnly);
  if (ritz.info() != Eigen::Success) return true;
  return ritz.eigenvalues()(0) <= kZeroEigenvalue * lambda_scale;
}

// All eigenpairs of a small problem by a dense generalized solver, lowest `wanted` kept.
RitzPairs SolveDense(const SparseMatrix& K, const SparseMatrix& M) {
  const Eigen::MatrixXd Kd = Eigen::MatrixXd(K);
  const Eigen::MatrixXd Md = Eigen::MatrixXd(M);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> dense(Kd, Md, Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
  if (dense.info() != Eigen::Success) {
    throw InputError("eigenproblem: dense generalized eigensolver failed: M is not positive definite");
  }
  return {dense.eigenvalues(), dense.eigenvectors()};
}

// One Solve of the spectra backend, in named steps: the shift and its factorisation, the
// methods, the band's Sturm count, the Krylov runs with their missed-mode checks (or a dense
// solve of a small model), then refinement and the acceptance checks.
class SpectraSolve {
 public:
  // `given`: the caller's factorisation of K - sigma M (SolveFactorized), or null to make one.
  SpectraSolve(const SparseMatrix& K, const SparseMatrix& M, const EigenOptions& options,
               const ShiftedFactorization* given, std::string_view backend)
      : K_(K), M_(M), options_(options), given_(given), mass_(M), n_(K.rows()),
        band_(options.max_frequency_hz > 0.0), cap_(options.num_modes),
        automatic_(given == nullptr && !options.shift_hz.has_value()),
        lambda_scale_(K.diagonal().sum() / M.diagonal().sum()) {
    const double omega_max = 2.0 * std::numbers::pi * options.max_frequency_hz;
    lambda_max_ = band_ ? omega_max * omega_max : std::numeric_limits<double>::infinity();
    solution_.backend = std::string(backend);
  }

  EigenSolution Run() {
    FactorizeShifted();
    ChooseMethods();
    CountBand();
    // Number of pairs wanted, if known yet (with a band: cap 0 = no cap).
    wanted_ = band_ ? (band_count_ < 0 ? -1 : cap_ > 0 ? std::min(cap_, band_count_) : band_count_) : cap_;
    const bool dense = wanted_ + 1 > n_ - 1 || !RunKrylov();
    if (dense) SolveAllDensely();
    SelectAndRefine();
    return Finish();
  }

 private:
  // What the Krylov loop carries from one run to the next.
  struct KrylovLoop {
    Eigen::MatrixXd basis;     // every pair found so far (Ritz vectors)
    Index nev = 0;             // pairs the next run looks for
    double cut = std::numeric_limits<double>::quiet_NaN();  // where the missed-mode check is made
    Index cut_count = -1;      // Sturm count at `cut`
    bool verifying = false;    // the last run was a deflated verification run below `cut`
    bool block_undecided = false;  // the block check could not decide: the Lanczos check does
    Eigen::MatrixXd missed;    // pairs below the cut the block check found, to add next
    Index below_cut_before = 0;
  };
  // What a pass of the Krylov loop decided.
  enum class Next { kRunAgain, kDone };

  // Shift-invert operator: Cholesky of K - sigma M, which must be positive definite. The
  // automatic shift tries sigma = 0 first and moves below zero if K has zero eigenvalues.
  void FactorizeShifted() {
    if (given_ != nullptr) {
      FLEXMBS_CHECK(given_->ok() && given_->rows() == n_ &&
                        given_->method() == ShiftedFactorization::Method::kSupernodalCholesky,
                    "SolveFactorized: the factorisation must be an ok() Cholesky factorisation of K - sigma M");
      sigma_ = given_->sigma();
      FLEXMBS_CHECK(!options_.shift_hz || ShiftFromHz(*options_.shift_hz) == sigma_,
                    "SolveFactorized: options.shift_hz differs from the factorisation's shift");
      factor_ = given_;
      solution_.shift = sigma_;
      return;
    }
    sigma_ = automatic_ ? 0.0 : ShiftFromHz(*options_.shift_hz);
    ++solution_.factorizations;
    auto status = own_.Factorize(K_, M_, sigma_, ShiftedFactorization::Method::kSupernodalCholesky);
    if (automatic_ && (status != ShiftedFactorization::Status::kOk ||
                       HasZeroEigenvalue(own_, K_, mass_, lambda_scale_, &solves_))) {
      sigma_ = FreeBodyShift(K_, M_);
      ++solution_.factorizations;
      status = own_.Factorize(K_, M_, sigma_, ShiftedFactorization::Method::kSupernodalCholesky);
    }
    if (status != ShiftedFactorization::Status::kOk) {
      const double free_body_shift = FreeBodyShift(K_, M_);
      const bool free_body_shift_works =
          sigma_ < 0.0 && free_body_shift < sigma_ &&
          own_.Factorize(K_, M_, free_body_shift, ShiftedFactorization::Method::kSupernodalCholesky) ==
              ShiftedFactorization::Status::kOk;
      throw InputError(NotPositiveDefiniteMessage(sigma_, automatic_, free_body_shift_works, free_body_shift));
    }
    solution_.factorization_seconds = Seconds(start_);
    factor_ = &own_;
    solution_.shift = sigma_;
  }

  // The missed-mode check and the Lanczos block size, automatic ones by the factorisation's cost.
  void ChooseMethods() {
    check_ = options_.check_missed_modes;
    if (check_ == MissedModeCheck::kAuto) {
      check_ = factor_->FactorFlops() <= kAutoSturmMaxFlops ? MissedModeCheck::kSturmCount
                                                             : MissedModeCheck::kBlockKrylov;
    }
    solution_.missed_mode_check = check_;
    lanczos_block_ = options_.lanczos_block_size;
    if (lanczos_block_ == 0) {
      lanczos_block_ = factor_->FactorFlops() > kAutoBlockLanczosMinFlops ? kAutoLanczosBlockSize : 1;
    }
    solution_.lanczos_block_size = static_cast<int>(lanczos_block_);
  }

  // With a Sturm count, the band's size is known before any Lanczos run; an empty band throws.
  void CountBand() {
    if (!band_ || check_ != MissedModeCheck::kSturmCount) return;
    const SturmResult sturm = SturmCount(K_, M_, lambda_max_, &solution_);
    band_count_ = sturm.count;
    solution_.sturm_count = static_cast<int>(sturm.count);
    solution_.sturm_cut = sturm.cut;
    solution_.checked_cut = sturm.cut;
    if (band_count_ > 0) return;
    std::optional<double> lowest;
    if (n_ >= 3) {
      const KrylovRun first = RunLanczos(*factor_, mass_, Eigen::MatrixXd(n_, 0), 1, options_, 0, &solves_);
      const RitzPairs pairs = RayleighRitz(K_, mass_, first.vectors);
      if (pairs.values.size() > 0) lowest = pairs.values(0);
    }
    ThrowEmptyBand(options_.max_frequency_hz, lowest);
  }

  // Krylov runs, each deflated against the pairs found, until the wanted pairs are found and
  // the missed-mode check passes. False if the runs exhausted the model (solve it densely).
  bool RunKrylov() {
    KrylovLoop loop;
    loop.basis.resize(n_, 0);
    loop.missed.resize(n_, 0);
    loop.nev = wanted_ > 0 ? wanted_ + GuardPairs(wanted_) : (cap_ > 0 ? cap_ + GuardPairs(cap_) : kInitialBandNev);
    for (int run = 0;; ++run) {
      if (run == kMaxKrylovRuns) {
        throw InputError(fmt::format("eigenproblem: modes still missing after {} Lanczos runs; raise "
                                     "max_iterations or tolerance", kMaxKrylovRuns));
      }
      Eigen::MatrixXd new_vectors;
      if (loop.missed.cols() > 0) {
        new_vectors.swap(loop.missed);
        loop.missed.resize(n_, 0);
      } else {
        loop.nev = std::min(loop.nev, n_ - loop.basis.cols() - 1);
        if (loop.nev < 1) return false;  // the Krylov bases exhausted the model: it is small
        new_vectors = KrylovVectors(loop, run);
      }
      AddToBasis(loop, new_vectors);
      if (loop.verifying) {
        // The deflated run from a fresh start vector found nothing new below the cut: verified.
        // Else it found a missed mode: decide again what is wanted, and check again.
        loop.verifying = false;
        if ((ritz_.values.array() < loop.cut).count() == loop.below_cut_before) return true;
      }
      if (DecideWanted(loop) == Next::kRunAgain) continue;
      if (CheckMissedModes(loop, run) == Next::kDone) return true;
    }
  }

  // One Lanczos run (single-vector or block) for loop.nev new pairs; throws if none converged.
  Eigen::MatrixXd KrylovVectors(const KrylovLoop& loop, int run) {
    const auto krylov_start = std::chrono::steady_clock::now();
    const auto seed = static_cast<unsigned>(run);
    const double lowest_found =
        ritz_.values.size() > 0 ? ritz_.values(0) : std::numeric_limits<double>::quiet_NaN();
    KrylovRun krylov =
        lanczos_block_ > 1
            ? RunBlock(*factor_, mass_, loop.basis, lowest_found, loop.nev, options_, lanczos_block_, seed, &solves_)
            : RunLanczos(*factor_, mass_, loop.basis, loop.nev, options_, seed, &solves_);
    ++solution_.krylov_runs;
    solution_.restarts += krylov.restarts;
    if (krylov.vectors.cols() == 0 && lanczos_block_ > 1) {
      throw InputError(fmt::format("eigenproblem: block Lanczos converged no pair within {} Krylov vectors "
                                   "(tolerance {:g}); raise tolerance or set lanczos_block_size 1",
                                   BlockRunDimension(n_ - loop.basis.cols(), loop.nev, lanczos_block_),
                                   options_.tolerance));
    }
    if (krylov.vectors.cols() == 0) {
      throw InputError(fmt::format("eigenproblem: Lanczos did not converge within max_iterations = {} "
                                   "restarts (tolerance {:g}); raise max_iterations", options_.max_iterations,
                                   options_.tolerance));
    }
    solution_.krylov_seconds += Seconds(krylov_start);
    return std::move(krylov.vectors);
  }

  // Rayleigh-Ritz on the basis and the new vectors: the new basis and Ritz pairs.
  void AddToBasis(KrylovLoop& loop, const Eigen::MatrixXd& new_vectors) {
    const auto ritz_start = std::chrono::steady_clock::now();
    Eigen::MatrixXd extended(n_, loop.basis.cols() + new_vectors.cols());
    extended << loop.basis, new_vectors;
    ritz_ = RayleighRitz(K_, mass_, extended);
    loop.basis = ritz_.vectors;
    solution_.krylov_seconds += Seconds(ritz_start);
    CheckNotSingular(ritz_.values, sigma_, automatic_, lambda_scale_);
  }

  // Whether the pairs found decide which are wanted (then wanted_ is set), else how many more
  // pairs the next run looks for.
  Next DecideWanted(KrylovLoop& loop) {
    const Index found = ritz_.values.size();
    const Index below_band = band_ ? (ritz_.values.array() < lambda_max_).count() : 0;
    if (band_ && band_count_ >= 0) {
      if (below_band > band_count_) {
        throw InputError(fmt::format("eigenproblem: {} modes found below max_frequency_hz = {:g} Hz but the "
                                     "Sturm count is {}: an eigenvalue lies at the band edge; move "
                                     "max_frequency_hz a little", below_band, options_.max_frequency_hz,
                                     band_count_));
      }
      if (below_band < wanted_) {
        loop.nev = wanted_ - below_band + GuardPairs(wanted_ - below_band);
        return Next::kRunAgain;
      }
    } else if (band_) {
      // Unknown band size: grow until a Ritz value beyond the band shows up (or the cap is met).
      const bool covered = ritz_.values(found - 1) >= lambda_max_ || (cap_ > 0 && below_band >= cap_);
      if (!covered) {
        loop.nev = std::max<Index>(found, kInitialBandNev);
        return Next::kRunAgain;
      }
      if (below_band == 0) ThrowEmptyBand(options_.max_frequency_hz, ritz_.values(0));
      wanted_ = cap_ > 0 ? std::min(cap_, below_band) : below_band;
    } else if (found < wanted_) {
      loop.nev = wanted_ - found + GuardPairs(wanted_ - found);
      return Next::kRunAgain;
    }
    return Next::kDone;
  }

  // The missed-mode check at the cut (the band edge if every mode below it is wanted, else
  // after the last wanted mode): done, or the next run (missed modes, a verification run).
  Next CheckMissedModes(KrylovLoop& loop, int run) {
    const Index below_band = band_ ? (ritz_.values.array() < lambda_max_).count() : 0;
    const bool whole_band = band_ && (cap_ == 0 || below_band <= cap_);
    const double new_cut = whole_band ? lambda_max_ : SturmCutAfter(ritz_.values, wanted_, sigma_);
    if (!(new_cut == loop.cut)) {
      loop.cut = new_cut;
      loop.cut_count = -1;
    }
    solution_.checked_cut = loop.cut;
    const Index below_cut = (ritz_.values.array() < loop.cut).count();
    if (check_ == MissedModeCheck::kNone) return Next::kDone;
    if (check_ == MissedModeCheck::kSturmCount) return CheckBySturmCount(loop, whole_band, below_cut);
    if (check_ == MissedModeCheck::kBlockKrylov && !loop.block_undecided) {
      // Block Lanczos from random vectors, deflated against everything found.
      const auto check_start = std::chrono::steady_clock::now();
      BlockCheckOptions block;
      block.tolerance = options_.tolerance;
      block.seed = kBlockCheckSeed + static_cast<std::uint64_t>(run);
      BlockCheckResult result = CheckForMissedModes(FactorizationSpace(*factor_, mass_), loop.basis, loop.cut, block);
      solves_ += static_cast<int>(result.columns);
      ++solution_.krylov_runs;
      solution_.krylov_seconds += Seconds(check_start);
      if (result.verdict == BlockCheckVerdict::kNoneMissed) return Next::kDone;
      if (result.verdict == BlockCheckVerdict::kMissed) {
        loop.missed.swap(result.missed_vectors);  // added by the next pass; then checked again
        return Next::kRunAgain;
      }
      loop.block_undecided = true;
      solution_.missed_mode_check = MissedModeCheck::kDeflatedLanczos;
    }
    // kDeflatedLanczos: one more run, deflated against everything found, from a new start.
    loop.verifying = true;
    loop.below_cut_before = below_cut;
    loop.nev = kVerificationNev;
    return Next::kRunAgain;
  }

  // The Sturm count at the cut (the band's own if the cut is the band edge) against the pairs
  // found below it: done, or a deflated run for the missed ones.
  Next CheckBySturmCount(KrylovLoop& loop, bool whole_band, Index below_cut) {
    if (loop.cut_count < 0) {
      if (whole_band && band_count_ >= 0) {
        loop.cut_count = band_count_;
      } else {
        const SturmResult sturm = SturmCount(K_, M_, loop.cut, &solution_);
        loop.cut = sturm.cut;
        loop.cut_count = sturm.count;
        solution_.sturm_count = static_cast<int>(sturm.count);
        solution_.sturm_cut = sturm.cut;
        solution_.checked_cut = sturm.cut;
      }
    }
    if (below_cut > loop.cut_count) {
      throw InputError(fmt::format("eigenproblem: {} modes found below {:g} Hz but the Sturm count is {}: "
                                   "the LDL^T inertia is unreliable for this model; use the deflated Lanczos "
                                   "check", below_cut, HzOf(loop.cut), loop.cut_count));
    }
    if (below_cut == loop.cut_count) return Next::kDone;
    loop.nev = loop.cut_count - below_cut + GuardPairs(loop.cut_count - below_cut);  // missed modes
    return Next::kRunAgain;
  }

  // Every pair of a small model by a dense solve: nothing can be missed.
  void SolveAllDensely() {
    if (n_ > kMaxDenseDofs) {
      throw InputError(fmt::format("eigenproblem: the modes asked for are too many for the Lanczos backend on a "
                                   "{} DOF model; ask for fewer modes or a lower max_frequency_hz", n_));
    }
    ritz_ = SolveDense(K_, M_);
    CheckNotSingular(ritz_.values, sigma_, automatic_, lambda_scale_);
    solution_.missed_mode_check = MissedModeCheck::kNone;
    solution_.lanczos_block_size = 0;
    if (band_) {
      const Index below = (ritz_.values.array() < lambda_max_).count();
      if (below == 0) ThrowEmptyBand(options_.max_frequency_hz, ritz_.values(0));
      wanted_ = cap_ > 0 ? std::min(cap_, below) : below;
    } else {
      wanted_ = cap_;
    }
  }

  // The lowest `wanted_` pairs; refine the whole basis by subspace iteration while a residual
  // is above its bound. Near the round-off floor a step can also make a pair worse (1.7 -> 4.6
  // floors on the stiffness-ratio-1e6 hard case), so the step that meets the acceptance bound
  // best is kept; then M-orthonormalised to kOrthonormalityTarget.
  void SelectAndRefine() {
    auto select = [&](const RitzPairs& r) {
      solution_.eigenvalues = r.values.head(wanted_);
      solution_.modes = r.vectors.leftCols(wanted_);
      residuals_ = ComputeResiduals(SparseOperator(K_), mass_, solution_.eigenvalues, solution_.modes, sigma_);
    };
    select(ritz_);
    double best_ratio = residuals_.WorstRatio(options_.residual_tolerance);
    Eigen::VectorXd best_values = solution_.eigenvalues;
    Eigen::MatrixXd best_modes = solution_.modes;
    PairResiduals best_residuals = residuals_;
    for (int step = 0; step < kMaxRefinementSteps && ritz_.values.size() > 0 &&
                       !residuals_.Accepted(kRefinementMargin * options_.residual_tolerance, nullptr,
                                            kRefinementFloorFactor);
         ++step) {
      const Eigen::MatrixXd MB = mass_.Times(ritz_.vectors);
      Eigen::MatrixXd B(n_, MB.cols());
      factor_->Solve(MB.data(), B.data(), MB.cols());
      solves_ += static_cast<int>(MB.cols());
      ritz_ = RayleighRitz(K_, mass_, B);
      ++solution_.refinement_steps;
      select(ritz_);
      const double ratio = residuals_.WorstRatio(options_.residual_tolerance);
      if (ratio < best_ratio) {
        best_ratio = ratio;
        best_values = solution_.eigenvalues;
        best_modes = solution_.modes;
        best_residuals = residuals_;
      }
    }
    solution_.eigenvalues.swap(best_values);
    solution_.modes.swap(best_modes);
    residuals_ = std::move(best_residuals);
    solution_.orthonormality_error = MOrthonormalityError(mass_, solution_.modes);
    for (int pass = 0; pass < 2 && solution_.orthonormality_error > kOrthonormalityTarget; ++pass) {
      MOrthonormalize(mass_, solution_.modes);
      solution_.orthonormality_error = MOrthonormalityError(mass_, solution_.modes);
      residuals_ = ComputeResiduals(SparseOperator(K_), mass_, solution_.eigenvalues, solution_.modes, sigma_);
    }
  }

  // The acceptance checks (residuals, M-orthonormality) and the solution's counts.
  EigenSolution Finish() {
    Eigen::Index worst = 0;
    if (!residuals_.Accepted(options_.residual_tolerance, &worst)) {
      throw InputError(fmt::format("eigenproblem: mode {} ({:g} Hz) has relative residual {:.3g} > max({:g}, {:g} x "
                                   "round-off floor {:.3g}) after {} refinement steps",
                                   worst + 1, HzOf(solution_.eigenvalues(worst)), residuals_.relative(worst),
                                   options_.residual_tolerance, kResidualFloorFactor, residuals_.floor(worst),
                                   solution_.refinement_steps));
    }
    if (solution_.orthonormality_error > 1e-10) {
      throw InputError(fmt::format("eigenproblem: modes are M-orthonormal only to {:.3g}", solution_.orthonormality_error));
    }
    solution_.relative_residuals = residuals_.relative;
    solution_.residual_floors = residuals_.floor;
    solution_.operator_applications = solves_;
    solution_.seconds = Seconds(start_);
    return std::move(solution_);
  }

  const std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  const SparseMatrix& K_;
  const SparseMatrix& M_;
  const EigenOptions& options_;
  const ShiftedFactorization* given_;
  const MassOperator mass_;
  const Index n_;
  const bool band_;         // all modes below max_frequency_hz
  const Index cap_;         // options.num_modes (with a band: 0 = no cap)
  const bool automatic_;    // the shift is chosen here
  const double lambda_scale_;  // trace(K) / trace(M)
  double lambda_max_ = 0.0;    // the band edge [rad^2/s^2] (infinite without a band)
  ShiftedFactorization own_;
  const ShiftedFactorization* factor_ = nullptr;  // given_ or &own_
  double sigma_ = 0.0;
  MissedModeCheck check_ = MissedModeCheck::kNone;
  Index lanczos_block_ = 1;
  Index band_count_ = -1;   // the band's Sturm count, if made
  Index wanted_ = -1;       // pairs returned, once known
  RitzPairs ritz_;          // the latest Ritz pairs
  PairResiduals residuals_;
  int solves_ = 0;
  EigenSolution solution_;
};

class SpectraEigensolver final : public Eigensolver {
 public:
  std::string_view name() const override { return "spectra"; }
  EigenSolution Solve(const SparseMatrix& K, const SparseMatrix& M, const EigenOptions& options) const override {
    ValidateEigenInputs(K, M, options);
    return SpectraSolve(K, M, options, nullptr, name()).Run();
  }
  bool UsesGivenFactorization() const override { return true; }
  EigenSolution SolveFactorized(const SparseMatrix& K, const SparseMatrix& M, const EigenOptions& options,
                                const ShiftedFactorization& factor) const override {
    ValidateEigenInputs(K, M, options);
    return SpectraSolve(K, M, options, &factor, name()).Run();
  }
};

}  // namespace

std::unique_ptr<Eigensolver> MakeSpectraEigensolver() { return std::make_unique<SpectraEigensolver>(); }

}  // namespace flexmbs::eigensolvers
