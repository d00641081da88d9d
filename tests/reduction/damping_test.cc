// The reduced damping matrix: modal ratios and Rayleigh damping.
#include "reduction/damping.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "basis_test_support.h"
#include "reduction/craig_bampton.h"
#include "tests/input_error.h"

namespace flexmbs::reduction {
namespace {

using fem::ElementType;

// De of an M-orthonormal modal basis against diag(2 zeta omega): round-off of Me V (V = I up to
// the eigensolver's round-off on a diagonal pair), relative to the largest entry.
constexpr double kModalRoundOff = 1e-10;
// Damping ratios recovered from the eigenvalues of the 2n first-order system (Eigen's
// non-symmetric QR algorithm): error ~ eps ||A|| / omega_k with ||A|| ~ omega_max^2 of the
// reduced system; for the clamped Craig-Bampton beam (omega 1.1e3 .. 8.5e4 rad/s) that is
// ~1.5e-9 (measured 4.8e-10).
constexpr double kRatioError = 1e-8;
// A rigid vector of the reduced system times De against |De| |v|: round-off.
constexpr double kRigidRoundOff = 1e-10;

const fem::IsotropicMaterial kSteel = testing::Steel();

testing::Body Beam() {
  return testing::MakeBox(ElementType::kHex8, {6, 1, 1}, {0.6, 0.05, 0.04}, kSteel);
}

DampingSpec Modal(double ratio) {
  DampingSpec d;
  d.kind = DampingKind::kModal;
  d.modal_ratio = ratio;
  return d;
}

DampingSpec PerMode(std::vector<double> ratios) {
  DampingSpec d;
  d.kind = DampingKind::kModal;
  d.modal_ratios = std::move(ratios);
  return d;
}

// The damped modes of M q'' + D q' + K q = 0: eigenvalues s of the first-order system
// [q; q']' = [0, I; -M^-1 K, -M^-1 D] [q; q'], one per conjugate pair (Im s > 0), by |s|.
// For an underdamped mode, s = omega (-zeta + i sqrt(1 - zeta^2)): omega = |s|,
// zeta = -Re(s) / |s|. The system is solved in the balanced form [q; q' / c] with
// c = ||M^-1 K||^(1/2) (a similarity: the same s): unbalanced, its norm omega_max^2 made the
// lowest |s| accurate only to ~1e-8 on the Craig-Bampton beam (omega 1.1e3 .. 8.5e4 rad/s).
struct DampedMode {
  double omega;
  double zeta;
};
std::vector<DampedMode> DampedModes(const Eigen::MatrixXd& M, const Eigen::MatrixXd& D,
                                    const Eigen::MatrixXd& K) {
  const Eigen::Index n = M.rows();
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(M);
  const Eigen::MatrixXd M_inv_K = lu.solve(K);
  const double c = std::sqrt(M_inv_K.cwiseAbs().rowwise().sum().maxCoeff());
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  A.topRightCorner(n, n) = c * Eigen::MatrixXd::Identity(n, n);
  A.bottomLeftCorner(n, n) = -M_inv_K / c;
  A.bottomRightCorner(n, n) = -lu.solve(D);
  const Eigen::EigenSolver<Eigen::MatrixXd> eigen(A, false);
  std::vector<DampedMode> modes;
  for (const std::complex<double>& s : eigen.eigenvalues()) {
    if (s.imag() > 0.0) modes.push_back({std::abs(s), -s.real() / std::abs(s)});
  }
  std::sort(modes.begin(), modes.end(),
            [](const DampedMode& a, const DampedMode& b) { return a.omega < b.omega; });
  return modes;
}

// Undamped circular frequencies of the reduced pair, ascending (independent dense solve).
Eigen::VectorXd Omegas(const ReducedBasis& basis) {
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eigen(basis.K_reduced,
                                                                        basis.M_reduced);
  return eigen.eigenvalues().cwiseMax(0.0).cwiseSqrt();
}

ReducedBasis ClampedCraigBampton(const testing::Body& b) {
  BoundaryConditions conditions;
  conditions.supports.push_back({"clamp", testing::NodesAt(b.mesh, 0, 0.0)});
  conditions.interfaces.push_back(
      {"tip", testing::NodesAt(b.mesh, 0, 0.6), Coupling::kRigid, std::nullopt, {}});
  eigensolvers::EigenOptions eigen;
  eigen.num_modes = 5;
  return CraigBamptonBasis(b.model(), conditions, eigen, testing::Spectra());
}

TEST(Damping, ModalRatiosOnAnOrthonormalModalBasisGiveTwoZetaOmegaOnTheDiagonal) {
  const testing::Body b = Beam();
  FreeFreeOptions options;
  options.eigen.num_modes = 6;
  const ReducedBasis modal = FreeFreeModalBasis(b.model(), options, testing::Spectra());
  ASSERT_EQ(modal.num_modes(), 12);
  const std::vector<double> ratios = {0.01, 0.02, 0.015, 0.05, 0.03, 0.001};
  for (const DampingSpec& spec : {Modal(0.02), PerMode(ratios)}) {
    const ReducedDamping damping = DampingMatrix(spec, b.model(), modal);
    Eigen::VectorXd expected = Eigen::VectorXd::Zero(12);  // rigid-body modes: no damping
    for (Eigen::Index k = 6; k < 12; ++k) {
      const double zeta =
          spec.modal_ratios.empty() ? spec.modal_ratio : ratios[static_cast<std::size_t>(k - 6)];
      expected(k) = 2.0 * zeta * 2.0 * std::numbers::pi * modal.frequency_hz(k);
    }
    const double error =
        (damping.De - Eigen::MatrixXd(expected.asDiagonal())).cwiseAbs().maxCoeff();
    EXPECT_LT(error, kModalRoundOff * expected.maxCoeff());
    std::printf("modal basis, %s: max |De - diag(2 zeta omega)| / max = %.2e\n",
                damping.description.c_str(), error / expected.maxCoeff());
  }
  EXPECT_EQ(DampingMatrix(Modal(0.02), b.model(), modal).description, "modal 2 %");
  EXPECT_EQ(DampingMatrix(PerMode(ratios), b.model(), modal).description,
            "modal 0.1 % .. 5 % (per elastic mode)");
  EXPECT_EQ(flexmbs::testing::InputErrorMessage([&] {
              DampingMatrix(PerMode({0.01, 0.02}), b.model(), modal);
            }),
            "sid.damping: 2 damping ratios for 6 elastic modes of the reduced system");
}

TEST(Damping, ModalRatiosOnACraigBamptonBasisDampEachReducedModeByItsRatio) {
  const testing::Body b = Beam();
  const ReducedBasis cb = ClampedCraigBampton(b);
  const Eigen::Index n = cb.num_modes();
  ASSERT_EQ(n, 11);  // 6 constraint + 5 normal modes, held by the clamp: no rigid-body mode
  std::vector<double> ratios;
  for (Eigen::Index k = 0; k < n; ++k) ratios.push_back(0.005 * static_cast<double>(k + 1));
  const ReducedDamping damping = DampingMatrix(PerMode(ratios), b.model(), cb);
  EXPECT_LT((damping.De - damping.De.transpose()).cwiseAbs().maxCoeff(),
            1e-14 * damping.De.cwiseAbs().maxCoeff());

  const std::vector<DampedMode> modes = DampedModes(cb.M_reduced, damping.De, cb.K_reduced);
  const Eigen::VectorXd omega = Omegas(cb);
  ASSERT_EQ(modes.size(), static_cast<std::size_t>(n));
  double worst = 0.0;
  double worst_omega = 0.0;
  for (Eigen::Index k = 0; k < n; ++k) {
    const DampedMode& m = modes[static_cast<std::size_t>(k)];
    EXPECT_NEAR(m.zeta, ratios[static_cast<std::size_t>(k)], kRatioError) << "mode " << k;
    EXPECT_NEAR(m.omega, omega(k), kRatioError * omega(k)) << "mode " << k;
    worst = std::max(worst, std::abs(m.zeta - ratios[static_cast<std::size_t>(k)]));
    worst_omega = std::max(worst_omega, std::abs(m.omega / omega(k) - 1.0));
  }
  std::printf("Craig-Bampton: largest damping ratio error %.2e, relative omega error %.2e, omega %.3g .. %.3g "
              "rad/s\n",
              worst, worst_omega, omega(0), omega(n - 1));
}

TEST(Damping, RigidBodyModesOfAFreeCraigBamptonBasisAreNotDamped) {
  const testing::Body b = Beam();
  BoundaryConditions conditions;  // one rigid interface, otherwise free: six rigid-body modes
  conditions.interfaces.push_back(
      {"root", testing::NodesAt(b.mesh, 0, 0.0), Coupling::kRigid, std::nullopt, {}});
  eigensolvers::EigenOptions eigen;
  eigen.num_modes = 4;
  const ReducedBasis cb = CraigBamptonBasis(b.model(), conditions, eigen, testing::Spectra());
  ASSERT_EQ(cb.num_modes(), 10);
  // The ratio count is that of the elastic modes: 10 - 6.
  EXPECT_EQ(flexmbs::testing::InputErrorMessage(
                [&] { DampingMatrix(PerMode(std::vector<double>(10, 0.02)), b.model(), cb); }),
            "sid.damping: 10 damping ratios for 4 elastic modes of the reduced system");
  const std::vector<double> ratios = {0.01, 0.02, 0.03, 0.04};
  const ReducedDamping damping = DampingMatrix(PerMode(ratios), b.model(), cb);
  // The constraint modes of the rigid interface are rigid motions: De annihilates them.
  const Eigen::MatrixXd rigid = cb.Phi.leftCols<6>();
  ASSERT_LT((b.K * rigid).norm(), 1e-6 * (b.K.cwiseAbs() * rigid.cwiseAbs()).norm());
  const Eigen::MatrixXd De_rigid = damping.De.leftCols<6>();
  EXPECT_LT(De_rigid.norm(), kRigidRoundOff * damping.De.norm());
  // The elastic modes have their ratios.
  const std::vector<DampedMode> modes = DampedModes(cb.M_reduced, damping.De, cb.K_reduced);
  const Eigen::VectorXd omega = Omegas(cb);
  std::vector<DampedMode> elastic;
  for (const DampedMode& m : modes) {
    if (m.omega > 1e-3 * omega(6)) elastic.push_back(m);
  }
  ASSERT_EQ(elastic.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_NEAR(elastic[k].zeta, ratios[k], kRatioError) << "mode " << k;
    EXPECT_NEAR(elastic[k].omega, omega(6 + static_cast<Eigen::Index>(k)), kRatioError * omega(6))
        << "mode " << k;
  }
}

TEST(Damping, RayleighIsAMePlusBKeWithRatiosAOverTwoOmegaPlusBOmegaOverTwo) {
  const testing::Body b = Beam();
  const ReducedBasis cb = ClampedCraigBampton(b);
  DampingSpec spec;
  spec.kind = DampingKind::kRayleigh;
  spec.rayleigh_mass_per_s = 30.0;
  spec.rayleigh_stiffness_s = 2e-6;
  const ReducedDamping damping = DampingMatrix(spec, b.model(), cb);
  EXPECT_EQ(damping.description, "Rayleigh a = 30 1/s, b = 2e-06 s");
  const Eigen::MatrixXd expected = 30.0 * cb.M_reduced + 2e-6 * cb.K_reduced;
  EXPECT_LT((damping.De - expected).cwiseAbs().maxCoeff(), 1e-15 * expected.cwiseAbs().maxCoeff());
  const std::vector<DampedMode> modes = DampedModes(cb.M_reduced, damping.De, cb.K_reduced);
  const Eigen::VectorXd omega = Omegas(cb);
  ASSERT_EQ(modes.size(),
            static_cast<std::size_t>(cb.num_modes()));  // all underdamped at these a, b
  for (std::size_t k = 0; k < modes.size(); ++k) {
    const double w = omega(static_cast<Eigen::Index>(k));
    EXPECT_NEAR(modes[k].zeta, 30.0 / (2.0 * w) + 2e-6 * w / 2.0, kRatioError) << "mode " << k;
  }
}

TEST(Damping, NoneIsZero) {
  const testing::Body b = Beam();
  const ReducedBasis cb = ClampedCraigBampton(b);
  const ReducedDamping damping = DampingMatrix(DampingSpec{}, b.model(), cb);
  EXPECT_EQ(damping.description, "none");
  EXPECT_EQ(damping.De, Eigen::MatrixXd::Zero(cb.num_modes(), cb.num_modes()));
}

}  // namespace
}  // namespace flexmbs::reduction
