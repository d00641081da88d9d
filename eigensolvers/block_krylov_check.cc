#include "eigensolvers/block_krylov_check.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "core/error.h"
#include "eigensolvers/mass_operator.h"
#include "eigensolvers/shifted_factorization.h"
#include "eigensolvers/tall_products.h"

namespace flexmbs::eigensolvers {
namespace {

using Index = Eigen::Index;
using Matrix = Eigen::MatrixXd;

// A new Krylov direction whose M-norm after orthogonalisation is below this fraction of the
// largest column of T Q_k is taken as already in the space (the space is invariant in it):
// six orders above the round-off that two Gram-Schmidt passes leave.
constexpr double kRankTolerance = 1e-10;
// The hidden-component bound is evaluated at lambda - sigma = (cut - sigma) 2^(-g/4),
// g = 0 .. kBoundGridPoints - 1 (down to 2.4e-4 of the distance from the shift to the cut).
// It falls towards the shift like (lambda - sigma)^(steps); its largest value was at the cut in
// every case measured.
constexpr int kBoundGridPoints = 49;

// Removes the span of the M-orthonormal X from W (two passes); adds the squared M-norms of
// the removed parts, per column, to `removed`.
void Deflate(const BlockKrylovSpace& space, const Matrix& X, const Matrix& MX, Matrix& W,
             Eigen::RowVectorXd& removed) {
  if (X.cols() == 0) return;
  for (int pass = 0; pass < 2; ++pass) {
    const Matrix c = space.Sum(TransposeTimes(MX, W));
    SubtractProduct(X, c, W);
    removed += c.colwise().squaredNorm();
  }
}

// W = Q B with Q M-orthonormal (r columns), from the eigen-decomposition of the Gram matrix.
// `removed`: the squared M-norms, per column, of what orthogonalisation took out of W, so that
// reference = the largest M-norm W had before; directions of M-norm <= kRankTolerance *
// reference are dropped (r < W.cols()).
struct MOrthonormalized {
  Matrix Q;
  Matrix MQ;
  Matrix B;  // r x W.cols()
};
MOrthonormalized MOrthonormalize(const BlockKrylovSpace& space, const Matrix& W, const Eigen::RowVectorXd& removed) {
  const Matrix MW = space.Mass(W);
  Matrix G = space.Sum(W.transpose() * MW);
  G = 0.5 * (G + G.transpose()).eval();
  const double reference_squared = (removed + G.diagonal().transpose().cwiseMax(0.0)).maxCoeff();
  Eigen::SelfAdjointEigenSolver<Matrix> gram(G);
  const Eigen::VectorXd& g = gram.eigenvalues();  // ascending
  const double floor = kRankTolerance * kRankTolerance * reference_squared;
  Index first = 0;
  while (first < g.size() && !(g(first) > floor)) ++first;
  const Index r = g.size() - first;
  const Matrix U = gram.eigenvectors().rightCols(r);
  const Eigen::VectorXd root = g.tail(r).cwiseSqrt();
  const Matrix scale = U * root.cwiseInverse().asDiagonal();
  return {W * scale, MW * scale, root.asDiagonal() * U.transpose()};
}

}  // namespace

FactorizationSpace::FactorizationSpace(const ShiftedFactorization& factor, const SymmetricOperator& M)
    : factor_(factor), M_(M) {
  FLEXMBS_CHECK(factor.ok() && factor.rows() == M.rows(),
                "FactorizationSpace: the factorisation and M must be of one size");
}

double FactorizationSpace::sigma() const { return factor_.sigma(); }

Matrix FactorizationSpace::ShiftInvert(const Matrix& B) const {
  Matrix X(B.rows(), B.cols());
  factor_.Solve(B.data(), X.data(), B.cols());
  return X;
}

DeflatedBlockLanczos::DeflatedBlockLanczos(const BlockKrylovSpace& space, const Matrix& found, Matrix start)
    : space_(space), X_(found), start_(std::move(start)) {
  const Index n = space.local_rows();
  FLEXMBS_CHECK(found.rows() == n && start_.rows() == n,
                "DeflatedBlockLanczos: the found modes and the start block must have the space's rows");
  MX_ = space.Mass(X_);
  Eigen::RowVectorXd removed = Eigen::RowVectorXd::Zero(start_.cols());
  Deflate(space, X_, MX_, start_, removed);
  MOrthonormalized first = MOrthonormalize(space, start_, removed);
  start_coordinates_ = std::move(first.B);
  Append(first.Q, first.MQ);
  next_coupling_ = Matrix(widths_.back(), 0);
}

void DeflatedBlockLanczos::Append(const Matrix& Q, const Matrix& MQ) {
  const Index w = Q.cols();
  if (stored_ + w > Q_.cols()) {
    const Index capacity = std::max(2 * Q_.cols(), stored_ + w);
    Matrix grown_Q(Q.rows(), capacity);
    Matrix grown_MQ(Q.rows(), capacity);
    if (stored_ > 0) {  // the first block: Q_ is still 0 x 0, and Eigen refuses an n x 0 copy of it
      grown_Q.leftCols(stored_) = Q_.leftCols(stored_);
      grown_MQ.leftCols(stored_) = MQ_.leftCols(stored_);
    }
    Q_.swap(grown_Q);
    MQ_.swap(grown_MQ);
  }
  Q_.middleCols(stored_, w) = Q;
  MQ_.middleCols(stored_, w) = MQ;
  stored_ += w;
  widths_.push_back(w);
}

bool DeflatedBlockLanczos::Extend() {
  const Index w = widths_.back();
  if (w == 0) return false;
  const Index d_old = ritz_values_.size();
  const Index d = d_old + w;  // = stored_

  Matrix W = space_.ShiftInvert(MQ_.middleCols(d_old, w));  // T Q_k before deflation
  columns_solved_ += w;
  // Two passes of block classical Gram-Schmidt against the found modes (the deflation) and the
  // Krylov blocks; the coefficients along the blocks are the new block column of H.
  Matrix coefficients = Matrix::Zero(d, w);
  Eigen::RowVectorXd removed = Eigen::RowVectorXd::Zero(w);  // squared M-norms taken out
  for (int pass = 0; pass < 2; ++pass) {
    Deflate(space_, X_, MX_, W, removed);
    const Matrix c = space_.Sum(TransposeTimes(MQ_.leftCols(d), W));
    SubtractProduct(Q_.leftCols(d), c, W);
    coefficients += c;
    removed += c.colwise().squaredNorm();
  }
  MOrthonormalized next = MOrthonormalize(space_, W, removed);

  Matrix H = Matrix::Zero(d, d);
  H.topLeftCorner(d_old, d_old) = H_;
  H.middleCols(d_old, w) = coefficients;
  if (d_old > 0) H.block(d_old, d_old - next_coupling_.cols(), w, next_coupling_.cols()) = next_coupling_;
  H_ = std::move(H);
  next_coupling_ = std::move(next.B);
  Append(next.Q, next.MQ);

  const Matrix symmetric = 0.5 * (H_ + H_.transpose());
  Eigen::SelfAdjointEigenSolver<Matrix> ritz(symmetric);
  ritz_values_ = ritz.eigenvalues().reverse();
  ritz_coordinates_ = ritz.eigenvectors().rowwise().reverse();
  return true;
}

Eigen::VectorXd DeflatedBlockLanczos::RitzResiduals() const {
  const Index d = ritz_values_.size();
  if (d == 0 || next_coupling_.rows() == 0) return Eigen::VectorXd::Zero(d);
  const Index last = widths_[widths_.size() - 2];
  return (next_coupling_ * ritz_coordinates_.bottomRows(last)).colwise().norm().transpose();
}

Matrix DeflatedBlockLanczos::RitzVectors(const std::vector<Index>& which) const {
  Matrix S(ritz_values_.size(), static_cast<Index>(which.size()));
  for (std::size_t j = 0; j < which.size(); ++j) S.col(static_cast<Index>(j)) = ritz_coordinates_.col(which[j]);
  return Q_.leftCols(ritz_values_.size()) * S;
}

double DeflatedBlockLanczos::HiddenComponentBound(double mu) const {
  const Index d = ritz_values_.size();
  if (d == 0 || next_coupling_.rows() == 0) return 0.0;
  const Index first = widths_.front();
  const Index last = widths_[widths_.size() - 2];
  // B E^T S (mu - Theta)^{-1} S^T E_0 R_0, with H = S Theta S^T.
  const Matrix G = next_coupling_ * ritz_coordinates_.bottomRows(last);
  const Matrix C = ritz_coordinates_.topRows(first).transpose() * start_coordinates_;
  Eigen::VectorXd inverse(d);
  for (Index j = 0; j < d; ++j) {
    if (mu == ritz_values_(j)) return std::numeric_limits<double>::infinity();
    inverse(j) = 1.0 / (mu - ritz_values_(j));
  }
  const Matrix F = G * inverse.asDiagonal() * C;
  return Eigen::JacobiSVD<Matrix>(F).singularValues()(0);
}

double ScaledMassFloorEstimate(const MassSpace& space, int steps, std::uint64_t seed) {
  const Index n = space.local_rows();
  const Index k_max = std::min<Index>(steps, space.global_rows());
  FLEXMBS_CHECK(k_max >= 1, "ScaledMassFloorEstimate: no Lanczos step");
  const Eigen::VectorXd scale = space.MassDiagonal().cwiseSqrt().cwiseInverse();
  const auto norm = [&](const Eigen::VectorXd& v) {
    return std::sqrt(space.Sum(Matrix::Constant(1, 1, v.squaredNorm()))(0, 0));
  };
  std::mt19937_64 rng(seed ^ space.stream());
  std::normal_distribution<double> normal;
  Matrix V(n, k_max);
  Eigen::VectorXd v(n);
  for (Index i = 0; i < n; ++i) v(i) = normal(rng);
  V.col(0) = v / norm(v);
  Matrix H = Matrix::Zero(k_max, k_max);
  Index k = 0;
  for (; k < k_max; ++k) {
    Eigen::VectorXd w = scale.cwiseProduct(space.Mass(scale.cwiseProduct(V.col(k))));
    for (int pass = 0; pass < 2; ++pass) {
      const Eigen::VectorXd c = space.Sum(V.leftCols(k + 1).transpose() * w);
      w -= V.leftCols(k + 1) * c;
      H.col(k).head(k + 1) += c;
    }
    const double beta = norm(w);
    if (k + 1 == k_max || !(beta > kRankTolerance * H(k, k))) break;
    H(k + 1, k) = beta;
    V.col(k + 1) = w / beta;
  }
  const Index size = k + 1;
  const Matrix T = H.topLeftCorner(size, size);
  const double lowest = Eigen::SelfAdjointEigenSolver<Matrix>(0.5 * (T + T.transpose()), Eigen::EigenvaluesOnly)
                            .eigenvalues()(0);
  return 0.5 * lowest;
}

double ScaledMassFloorEstimate(const Eigen::SparseMatrix<double>& M, int steps, std::uint64_t seed) {
  class SparseMass final : public MassSpace {
   public:
    explicit SparseMass(const Eigen::SparseMatrix<double>& M) : M_(M) {}
    Index local_rows() const override { return M_.rows(); }
    Index global_rows() const override { return M_.rows(); }
    Matrix Mass(const Matrix& X) const override { return M_ * X; }
    Eigen::VectorXd MassDiagonal() const override { return M_.diagonal(); }

   private:
    const Eigen::SparseMatrix<double>& M_;
  };
  return ScaledMassFloorEstimate(SparseMass(M), steps, seed);
}

BlockCheckResult CheckForMissedModes(const BlockKrylovSpace& space, const Matrix& found, double cut,
                                     const BlockCheckOptions& options) {
  const Index n = space.local_rows();
  const double sigma = space.sigma();
  FLEXMBS_CHECK(cut > sigma, "CheckForMissedModes: the cut must lie above the shift");
  FLEXMBS_CHECK(options.block_size >= 1 && options.max_steps >= 1 && options.failure_probability > 0.0 &&
                    options.tolerance > 0.0 && options.scale_steps >= 1,
                "CheckForMissedModes: bad options");
  const double mu_cut = 1.0 / (cut - sigma);
  BlockCheckResult result;
  const Index p = std::min(options.block_size, space.global_rows() - found.cols());
  if (p <= 0) {  // nothing outside span(found)
    result.verdict = BlockCheckVerdict::kNoneMissed;
    result.failure_probability = 0.0;
    return result;
  }
  result.component_scale = std::sqrt(ScaledMassFloorEstimate(space, options.scale_steps, options.seed ^ 0x5ca1e));

  std::mt19937_64 rng(options.seed ^ space.stream());
  std::normal_distribution<double> normal;
  const Eigen::VectorXd scale = space.MassDiagonal().cwiseSqrt().cwiseInverse();
  Matrix start(n, p);
  for (Index j = 0; j < p; ++j) {
    for (Index i = 0; i < n; ++i) start(i, j) = scale(i) * normal(rng);
  }
  DeflatedBlockLanczos lanczos(space, found, std::move(start));

  for (int step = 0; step < options.max_steps; ++step) {
    const bool extended = lanczos.Extend();
    result.steps = lanczos.steps();
    result.columns = lanczos.columns_solved();
    const Eigen::VectorXd& mu = lanczos.ritz_values();
    const Index below = (mu.array() > mu_cut).count();
    if (below > 0) {
      // Interlacing: at least `below` eigenvalues of the deflated problem lie below the cut.
      const Eigen::VectorXd residuals = lanczos.RitzResiduals();
      bool converged = true;
      for (Index j = 0; j < below; ++j) converged = converged && residuals(j) <= options.tolerance * mu(j);
      if (converged) {
        std::vector<Index> which(static_cast<std::size_t>(below));
        for (Index j = 0; j < below; ++j) which[static_cast<std::size_t>(j)] = j;
        result.verdict = BlockCheckVerdict::kMissed;
        result.missed_vectors = lanczos.RitzVectors(which);
        result.missed_values = (sigma + mu.head(below).array().inverse()).matrix();
        return result;
      }
      if (!extended) break;
      continue;
    }
    double bound = 0.0;
    for (int g = 0; g < kBoundGridPoints; ++g) {
      bound = std::max(bound, lanczos.HiddenComponentBound(mu_cut * std::exp2(0.25 * g)));
    }
    result.hidden_component_bound = bound;
    const double half_p = 0.5 * static_cast<double>(p);
    const double x = bound * bound / (result.component_scale * result.component_scale);
    result.failure_probability =
        x > 0.0 ? std::min(1.0, std::exp(half_p * std::log(0.5 * x) - std::lgamma(half_p + 1.0))) : 0.0;
    if (result.failure_probability <= options.failure_probability) {
      result.verdict = BlockCheckVerdict::kNoneMissed;
      return result;
    }
    if (!extended) break;
  }
  result.verdict = BlockCheckVerdict::kUndecided;
  return result;
}

BlockCheckResult CheckForMissedModes(const ShiftedFactorization& factor, const Eigen::SparseMatrix<double>& M,
                                     const Matrix& found, double cut, const BlockCheckOptions& options) {
  const MassOperator mass(M);
  return CheckForMissedModes(FactorizationSpace(factor, mass), found, cut, options);
}

}  // namespace flexmbs::eigensolvers
