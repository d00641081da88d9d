// A pendulum with a flexible link: reduced floating-frame models with n modes converge to the
// same formulation with the complete basis, every FE displacement of the clamped link (issue
// "must show"). What this shows is the modal truncation's convergence: the reference runs the
// same FlexibleBody and integrator, so it is no independent check of the floating-frame
// formulation itself. That is checked against independent references elsewhere: Simeon's crank
// against the IVP Test Set (simeon_crank_test), the slider-crank against a geometrically exact
// planar beam by SciPy (slider_crank_test), the rotating cantilever against Southwell's 1-D beam
// (rotating_cantilever_test), Kane's spin-up against a 1-D beam (spin_up_test).
//
// The link: steel, 1 m x 5 mm (in the plane of the swing) x 10 mm, hex20 (3 x 1 x 1 cells), its
// root face clamped in a hub (a steel disc) that turns on a horizontal revolute joint. A brake
// on the hub holds the link horizontal, a cantilever bent 20 mm by gravity; it opens over 20 ms
// and the link swings down, springing back and vibrating (first clamped mode 4.45 Hz, Euler-
// Bernoulli 4.18 Hz on this coarse mesh; the hinged link vibrates at about 19 Hz).
// tests/validation/flexible_pendulum_model.h has the set-up and why the hub is there.
//
// The complete-basis model ("full" below). The floating-frame formulation with the complete
// basis, every eigenvector of the clamped K, M (108, a dense solve), spans every FE displacement
// that keeps the root face in the hub. Its SID invariants are exact integrals of the consistent
// mass (docs/sid.md), so it is the linear-elastic FE model in the floating frame, exactly: the
// reference for the truncation. The first test
// checks it: Me = I, Ke = diag(lambda) = Phi^T K Phi, the basis spans the free DOF, and its held
// deflection is the FE static solution. The reduced models keep its first n modes
// (mbs::RestrictModes, exact for every block): the same equations without the other modes.
//
// Geometric stiffening is off (FlexibleBody(..., false)): the linear FE model has none, and the
// reduced models then differ from the reference by the truncation alone.
//
// The integrator: the L-stable ESDIRK for every model (the full model's modes reach 1.5 MHz;
// the explicit method would need steps below 1e-7 s), the same tolerances, so the errors are
// the truncation's and the CPU time ratio compares like with like. The window is 0.2 s (the
// release and four periods of the hinged vibration) to keep the full model's run near 7 s (the
// model Jacobian; 21 s with difference quotients); bench/flexible_pendulum_bench.cc runs 1 s,
// finer meshes and the explicit method.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/SparseCholesky>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "tests/fem/test_meshes.h"
#include "tests/validation/flexible_pendulum_model.h"

namespace flexmbs::validation {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

const LinkGeometry kGeometry{1.0, 5e-3, 10e-3, Eigen::Vector3i(3, 1, 1)};
constexpr Index kModes[] = {1, 2, 4, 8, 16};
constexpr double kEndTime = 0.2;  // [s]
// The ESDIRK's tolerances, for every model. Absolute 1e-8 (not lower): the iteration matrix
// I - gamma h df/dy of the full model is as ill-conditioned as (h omega_max)^2 allows, and at
// 1e-10 its Newton iteration needed a fresh Jacobian at nearly every step (measured with
// difference-quotient Jacobians).
constexpr double kRelativeTolerance = 1e-8, kAbsoluteTolerance = 1e-8;

// The complete basis is a double-precision eigensolution of the clamped problem, whose
// condition number kappa = lambda_max / lambda_1 is 1.2e11 (1.5 MHz against 4.4 Hz): its
// M-orthonormality, Phi^T K Phi against diag(lambda) (scaled by the frequencies) and the static
// solution through it hold to eps kappa = 2.6e-5 (measured 6.5e-7, 2.9e-7, 1.2e-6). None of this
// touches the model's exactness: the invariants are exact for whatever basis spans the DOF.
constexpr double kConditionRoundOffFactor = 1.0;  // x eps kappa
// The span: u = Phi Me^-1 Phi^T M u (the M-orthogonal projection onto the basis) for any u that
// is zero on the root face, to round-off: measured 1.3e-14 relative (was 1e-12).
constexpr double kSpanRoundOff = 1e-13;

// The truncation error of the tip deflection at n = 16 relative to the largest deflection of
// the swing. Measured 8.5e-6 (1.7e-7 m): the modes above 16 contribute quasi-statically only
// (above 3 kHz, against a 20-ms release), and the two runs' integration errors add about 1e-7 m
// (the same comparison at relative tolerance 1e-7 gives 2.2e-7 m).
constexpr double kTipErrorAt16 = 5e-5;
// Errors of models that differ by modes outside the swing's plane (out-of-plane bending,
// torsion: no load reaches them by symmetry) agree to the integration error: measured 1e-9 m.
constexpr double kIntegrationNoise = 1e-6;  // [m]
// The full model's energy after the release (no damping, the brake's work done), relative to
// m g x_cm: the local errors (<= the tolerance per step) over ~800 steps bound it by ~1e-5 in
// the worst case; measured 3.5e-8.
constexpr double kEnergyTolerance = 1e-6;

const FeLink& Link() {
  static const FeLink link = BuildLink(kGeometry);
  return link;
}

SwingOptions Options() {
  SwingOptions options;
  options.end_time = kEndTime;
  options.output_interval = 1e-3;
  options.integrator.method = mbs::OdeMethod::kImplicit;
  options.integrator.relative_tolerance = kRelativeTolerance;
  options.integrator.absolute_tolerance = kAbsoluteTolerance;
  return options;
}

TEST(FlexiblePendulum, CompleteBasisIsTheFeModel) {
  const FeLink& link = Link();
  const sid::ReducedBody& body = link.body;
  const Index n = body.num_modes();
  ASSERT_EQ(n, static_cast<Index>(link.free_dofs.size())) << "one mode per free DOF";
  const double kappa = link.eigenvalues.maxCoeff() / link.eigenvalues.minCoeff();
  const double round_off = kConditionRoundOffFactor * std::numeric_limits<double>::epsilon() * kappa;
  EXPECT_LE((body.Me.m0 - MatrixXd::Identity(n, n)).cwiseAbs().maxCoeff(), round_off);
  const VectorXd inverse_frequency = link.eigenvalues.cwiseSqrt().cwiseInverse();
  const MatrixXd scaled_Ke = inverse_frequency.asDiagonal() * body.Ke.m0 * inverse_frequency.asDiagonal();
  EXPECT_LE((scaled_Ke - MatrixXd::Identity(n, n)).cwiseAbs().maxCoeff(), round_off);

  // Any displacement of the free DOF is Phi (Phi^T M u): the basis spans them all.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  VectorXd u = VectorXd::Zero(link.mesh.num_dofs());
  for (const int d : link.free_dofs) u(d) = uniform(rng);
  const MatrixXd& Phi = link.basis.Phi;
  const VectorXd rebuilt = Phi * body.Me.m0.ldlt().solve(Phi.transpose() * (link.M * u));
  EXPECT_LE((rebuilt - u).cwiseAbs().maxCoeff(), kSpanRoundOff * u.cwiseAbs().maxCoeff());

  // The held deflection of the complete basis is the FE static solution K_oo u_o = f_o under
  // gravity, f = M g (g_B = R0^T g_W on every node: 9.81 m/s^2 along the link's y).
  VectorXd g_field = VectorXd::Zero(link.mesh.num_dofs());
  for (Index k = 0; k < link.mesh.num_nodes(); ++k) g_field(3 * k + 1) = 9.81;
  const VectorXd f = link.M * g_field;
  const Eigen::SparseMatrix<double> K_oo = fem::testing::Submatrix(link.K, link.free_dofs, link.free_dofs);
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> factor(K_oo);
  ASSERT_EQ(factor.info(), Eigen::Success);
  const VectorXd u_fe = factor.solve(VectorXd(f(link.free_dofs)));
  const VectorXd u_modal = (Phi * HeldDeflection(body))(link.free_dofs);
  const double largest = u_fe.cwiseAbs().maxCoeff();
  EXPECT_LE((u_modal - u_fe).cwiseAbs().maxCoeff(), round_off * largest);
  const double held_tip = body.nodes.front().phi.m0.row(1).dot(HeldDeflection(body));  // the only node: "tip"
  std::printf("[ numbers  ] complete basis: %ld modes, %.4g Hz ... %.4g Hz, kappa %.2e; |Me - I| %.1e, "
              "|Ke / lambda - I| %.1e, span %.1e, static %.1e; held tip deflection %.4f mm\n",
              static_cast<long>(n), link.basis.frequency_hz(0), link.basis.frequency_hz(n - 1), kappa,
              (body.Me.m0 - MatrixXd::Identity(n, n)).cwiseAbs().maxCoeff(),
              (scaled_Ke - MatrixXd::Identity(n, n)).cwiseAbs().maxCoeff(),
              (rebuilt - u).cwiseAbs().maxCoeff() / u.cwiseAbs().maxCoeff(),
              (u_modal - u_fe).cwiseAbs().maxCoeff() / largest, 1e3 * held_tip);
}

TEST(FlexiblePendulum, ReducedSwingsConvergeToTheCompleteBasisModel) {
  const FeLink& link = Link();
  const SwingOptions options = Options();
  const Swing full = RunSwing(link.body, options);
  const double largest = LargestTipDeflection(full);
  const double energy_drift = EnergyDriftAfterRelease(full, options.release_time) / SwingEnergyScale(link.body);
  std::printf("[ numbers  ] full model (%ld modes): %ld steps, %.2f s CPU; largest tip deflection %.3f mm; energy "
              "after the release constant to %.1e of m g x_cm\n",
              static_cast<long>(link.body.num_modes()), full.steps, full.cpu_seconds, 1e3 * largest, energy_drift);
  EXPECT_LE(energy_drift, kEnergyTolerance);

  std::printf("[ numbers  ]   n | max tip error [m] | relative | max hinge angle error [rad] | CPU [s] | speed-up\n");
  std::vector<SwingDeviation> errors;
  for (const Index n : kModes) {
    const Swing reduced = RunSwing(FirstModes(link.body, n), options);
    errors.push_back(Deviation(reduced, full));
    std::printf("[ numbers  ] %3ld | %17.3e | %8.2e | %27.3e | %7.3f | %8.1f\n", static_cast<long>(n),
                errors.back().tip_deflection, errors.back().tip_deflection / largest, errors.back().hinge_angle,
                reduced.cpu_seconds, full.cpu_seconds / reduced.cpu_seconds);
  }

  // The error falls with every mode in the swing's plane and stays where the added modes are
  // out of it (gravity's modal force Ct_j g_B is zero for them).
  const Eigen::Vector3d g_B(0.0, 9.81, 0.0);
  const VectorXd modal_gravity = link.body.Ct.m0 * g_B;
  for (std::size_t k = 1; k < errors.size(); ++k) {
    const Index from = kModes[k - 1], to = kModes[k];
    const bool in_plane = modal_gravity.segment(from, to - from).cwiseAbs().maxCoeff() > 1e-6 * modal_gravity.cwiseAbs().maxCoeff();
    if (in_plane) {
      EXPECT_LT(errors[k].tip_deflection, errors[k - 1].tip_deflection) << "n " << to;
      EXPECT_LT(errors[k].hinge_angle, errors[k - 1].hinge_angle) << "n " << to;
    } else {
      EXPECT_NEAR(errors[k].tip_deflection, errors[k - 1].tip_deflection, kIntegrationNoise) << "n " << to;
    }
  }
  EXPECT_LE(errors.back().tip_deflection, kTipErrorAt16 * largest);
}

}  // namespace
}  // namespace flexmbs::validation
