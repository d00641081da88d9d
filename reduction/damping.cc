#include "reduction/damping.h"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "reduction/basis_algebra.h"
#include "eigensolvers/eigensolver.h"

namespace flexmbs::reduction {
namespace {

using Index = Eigen::Index;

std::string Percent(double ratio) { return fmt::format("{:g} %", 100.0 * ratio); }

ReducedDamping ModalDamping(const DampingSpec& damping, const FeModel& model,
                            const ReducedBasis& basis) {
  const Index n = basis.num_modes();
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eigen(
      basis.K_reduced, basis.M_reduced, Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
  FLEXMBS_CHECK(eigen.info() == Eigen::Success, "the reduced mass matrix is positive definite");
  const double zero = eigensolvers::kZeroEigenvalue * model.stiffness().Diagonal().sum() / model.mass().Diagonal().sum();
  const Eigen::VectorXd& lambda = eigen.eigenvalues();  // ascending
  const Index num_rigid =
      std::count_if(lambda.begin(), lambda.end(), [&](double l) { return l <= zero; });
  CheckModalRatioCount(damping, n - num_rigid);

  Eigen::VectorXd c = Eigen::VectorXd::Zero(n);  // 2 zeta_k omega_k
  for (Index k = num_rigid; k < n; ++k) {
    const Index elastic = k - num_rigid;
    const double zeta = damping.modal_ratios.empty()
                            ? damping.modal_ratio
                            : damping.modal_ratios[static_cast<std::size_t>(elastic)];
    c(k) = 2.0 * zeta * std::sqrt(lambda(k));
  }
  const Eigen::MatrixXd MV = basis.M_reduced * eigen.eigenvectors();
  ReducedDamping result;
  result.De = Symmetrized(MV * c.asDiagonal() * MV.transpose());
  if (damping.modal_ratios.empty()) {
    result.description = "modal " + Percent(damping.modal_ratio);
  } else {
    const auto [low, high] =
        std::minmax_element(damping.modal_ratios.begin(), damping.modal_ratios.end());
    result.description =
        fmt::format("modal {} .. {} (per elastic mode)", Percent(*low), Percent(*high));
  }
  return result;
}

}  // namespace

ReducedDamping DampingMatrix(const DampingSpec& damping, const FeModel& model,
                             const ReducedBasis& basis) {
  const Index n = basis.num_modes();
  FLEXMBS_CHECK(basis.K_reduced.rows() == n && basis.K_reduced.cols() == n &&
                    basis.M_reduced.rows() == n && basis.M_reduced.cols() == n,
                "reduced matrices of the basis's size");
  switch (damping.kind) {
    case DampingKind::kNone:
      return {Eigen::MatrixXd::Zero(n, n), "none"};
    case DampingKind::kRayleigh:
      return {damping.rayleigh_mass_per_s * basis.M_reduced +
                  damping.rayleigh_stiffness_s * basis.K_reduced,
              fmt::format("Rayleigh a = {:g} 1/s, b = {:g} s", damping.rayleigh_mass_per_s,
                          damping.rayleigh_stiffness_s)};
    case DampingKind::kModal:
      return ModalDamping(damping, model, basis);
  }
  FLEXMBS_CHECK(false, "every damping kind is handled");
  return {};
}

}  // namespace flexmbs::reduction
