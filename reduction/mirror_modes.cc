#include "reduction/mirror_modes.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <vector>

#include "core/mirror_symmetry.h"

namespace flexmbs::reduction {
namespace {

using Index = Eigen::Index;

// Whether C is diagonal with entries +-1 to kMirrorInvariance: its columns already even or odd.
bool AlreadySplit(const Eigen::MatrixXd& C) {
  Eigen::MatrixXd signs = Eigen::MatrixXd::Zero(C.rows(), C.cols());
  for (Index i = 0; i < C.rows(); ++i) signs(i, i) = C(i, i) >= 0.0 ? 1.0 : -1.0;
  return (C - signs).cwiseAbs().maxCoeff() <= kMirrorInvariance;
}

// Splits basis columns [first, first + count) (one cluster) if P maps it onto itself.
void SplitCluster(const FeModel& model, const std::vector<Index>& mirror, Index first, Index count, ReducedBasis* basis) {
  const Eigen::MatrixXd Phi_c = basis->Phi.middleCols(first, count);
  Eigen::MatrixXd C = Phi_c.transpose() * model.mass().Times(ReflectedAboutXy(mirror, Phi_c));
  C = (0.5 * (C + C.transpose())).eval();
  if (AlreadySplit(C)) return;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> reflection(C);
  if ((reflection.eigenvalues().cwiseAbs().array() - 1.0).abs().maxCoeff() > kMirrorInvariance) return;

  // Rayleigh-Ritz within the odd (eigenvalue -1, first) and the even (+1) columns.
  std::vector<double> values;
  std::vector<Eigen::VectorXd> columns;
  for (const bool even : {false, true}) {
    std::vector<Index> group;
    for (Index k = 0; k < count; ++k) {
      if ((reflection.eigenvalues()(k) > 0.0) == even) group.push_back(k);
    }
    if (group.empty()) continue;
    const Eigen::MatrixXd Psi = Phi_c * reflection.eigenvectors()(Eigen::all, group);
    Eigen::MatrixXd K_g = Psi.transpose() * model.stiffness().Times(Psi);
    K_g = (0.5 * (K_g + K_g.transpose())).eval();
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> ritz(K_g);
    const Eigen::MatrixXd rotated = Psi * ritz.eigenvectors();
    for (Index k = 0; k < rotated.cols(); ++k) {
      values.push_back(ritz.eigenvalues()(k));
      columns.push_back(rotated.col(k));
    }
  }
  std::vector<std::size_t> order(values.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return values[a] < values[b]; });

  const double residual = basis->relative_residuals.segment(first, count).norm();
  const double floor = basis->residual_floors.segment(first, count).maxCoeff();
  for (Index k = 0; k < count; ++k) {
    const std::size_t from = order[static_cast<std::size_t>(k)];
    basis->Phi.col(first + k) = columns[from];
    basis->frequency_hz(first + k) = std::sqrt(std::max(0.0, values[from])) / (2.0 * std::numbers::pi);
    basis->relative_residuals(first + k) = residual;
    basis->residual_floors(first + k) = floor;
  }
}

}  // namespace

void SplitEqualModesByMirror(const FeModel& model, ReducedBasis* basis) {
  const std::vector<Index> mirror = MirrorPointsAboutXy(model.nodes, kMirrorNodeDistance);
  if (std::find(mirror.begin(), mirror.end(), Index{-1}) != mirror.end()) return;
  const auto lambda = [&](Index j) { return std::pow(2.0 * std::numbers::pi * basis->frequency_hz(j), 2); };
  const auto normal = [&](Index j) { return basis->kinds[static_cast<std::size_t>(j)] == ModeKind::kNormal; };
  const Index n = basis->num_modes();
  for (Index first = 0; first < n;) {
    Index end = first + 1;
    if (normal(first)) {
      while (end < n && normal(end) && lambda(end) - lambda(end - 1) <= kEqualEigenvalue * std::abs(lambda(end))) ++end;
    }
    if (end - first >= 2) SplitCluster(model, mirror, first, end - first, basis);
    first = end;
  }
}

}  // namespace flexmbs::reduction
