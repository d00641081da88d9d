// Geometric stiffening in the multibody equations (docs/mbs.md, "Geometric stiffening"): the
// mass matrix stays the kinematic one, positive definite where the symmetric placement of the
// K0t, K0r terms in M is not; the stiffening by the frame's acceleration enters by one corrector
// step of MultibodySystem::Accelerations, whose error is of second order against the exact
// solution of the non-symmetric system (assembled here from the K0 matrices of the SID data,
// not through the body); the rigid rows keep momentum; point loads at nodes stiffen the body
// through MultibodySystem::AddMarkerLoad. Body: the clamped Craig-Bampton steel beam of
// flexible_test_bodies.h (0.6 m, stiffening computed).

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <memory>
#include <random>
#include <utility>
#include <vector>

#include "core/rotation.h"
#include "mbs/flexible_body.h"
#include "mbs/force_element.h"
#include "mbs/joint.h"
#include "mbs/mode_selection.h"
#include "mbs/multibody_system.h"
#include "mbs/simulation.h"
#include "tests/mbs/flexible_test_bodies.h"

namespace flexmbs::mbs {
namespace {

using Eigen::Index;
using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;

const testing::FeReducedBody& Beam() { return testing::CraigBamptonBeam(); }
const double kLength = testing::kBeamSize.x();

// Two evaluations of the same quantities in another order (dense solves of 19 unknowns with
// entries from 1e-3 to 1e2: kg, kg m, kg m^2, modal masses): a few hundred ulps of the largest
// term. Measured: at most 3.2e-13 relative (the point load's virtual work; the iterated
// corrector 1.7e-13 at 1e-4 L). Was 1e-11.
constexpr double kRoundOff = 3e-12;
// Free floating with the explicit method at relative tolerance 1e-11: P and L drift by the
// global error projected on them (flexible_motion_test.cc: 3e-13 and 1.3e-12 over 1e5 steps at
// 1e-12; measured here 1.5e-13 over 1.4e4 steps); 1e-9 bounds it with room. (K0t, K0r placed in
// the rigid rows too, the former formulation, drift by 30 % in the same run from 1e-3 L.)
constexpr double kIntegratorTolerance = 1e-11;
// The orders of the corrector's errors in q are read from the decade 1e-5 L .. 1e-4 L of
// deformation, where the leading terms (A N) u'* and (A N)^2 u'* dominate (the next order, and
// u'*'s own dependence on q, are ~|A N| ~ 0.005 of them at 1e-4 L): log10 of the ratios is
// within 0.02 of 1 and 2 (measured 1.004 and 2.003, was 0.05; from 1e-4 L to 1e-3 L, where
// |A N| ~ 0.07, 1.14 and 2.2).
constexpr double kOrderTolerance = 0.02;
// |u'_1 - u'*| = |(A N) (u'_0 - u'*)|: below |u'_0 - u'*| by the loop gain of A N, the
// elastic rotations' order (measured 0.07 at 1e-3 L on this beam); asserted below 0.2.
constexpr double kLoopGainBound = 0.2;
// P's drift in the two floating runs: measured 1.2e-13 and 7.8e-15 relative (was 1e-9).
constexpr double kMomentumTolerance = 1e-12;
constexpr double kFloatingTime = 2e-3;  // [s]
constexpr double kMomentSampling = 1e-6;  // [s], ~7 steps of the floating run
constexpr double kSpin = 1000.0;          // [rad/s]
// The kinematic angular momentum must change by more than 10 times the total's drift for the
// gyroscopic torque to be shown at work (measured 4e4 times).
constexpr double kTorqueAtWork = 10.0;

std::vector<Index> Elastic() { return testing::ElasticColumns(Beam().basis); }

std::unique_ptr<FlexibleBody> MakeBeam(bool stiffening) {
  return std::make_unique<FlexibleBody>("beam", RestrictModes(Beam().body, Elastic()), stiffening);
}

// A state: pose anywhere, v ~ 1 m/s, w ~ 10 rad/s, q with largest nodal displacement
// `deformation` [m], qdot with nodal elastic velocities ~ 1 m/s.
struct State {
  VectorXd x, u;
};
State RandomState(unsigned seed, double deformation) {
  const MatrixXd Phi = Beam().basis.Phi(Eigen::all, Elastic());
  const Index n = Phi.cols();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const auto random = [&](Index size) { return VectorXd(VectorXd::NullaryExpr(size, [&] { return uniform(rng); })); };
  const auto largest = [&](const VectorXd& q) {
    return Eigen::Map<const Eigen::Matrix3Xd>(VectorXd(Phi * q).data(), 3, Phi.rows() / 3).colwise().norm().maxCoeff();
  };
  VectorXd q = random(n), qdot = random(n);
  q *= deformation / largest(q);
  qdot /= largest(qdot);
  State s{VectorXd(7 + n), VectorXd(6 + n)};
  s.x << random(3), random(4).normalized(), q;
  s.u << random(3), 10.0 * random(3), qdot;
  return s;
}

// N(x) with h_a = -N u': the elastic row's [dCt R^T, dCr, 0], dCt = [K0t_a q]_a, dCr = [K0r_a q]_a,
// from the SID data's stiffening matrices.
MatrixXd StiffeningMatrix(const VectorXd& x) {
  const std::vector<Index> keep = Elastic();
  const Index n = static_cast<Index>(keep.size());
  const sid::GeometricStiffening& K0 = Beam().body.stiffening;
  const VectorXd q = x.tail(n);
  const Matrix3d R = RotationFromEulerParameters(x.segment<4>(3));
  Eigen::MatrixX3d dCt(n, 3), dCr(n, 3);
  for (std::size_t a = 0; a < 3; ++a) {
    dCt.col(static_cast<Index>(a)) = K0.K0t[a](keep, keep) * q;
    dCr.col(static_cast<Index>(a)) = K0.K0r[a](keep, keep) * q;
  }
  MatrixXd N = MatrixXd::Zero(6 + n, 6 + n);
  N.block(6, 0, n, 3) = dCt * R.transpose();
  N.block(6, 3, n, 3) = dCr;
  return N;
}

double SmallestEigenvalue(const MatrixXd& M) { return Eigen::SelfAdjointEigenSolver<MatrixXd>(M).eigenvalues()(0); }

// The mass matrix with stiffening on is the kinematic one, positive definite at any deformation.
// Adding the K0t, K0r terms of the elastic row symmetrically (the former formulation: dCt R^T and
// dCr in the elastic row and their transposes in the rigid rows) makes it indefinite between
// 1e-3 L and 1e-2 L (0.6 and 6 mm) of deformation on this 0.6 m steel beam.
TEST(StiffeningForces, MassMatrixStaysKinematicAndPositiveDefinite) {
  const std::unique_ptr<FlexibleBody> stiff = MakeBeam(true), plain = MakeBeam(false);
  const Index n_u = stiff->num_velocities();
  bool symmetric_placement_indefinite = false;
  for (const double fraction : {1e-4, 1e-3, 1e-2, 5e-2}) {
    const State s = RandomState(3, fraction * kLength);
    MatrixXd M(n_u, n_u), M_plain(n_u, n_u);
    stiff->MassMatrix(s.x, M);
    plain->MassMatrix(s.x, M_plain);
    EXPECT_EQ(M, M_plain);
    const double smallest = SmallestEigenvalue(M);
    EXPECT_GT(smallest, 0.0) << "deformation " << fraction << " L";
    const MatrixXd N = StiffeningMatrix(s.x);
    const double smallest_symmetric = SmallestEigenvalue(M + N + N.transpose());
    symmetric_placement_indefinite = symmetric_placement_indefinite || smallest_symmetric < 0.0;
    std::cout << "deformation " << fraction << " L: smallest eigenvalue of M " << smallest
              << ", with K0t, K0r placed symmetrically " << smallest_symmetric << "\n";
  }
  EXPECT_TRUE(symmetric_placement_indefinite) << "the reason for keeping M kinematic";
}

// The system of the corrector tests: the beam (stiffening on, without Ke and De so that u' does
// not grow with q and the errors' orders in q show directly) under gravity, spinning, its tip
// held by a spherical joint to the ground (so the Schur complement takes part), no Baumgarte
// terms.
struct PinnedBeam {
  MultibodySystem system{Vector3d(1.0, -2.0, -9.81)};
  PinnedBeam() {
    sid::ReducedBody data = RestrictModes(Beam().body, Elastic());
    data.Ke.m0.setZero();
    data.De.m0.setZero();
    system.AddBody(std::make_unique<FlexibleBody>("beam", std::move(data), true));
    system.AddJoint(Joint("pin", JointType::kSpherical, MarkerRef::Ground(Vector3d(0.2, 0.1, -0.3)),
                          system.Marker("beam", "tip")));
  }
};

// Dense solve of [M, G^T; G, 0] [u'; lambda] = [rhs; target] (M may be non-symmetric).
MatrixXd SolveSaddle(const MatrixXd& M, const MatrixXd& G, const MatrixXd& rhs, const MatrixXd& target) {
  const Index n_u = M.rows(), m = G.rows();
  MatrixXd K = MatrixXd::Zero(n_u + m, n_u + m);
  K.topLeftCorner(n_u, n_u) = M;
  K.topRightCorner(n_u, m) = G.transpose();
  K.bottomLeftCorner(m, n_u) = G;
  MatrixXd b(n_u + m, rhs.cols());
  b.topRows(n_u) = rhs;
  b.bottomRows(m) = target;
  return Eigen::FullPivLU<MatrixXd>(K).solve(b).topRows(n_u);
}

// The relative errors of u'_0 (no acceleration-dependent forces) and of the corrected u'_1
// (MultibodySystem::Accelerations) against u'* of the exact (M + N) u' = h + G^T lambda.
struct CorrectorErrors {
  double uncorrected = 0.0, corrected = 0.0, fixed_point = 0.0;
};
CorrectorErrors Errors(double deformation) {
  const PinnedBeam pinned;
  const MultibodySystem& system = pinned.system;
  const State s = RandomState(7, deformation);
  VectorXd y = system.NeutralState();
  system.SetBodyState(0, s.x, s.u, y);
  VectorXd u_dot(system.num_velocities()), lambda(system.num_constraints());
  system.Accelerations(0.0, y, u_dot, lambda);

  const MatrixXd M = system.BodyMassMatrix(0, y), N = StiffeningMatrix(s.x);
  const VectorXd h = system.Forces(0.0, y);
  const SystemConstraints c = system.Constraints(0.0, y);
  const VectorXd exact = SolveSaddle(M + N, c.G, h, c.gamma);
  const VectorXd first = SolveSaddle(M, c.G, h, c.gamma);
  // The corrector iterated to its fixed point through the bodies' seam.
  VectorXd iterate = first;
  for (int k = 0; k < 20; ++k) {
    VectorXd h_a(system.num_velocities());
    EXPECT_TRUE(system.AccelerationDependentForces(y, iterate, h_a));
    iterate = SolveSaddle(M, c.G, h + h_a, c.gamma);
  }
  const double scale = exact.norm();
  return {(first - exact).norm() / scale, (u_dot - exact).norm() / scale, (iterate - exact).norm() / scale};
}

// With A the constrained solution operator and h_a = -N u', the exact u'* solves
// (M + N) u' = h + G^T lambda; the uncorrected u'_0 = u'* + (A N) u'* and the corrected
// u'_1 = u'* - (A N)^2 u'*. N grows with q, so the errors are of first and second order in q:
// ten times the deformation gives ten and a hundred times the errors, and at the largest
// deformation the corrected error is below the uncorrected one by |A N|. The corrector
// iterated to convergence gives u'*.
TEST(StiffeningForces, OneCorrectorStepLeavesAnErrorOfSecondOrderInTheDeformation) {
  const CorrectorErrors small = Errors(1e-5 * kLength), medium = Errors(1e-4 * kLength), large = Errors(1e-3 * kLength);
  for (const auto& [name, e] : {std::pair{"1e-5", small}, std::pair{"1e-4", medium}, std::pair{"1e-3", large}}) {
    std::cout << "deformation " << name << " L: relative error of u' uncorrected " << e.uncorrected << ", corrected "
              << e.corrected << ", iterated to the fixed point " << e.fixed_point << "\n";
    EXPECT_LT(e.fixed_point, kRoundOff) << name;
  }
  EXPECT_GT(small.corrected, 1e3 * kRoundOff) << "the errors must stand above round-off";
  EXPECT_NEAR(std::log10(medium.uncorrected / small.uncorrected), 1.0, kOrderTolerance);
  EXPECT_NEAR(std::log10(medium.corrected / small.corrected), 2.0, kOrderTolerance);
  EXPECT_LT(large.corrected, large.uncorrected * kLoopGainBound);
}

// Free floating with stiffening on (the acceleration-dependent forces of K0t, K0r act at every
// evaluation: the clamped basis's K0t, K0r do not vanish), from a state deformed by 1e-4 L with
// nodal elastic velocities of 1 m/s, for about 1.4e4 steps (the steel beam's stiffest modes set
// the step). The translational row is the kinematic momentum balance, so P stays. The
// rotational row adds the centrifugal stiffening's gyroscopic torque -(dJ' w + w x dJ w) and
// leaves out its acceleration partner -dJ alpha (mbs/stiffening_inertia.h), so
// L = L_kin + R dJ w changes at the rate R dJ alpha: its drift is bounded by the run's time
// times the largest |dJ alpha| (sampled every 1e-6 s, ~7 steps, with a factor 2 for the peaks
// between samples). Measured: 1.4e-7, 6.5e-3 of that bound (this body hardly spins: the
// spinning test below is the sharp one).
TEST(StiffeningForces, FreeFloatingBodyKeepsMomentumWithStiffeningOn) {
  sid::ReducedBody data = RestrictModes(Beam().body, Elastic());
  data.De.m0.setZero();
  const sid::GeometricStiffening K0 = data.stiffening;
  MultibodySystem system(Vector3d::Zero());
  system.AddBody(std::make_unique<FlexibleBody>("beam", std::move(data), true));
  const auto& body = dynamic_cast<const FlexibleBody&>(system.body(0));
  const State s = RandomState(11, 1e-4 * kLength);
  VectorXd y0 = system.NeutralState();
  system.SetBodyState(0, s.x, s.u, y0);
  const Momentum start = body.ComputeMomentum(s.x, s.u);

  SimulationOptions options;
  options.integrator.relative_tolerance = kIntegratorTolerance;
  options.integrator.absolute_tolerance = 1e-2 * kIntegratorTolerance;
  options.end_time = kFloatingTime;
  options.output_interval = kMomentSampling;
  double P_drift = 0.0, L_drift = 0.0, largest_stiffening = 0.0, largest_left_out = 0.0;
  const auto output = [&](double, const VectorXd& y, const VectorXd&) {
    const VectorXd x = system.BodyPositions(y, 0), u = system.BodyVelocities(y, 0);
    const Momentum now = body.ComputeMomentum(x, u);
    P_drift = std::max(P_drift, (now.linear_W - start.linear_W).norm() / start.linear_W.norm());
    L_drift = std::max(L_drift, (now.angular_Wo_W - start.angular_Wo_W).norm() / start.angular_Wo_W.norm());
    VectorXd u_dot(system.num_velocities()), lambda(0), h_a(system.num_velocities());
    system.Accelerations(0.0, y, u_dot, lambda);
    system.AccelerationDependentForces(y, u_dot, h_a);
    VectorXd h = system.Forces(0.0, y);
    largest_stiffening = std::max(largest_stiffening, h_a.norm() / h.norm());
    const Matrix3d dJ = testing::CentrifugalInertiaChange(K0, x.tail(x.size() - 7), x.tail(x.size() - 7));
    largest_left_out = std::max(largest_left_out, (dJ * u_dot.segment<3>(3)).norm());
  };
  const SimulationStatistics stats = Simulate(system, options, y0, output);
  const double L_bound = 2.0 * kFloatingTime * largest_left_out / start.angular_Wo_W.norm();
  std::cout << stats.integrator.steps << " steps; drift P " << P_drift << ", L " << L_drift << " (bound " << L_bound
            << "); largest |h_a| / |h| " << largest_stiffening << "\n";
  EXPECT_GT(largest_stiffening, 1e-8) << "the run must exercise the acceleration-dependent forces";
  EXPECT_LT(P_drift, kMomentumTolerance);
  EXPECT_LT(L_drift, L_bound);
}

// A free-free steel beam spinning at 1000 rad/s about its short axis z (centrifugal tension
// ~350 MPa at the root: stiffening of the bending modes by ~2 %) and vibrating (deformation
// 1e-3 L, nodal elastic velocities ~1 m/s): inertia relief makes K0t, K0r vanish, so the
// stiffening is the centrifugal K0omega alone and the left-out term is dJ alpha. With the
// gyroscopic torque the total angular momentum L = L_kin + R dJ w and the energy
// E = T_kin + w^T dJ w / 2 + V change only at the rates R dJ alpha and w . dJ alpha: each drift
// is bounded by the run's time times the largest sampled rate (factor 2 as above). The
// kinematic L_kin alone changes by the gyroscopic torque's impulse: far more (measured 4e4
// times) than L, so the torque is at work and the sum is what the body keeps. Measured (2800
// steps): L drifts by 1.5e-11 of L (bound 4.0e-10), E by 4.0e-12 of E (bound 1.5e-10), P as
// the integrator's error. (The spin is about Bo, the beam's end: P = m w x c, not zero.)
TEST(StiffeningForces, SpinningFreeBodyKeepsTheStiffeningFieldsMomentumAndEnergy) {
  const testing::FeReducedBody& fe = testing::FreeFreeBeam();
  const std::vector<Index> elastic = testing::ElasticColumns(fe.basis);
  sid::ReducedBody data = RestrictModes(fe.body, elastic);
  data.De.m0.setZero();
  const sid::GeometricStiffening K0 = data.stiffening;
  MultibodySystem system(Vector3d::Zero());
  system.AddBody(std::make_unique<FlexibleBody>("beam", std::move(data), true));
  const auto& body = dynamic_cast<const FlexibleBody&>(system.body(0));
  const Index n = static_cast<Index>(elastic.size());
  const MatrixXd Phi = fe.basis.Phi(Eigen::all, elastic);
  const auto largest = [&](const VectorXd& q) {
    return Eigen::Map<const Eigen::Matrix3Xd>(VectorXd(Phi * q).data(), 3, Phi.rows() / 3).colwise().norm().maxCoeff();
  };
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  VectorXd q = VectorXd::NullaryExpr(n, [&] { return uniform(rng); });
  VectorXd qdot = VectorXd::NullaryExpr(n, [&] { return uniform(rng); });
  q *= 1e-3 * kLength / largest(q);
  qdot /= largest(qdot);
  VectorXd x(7 + n), u(6 + n);
  x << Vector3d::Zero(), 1.0, 0.0, 0.0, 0.0, q;
  u << Vector3d::Zero(), 0.0, 0.0, kSpin, qdot;
  VectorXd y0 = system.NeutralState();
  system.SetBodyState(0, x, u, y0);
  const auto L_kinematic = [&](const VectorXd& x_b, const VectorXd& u_b) {
    const VectorXd q_b = x_b.tail(n);
    const Matrix3d dJ = testing::CentrifugalInertiaChange(K0, q_b, q_b);
    return Vector3d(body.ComputeMomentum(x_b, u_b).angular_Wo_W -
                    RotationFromEulerParameters(x_b.segment<4>(3)) * (dJ * u_b.segment<3>(3)));
  };
  const auto energy = [&](const VectorXd& x_b, const VectorXd& u_b) {
    return body.KineticEnergy(x_b, u_b) + body.PotentialEnergy(x_b, Vector3d::Zero());
  };
  const Momentum start = body.ComputeMomentum(x, u);
  const Vector3d L_kin_start = L_kinematic(x, u);
  const double E_start = energy(x, u);

  SimulationOptions options;
  options.integrator.relative_tolerance = kIntegratorTolerance;
  options.integrator.absolute_tolerance = 1e-2 * kIntegratorTolerance;
  options.end_time = kFloatingTime;
  options.output_interval = kMomentSampling;
  double P_drift = 0.0, L_drift = 0.0, L_kin_drift = 0.0, E_drift = 0.0, largest_torque = 0.0, largest_power = 0.0;
  const auto output = [&](double, const VectorXd& y, const VectorXd&) {
    const VectorXd x_b = system.BodyPositions(y, 0), u_b = system.BodyVelocities(y, 0);
    const Momentum now = body.ComputeMomentum(x_b, u_b);
    P_drift = std::max(P_drift, (now.linear_W - start.linear_W).norm() / start.linear_W.norm());
    L_drift = std::max(L_drift, (now.angular_Wo_W - start.angular_Wo_W).norm() / start.angular_Wo_W.norm());
    L_kin_drift = std::max(L_kin_drift, (L_kinematic(x_b, u_b) - L_kin_start).norm() / start.angular_Wo_W.norm());
    E_drift = std::max(E_drift, std::abs(energy(x_b, u_b) - E_start) / E_start);
    VectorXd u_dot(system.num_velocities()), lambda(0);
    system.Accelerations(0.0, y, u_dot, lambda);
    const Matrix3d dJ = testing::CentrifugalInertiaChange(K0, x_b.tail(n), x_b.tail(n));
    const Vector3d left_out = dJ * u_dot.segment<3>(3);
    largest_torque = std::max(largest_torque, left_out.norm());
    largest_power = std::max(largest_power, std::abs(u_b.segment<3>(3).dot(left_out)));
  };
  const SimulationStatistics stats = Simulate(system, options, y0, output);
  const double L_bound = 2.0 * kFloatingTime * largest_torque / start.angular_Wo_W.norm();
  const double E_bound = 2.0 * kFloatingTime * largest_power / E_start;
  std::cout << stats.integrator.steps << " steps; drift P " << P_drift << ", L " << L_drift << " (bound "
            << L_bound << "), L_kin " << L_kin_drift << ", E " << E_drift << " (bound " << E_bound << ")\n";
  EXPECT_LT(P_drift, kMomentumTolerance);
  EXPECT_LT(L_drift, L_bound);
  EXPECT_LT(E_drift, E_bound);
  EXPECT_GT(L_kin_drift, kTorqueAtWork * L_drift);
}

// A point load at a node adds, through AddMarkerLoad, the virtual work J^T [f; tau] of the
// node's motion, whose Jacobian carries the node's stiffening blocks with stiffening on
// (tests/mbs/flexible_body_test.cc checks those against the K0 matrices): the two bodies' loads
// differ by the stiffening and by nothing with it off.
TEST(StiffeningForces, PointLoadAtANodeDoesTheVirtualWorkOfTheNodesMotion) {
  const Vector3d f_W(300.0, -200.0, 500.0), tau_W(20.0, 10.0, -30.0);
  const State s = RandomState(13, 0.01 * kLength);
  std::array<VectorXd, 2> loads;
  for (const bool stiffening : {true, false}) {
    MultibodySystem loaded(Vector3d::Zero()), free(Vector3d::Zero());
    loaded.AddBody(MakeBeam(stiffening));
    free.AddBody(MakeBeam(stiffening));
    const MarkerRef mid = loaded.Marker("beam", "mid");
    loaded.AddForceElement(std::make_unique<PointLoad>(
        "load", mid, std::array<TimeFunctionPtr, 3>{MakeConstant(f_W.x()), MakeConstant(f_W.y()), MakeConstant(f_W.z())},
        std::array<TimeFunctionPtr, 3>{MakeConstant(tau_W.x()), MakeConstant(tau_W.y()), MakeConstant(tau_W.z())},
        LoadFrame::kWorld));
    VectorXd y = loaded.NeutralState();
    loaded.SetBodyState(0, s.x, s.u, y);
    const VectorXd dh = loaded.Forces(0.0, y) - free.Forces(0.0, y);

    const MarkerKinematics K = loaded.body(0).Marker(mid.marker, s.x, s.u);
    Eigen::Matrix<double, 6, 1> load;
    load << f_W, tau_W;
    EXPECT_LT((dh - K.jacobian.transpose() * load).norm(), kRoundOff * dh.norm()) << "stiffening " << stiffening;
    loads[stiffening ? 0 : 1] = dh;
  }
  const double stiffening_share = (loads[0] - loads[1]).norm() / loads[1].norm();
  std::cout << "|stiffening| / |load's generalised force| = " << stiffening_share << "\n";
  EXPECT_GT(stiffening_share, kRoundOff);
}

}  // namespace
}  // namespace flexmbs::mbs
