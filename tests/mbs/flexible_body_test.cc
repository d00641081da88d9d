// The floating-frame-of-reference flexible body (mbs/flexible_body.h) against the FE model it
// was reduced from, node by node: kinetic and potential energy, momentum and the generalised
// inertia forces from nodal velocities and accelerations computed here from the mesh and the
// basis (never from the SID invariants); elastic and damping forces against Phi^T K Phi; the
// power balance; the markers against the FE nodes and finite differences; geometric stiffening
// on versus off against the K0 matrices. Bodies: a Craig-Bampton beam (clamped root, rigid tip
// interface) and a free-free beam kept without its rigid modes.

#include "mbs/flexible_body.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <random>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "core/rotation.h"
#include "core/skew.h"
#include "mbs/mode_selection.h"
#include "tests/mbs/flexible_test_bodies.h"

namespace flexmbs::mbs {
namespace {

using Eigen::Index;
using Eigen::Matrix3d;
using Eigen::Matrix3Xd;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;
using testing::FeReducedBody;

// Two evaluations of the same exact integrals (sums over 63 nodes of products of the consistent
// mass matrix, against the SID blocks formed from the same matrix in another order): round-off.
// Measured: at most 3e-15.
constexpr double kRoundOff = 1e-12;
// Central differences in time with step kTimeStep [s] of functions whose rates are ~10/s (spin
// 10 rad/s, nodal elastic velocities 1 m/s on a 0.6 m beam): truncation ~ (10 kTimeStep)^2 = 1e-10
// and round-off ~ 1e-16 / (10 kTimeStep) = 1e-11, relative to the rate. Measured: at most 1e-10.
constexpr double kTimeStep = 1e-6;
constexpr double kDifferenceTolerance = 1e-8;
// Largest nodal displacement of a test state: 5 % of the beam's length, so that the terms of
// second order in q (J's order 2, ~ (0.05)^2 of J) are far above round-off.
constexpr double kDeformation = 0.05 * 0.6;
// Largest elastic node rotation [rad] of the marker tests' large-rotation states.
constexpr double kLargeRotation = 0.6;
const Vector3d kGravity(1.0, -2.0, -9.81);

Matrix3Xd Nodal(const VectorXd& dofs) { return Eigen::Map<const Matrix3Xd>(dofs.data(), 3, dofs.size() / 3); }
VectorXd Dofs(const Matrix3Xd& nodal) { return Eigen::Map<const VectorXd>(nodal.data(), nodal.size()); }

double RelativeError(const MatrixXd& value, const MatrixXd& reference) {
  return (value - reference).norm() / reference.norm();
}

struct Case {
  const char* name;
  const FeReducedBody& (*fe)();
};
void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

struct State {
  VectorXd x, u;
};

class FlexibleBodyTest : public ::testing::TestWithParam<Case> {
 protected:
  void SetUp() override {
    fe_ = &GetParam().fe();
    keep_ = testing::ElasticColumns(fe_->basis);
    Phi_ = fe_->basis.Phi(Eigen::all, keep_);
    body_ = std::make_unique<FlexibleBody>("beam", RestrictModes(fe_->body, keep_), false);
    // The same body without stiffness and damping: its h_b holds the inertia and gravity terms
    // alone, free of the round-off of Ke q (~1e7 N at 3 cm of steel).
    sid::ReducedBody inertial = RestrictModes(fe_->body, keep_);
    inertial.Ke.m0.setZero();
    inertial.De.m0.setZero();
    inertial_ = std::make_unique<FlexibleBody>("beam", std::move(inertial), false);
  }
  Index n() const { return static_cast<Index>(keep_.size()); }
  const Matrix3Xd& nodes() const { return fe_->mesh.nodes; }

  // A random state: position and orientation anywhere, q with the largest nodal displacement
  // `deformation`, v ~ 1 m/s, w ~ 10 rad/s, qdot with nodal elastic velocities ~ 1 m/s.
  State RandomState(unsigned seed, double deformation = kDeformation) const {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    const auto random = [&](Index size) { return VectorXd(VectorXd::NullaryExpr(size, [&] { return uniform(rng); })); };
    State s{VectorXd(7 + n()), VectorXd(6 + n())};
    VectorXd q = random(n()), qdot = random(n());
    q *= deformation / Nodal(Phi_ * q).colwise().norm().maxCoeff();
    qdot /= Nodal(Phi_ * qdot).colwise().norm().maxCoeff();
    s.x << random(3), random(4).normalized(), q;
    s.u << random(3), 10.0 * random(3), qdot;
    return s;
  }
  static Matrix3d Rotation(const State& s) { return RotationFromEulerParameters(s.x.segment<4>(3)); }
  // s_k = x_k + Phi_k q: the deformed nodes in B.
  Matrix3Xd Deformed(const State& s) const { return nodes() + Nodal(Phi_ * s.x.tail(n())); }
  // v_k = v + R (w x s_k + Phi_k qdot), in W.
  Matrix3Xd NodalVelocities(const State& s) const {
    const Matrix3Xd elastic = Nodal(Phi_ * s.u.tail(n()));
    const Matrix3Xd rho = Deformed(s);
    const Vector3d w = s.u.segment<3>(3);
    Matrix3Xd v(3, rho.cols());
    for (Index k = 0; k < rho.cols(); ++k) v.col(k) = s.u.head<3>() + Rotation(s) * (w.cross(rho.col(k)) + elastic.col(k));
    return v;
  }
  MatrixXd MassMatrix(const VectorXd& x) const {
    MatrixXd M(6 + n(), 6 + n());
    body_->MassMatrix(x, M);
    return M;
  }
  VectorXd Forces(const VectorXd& x, const VectorXd& u, const Vector3d& g) const {
    VectorXd h(6 + n());
    body_->Forces(0.0, x, u, g, h);
    return h;
  }
  VectorXd InertialForces(const VectorXd& x, const VectorXd& u, const Vector3d& g) const {
    VectorXd h(6 + n());
    inertial_->Forces(0.0, x, u, g, h);
    return h;
  }
  // Phi^T K Phi, Phi^T M Phi from the FE matrices.
  MatrixXd Ke() const { return Phi_.transpose() * (fe_->K * Phi_); }
  MatrixXd Me() const { return Phi_.transpose() * (fe_->M * Phi_); }

  const FeReducedBody* fe_ = nullptr;
  std::vector<Index> keep_;
  MatrixXd Phi_;
  std::unique_ptr<FlexibleBody> body_, inertial_;
};

TEST_P(FlexibleBodyTest, KineticEnergyIsTheFeModelsForRandomStates) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const State s = RandomState(seed);
    const VectorXd V = Dofs(NodalVelocities(s));
    const double T_fe = 0.5 * V.dot(fe_->M * V);
    EXPECT_LT(std::abs(body_->KineticEnergy(s.x, s.u) - T_fe) / T_fe, kRoundOff) << "seed " << seed;
    EXPECT_LT(std::abs(0.5 * s.u.dot(MassMatrix(s.x) * s.u) - T_fe) / T_fe, kRoundOff) << "seed " << seed;
  }
}

// M_b u̇ minus the velocity terms of h_b is the virtual work of the FE inertia forces M_FE a on
// the virtual motions of the coordinates: translations (W), rotations about Bo (B) and modes.
TEST_P(FlexibleBodyTest, GeneralisedInertiaForcesAreTheProjectedFeInertiaForces) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  double worst = 0.0;
  for (unsigned seed = 11; seed <= 15; ++seed) {
    const State s = RandomState(seed);
    VectorXd udot = VectorXd::NullaryExpr(6 + n(), [&] { return uniform(rng); });
    udot.segment<3>(3) *= 100.0;  // ~ w^2
    udot.tail(n()) *= 100.0 / Nodal(Phi_ * udot.tail(n())).colwise().norm().maxCoeff();
    // Nodal accelerations a_k = vdot + R (alpha x s + w x (w x s) + 2 w x Phi qdot + Phi qddot),
    // term by term, and the virtual work of M_FE a on translations (W), rotations about Bo (B)
    // and modes.
    const Matrix3d R = Rotation(s);
    const Vector3d w = s.u.segment<3>(3), alpha = udot.segment<3>(3);
    const Matrix3Xd rho = Deformed(s), elastic_v = Nodal(Phi_ * s.u.tail(n())), elastic_a = Nodal(Phi_ * udot.tail(n()));
    std::vector<Matrix3Xd> terms(5, Matrix3Xd(3, rho.cols()));
    for (Index k = 0; k < rho.cols(); ++k) {
      const Vector3d r = rho.col(k);
      terms[0].col(k) = udot.head<3>();
      terms[1].col(k) = R * alpha.cross(r);
      terms[2].col(k) = R * w.cross(w.cross(r));
      terms[3].col(k) = R * 2.0 * w.cross(elastic_v.col(k));
      terms[4].col(k) = R * elastic_a.col(k);
    }
    const auto virtual_work = [&](const Matrix3Xd& a) {
      const Matrix3Xd F = Nodal(fe_->M * Dofs(a));  // nodal inertia forces, W
      const Matrix3Xd F_B = R.transpose() * F;
      VectorXd work(6 + n());
      work.head<3>() = F.rowwise().sum();
      work.segment<3>(3).setZero();
      for (Index k = 0; k < rho.cols(); ++k) work.segment<3>(3) += rho.col(k).cross(F_B.col(k));
      work.tail(n()) = Phi_.transpose() * Dofs(F_B);
      return work;
    };
    Matrix3Xd a = Matrix3Xd::Zero(3, rho.cols());
    for (const Matrix3Xd& term : terms) a += term;
    const VectorXd expected = virtual_work(a);
    // Round-off is relative to the largest term's contribution (they cancel in part).
    VectorXd scale = VectorXd::Zero(6 + n());
    for (const Matrix3Xd& term : terms) scale = scale.cwiseMax(virtual_work(term).cwiseAbs());

    const VectorXd inertia = MassMatrix(s.x) * udot - InertialForces(s.x, s.u, Vector3d::Zero());
    const VectorXd error = inertia - expected;
    EXPECT_LT(error.head<3>().norm() / scale.head<3>().norm(), kRoundOff) << "seed " << seed;
    EXPECT_LT(error.segment<3>(3).norm() / scale.segment<3>(3).norm(), kRoundOff) << "seed " << seed;
    EXPECT_LT(error.tail(n()).norm() / scale.tail(n()).norm(), kRoundOff) << "seed " << seed;
    worst = std::max({worst, error.head<3>().norm() / scale.head<3>().norm(),
                      error.segment<3>(3).norm() / scale.segment<3>(3).norm(), error.tail(n()).norm() / scale.tail(n()).norm()});
  }
  std::cout << "largest relative error of the generalised inertia forces: " << worst << "\n";
}

// Without spin: h_b = [0; 0; -Ke q - De qdot] with Ke = Phi^T K Phi, De = a Me + b Ke (Rayleigh).
TEST_P(FlexibleBodyTest, ElasticAndDampingForcesAreThoseOfTheFeMatrices) {
  State s = RandomState(21);
  s.u.segment<3>(3).setZero();
  const VectorXd q = s.x.tail(n()), qdot = s.u.tail(n());
  const MatrixXd De = testing::kRayleighMassPerS * Me() + testing::kRayleighStiffnessS * Ke();
  const VectorXd h = Forces(s.x, s.u, Vector3d::Zero());
  EXPECT_EQ(h.head<6>().norm(), 0.0);
  EXPECT_LT(RelativeError(h.tail(n()), -Ke() * q - De * qdot), kRoundOff);
}

// V = 1/2 q^T Phi^T K Phi q - g . int r_W dm, the integral from the FE mass matrix and the
// deformed nodes in W; and the gravity forces of h_b are -dV/dx (translations, rotations of B,
// modes).
TEST_P(FlexibleBodyTest, PotentialEnergyIsTheFeModelsAndGravityItsGradient) {
  State s = RandomState(31);
  const VectorXd q = s.x.tail(n());
  const Matrix3Xd r_W = (Rotation(s) * Deformed(s)).colwise() + Vector3d(s.x.head<3>());
  const Vector3d first_moment = Nodal(fe_->M * Dofs(r_W)).rowwise().sum();
  const double elastic = 0.5 * q.dot(Ke() * q), gravity = -kGravity.dot(first_moment);
  const double V_elastic = body_->PotentialEnergy(s.x, Vector3d::Zero());
  EXPECT_LT(std::abs(V_elastic - elastic) / elastic, kRoundOff);
  EXPECT_LT(std::abs(inertial_->PotentialEnergy(s.x, kGravity) - gravity) / std::abs(gravity), kRoundOff);
  EXPECT_LT(std::abs(body_->PotentialEnergy(s.x, kGravity) - elastic - gravity) / elastic, kRoundOff);

  // Gravity alone (the body without stiffness: the elastic energy, ~1e6 J at 3 cm of steel, would
  // bring its round-off 1e-16 V / step into differences of ~400 N). Steps: V is linear in p and q
  // (central differences exact up to round-off); rotations by small angles about B's axes
  // (truncation ~ step^2 = 1e-10).
  s.u.setZero();
  const VectorXd h = InertialForces(s.x, s.u, kGravity);
  const double step = 1e-5;
  VectorXd gradient(6 + n());
  for (Index i = 0; i < 6 + n(); ++i) {
    State plus = s, minus = s;
    if (i < 3) {
      plus.x(i) += step;
      minus.x(i) -= step;
    } else if (i < 6) {
      const Vector3d axis = Vector3d::Unit(i - 3);
      plus.x.segment<4>(3) = EulerParametersFromRotation(Rotation(s) * Eigen::AngleAxisd(step, axis).toRotationMatrix());
      minus.x.segment<4>(3) = EulerParametersFromRotation(Rotation(s) * Eigen::AngleAxisd(-step, axis).toRotationMatrix());
    } else {
      plus.x(1 + i) += step;
      minus.x(1 + i) -= step;
    }
    gradient(i) = (inertial_->PotentialEnergy(plus.x, kGravity) - inertial_->PotentialEnergy(minus.x, kGravity)) / (2.0 * step);
  }
  EXPECT_LT(RelativeError(h.head<3>(), -gradient.head<3>()), kDifferenceTolerance);
  EXPECT_LT(RelativeError(h.segment<3>(3), -gradient.segment<3>(3)), kDifferenceTolerance);
  // The modal gravity forces int phi_j . g dm vanish for free-free elastic modes: measured against
  // their Cauchy-Schwarz bound |g| sqrt(m trace(Me)).
  const double modal_scale = kGravity.norm() * std::sqrt(fe_->body.mass * Me().trace());
  EXPECT_LT((h.tail(n()) + gradient.tail(n())).norm() / modal_scale, kDifferenceTolerance);
}

// dE/dt = -qdot^T De qdot with E = T + V and u̇ = M_b^-1 h_b: dE/dt = u^T h_b + dE/dx xdot
// (T is quadratic in u with matrix M_b, so dT/du u̇ = u^T M_b u̇ = u^T h_b); dE/dx xdot by
// central differences along xdot.
TEST_P(FlexibleBodyTest, PowerBalanceHoldsWithGravityAndDamping) {
  for (unsigned seed = 41; seed <= 43; ++seed) {
    const State s = RandomState(seed);
    VectorXd xdot(7 + n());
    PositionDerivative(s.x, s.u, xdot);
    const auto energy = [&](double tau) {
      const VectorXd x = s.x + tau * xdot;
      return body_->KineticEnergy(x, s.u) + body_->PotentialEnergy(x, kGravity);
    };
    const double along_x = (energy(kTimeStep) - energy(-kTimeStep)) / (2.0 * kTimeStep);
    const double work = s.u.dot(Forces(s.x, s.u, kGravity));
    const VectorXd qdot = s.u.tail(n());
    const double dissipation = qdot.dot((testing::kRayleighMassPerS * Me() + testing::kRayleighStiffnessS * Ke()) * qdot);
    const double scale = std::max({std::abs(work), std::abs(along_x), dissipation});
    EXPECT_LT(std::abs(work + along_x + dissipation) / scale, kDifferenceTolerance) << "seed " << seed;
  }
}

// P = sum over nodes of (M_FE v)_k and L = sum of r_k x (M_FE v)_k (the consistent mass couples
// nodes: int r x v dm = sum_kl M_s(k, l) r_k x v_l).
TEST_P(FlexibleBodyTest, MomentumIsTheSumOverTheFeNodes) {
  for (unsigned seed = 51; seed <= 53; ++seed) {
    const State s = RandomState(seed);
    const Matrix3Xd momenta = Nodal(fe_->M * Dofs(NodalVelocities(s)));
    const Matrix3Xd r_W = (Rotation(s) * Deformed(s)).colwise() + Vector3d(s.x.head<3>());
    Vector3d L = Vector3d::Zero();
    for (Index k = 0; k < r_W.cols(); ++k) L += r_W.col(k).cross(momenta.col(k));
    const Momentum momentum = body_->ComputeMomentum(s.x, s.u);
    EXPECT_LT(RelativeError(momentum.linear_W, momenta.rowwise().sum()), kRoundOff) << "seed " << seed;
    EXPECT_LT(RelativeError(momentum.angular_Wo_W, L), kRoundOff) << "seed " << seed;
  }
}

// Without gravity the equations of motion keep P and L: their rates along (xdot, u̇), by central
// differences, vanish against the size of their u̇ part (the momentum of u̇).
TEST_P(FlexibleBodyTest, EquationsOfMotionKeepMomentumWithoutExternalForces) {
  for (unsigned seed = 61; seed <= 63; ++seed) {
    const State s = RandomState(seed);
    VectorXd xdot(7 + n());
    PositionDerivative(s.x, s.u, xdot);
    const VectorXd udot = MassMatrix(s.x).ldlt().solve(Forces(s.x, s.u, Vector3d::Zero()));
    const auto at = [&](double tau) { return body_->ComputeMomentum(s.x + tau * xdot, s.u + tau * udot); };
    const Momentum plus = at(kTimeStep), minus = at(-kTimeStep);
    const Vector3d P_rate = (plus.linear_W - minus.linear_W) / (2.0 * kTimeStep);
    const Vector3d L_rate = (plus.angular_Wo_W - minus.angular_Wo_W) / (2.0 * kTimeStep);
    // The rates are sums of parts that cancel: the momenta of the translational, rotational and
    // elastic accelerations each.
    double P_scale = 0.0, L_scale = 0.0;
    for (const auto& [first, size] : {std::pair<Index, Index>{0, 3}, {3, 3}, {6, n()}}) {
      VectorXd part = VectorXd::Zero(6 + n());
      part.segment(first, size) = udot.segment(first, size);
      const Momentum of_part = body_->ComputeMomentum(s.x, part);
      P_scale = std::max(P_scale, of_part.linear_W.norm());
      L_scale = std::max(L_scale, of_part.angular_Wo_W.norm());
    }
    EXPECT_LT(P_rate.norm() / P_scale, kDifferenceTolerance) << "seed " << seed;
    EXPECT_LT(L_rate.norm() / L_scale, kDifferenceTolerance) << "seed " << seed;
    std::cout << "momentum rates relative to their parts: " << P_rate.norm() / P_scale << ", " << L_rate.norm() / L_scale << "\n";
  }
}

// The rows of the FE nodes carry p + R (x_k + Phi_k q): the single-node marker "corner" is there.
TEST_P(FlexibleBodyTest, NodeMarkerIsAtItsDeformedFeNode) {
  const State s = RandomState(71);
  const int corner = fe_->mesh.node_sets.at("corner").front();
  const MarkerKinematics marker = body_->Marker(body_->FindMarker("corner"), s.x, s.u);
  EXPECT_LT(RelativeError(marker.p_WM_W, Vector3d(s.x.head<3>()) + Rotation(s) * Deformed(s).col(corner)), kRoundOff);
  EXPECT_LT(RelativeError(marker.v_WM_W, NodalVelocities(s).col(corner)), kRoundOff);
  const MarkerKinematics origin = body_->Marker(body_->FindMarker("origin"), s.x, s.u);
  EXPECT_EQ(origin.p_WM_W, Vector3d(s.x.head<3>()));
  EXPECT_LT((origin.R_WM - Rotation(s)).norm(), kRoundOff);
  EXPECT_EQ(body_->FindMarker("nowhere"), -1);
}

// For every marker, with stiffening off and on (the nodes' second-order motion): J u is the
// returned velocity, the pose's central difference along xdot(x, u) is J u, and the velocity's
// along (xdot, u̇) is J u̇ + bias. Two states: elastic node rotations all below 0.5 rad (power
// series of the rotation coefficients) and some above (closed forms).
TEST_P(FlexibleBodyTest, MarkerJacobianAndBiasAreTheDerivativesOfThePose) {
  std::mt19937 rng(81);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const FlexibleBody stiff("beam", RestrictModes(fe_->body, keep_), true);
  const FlexibleBody* plain = body_.get();
  const int origin = plain->FindMarker("origin");
  // The largest first-order rotation |Psi_k q| [rad] over the marker nodes.
  const auto largest_rotation = [&](const VectorXd& q) {
    double largest = 0.0;
    for (int m = 0; m < origin; ++m) {
      largest = std::max(largest, (fe_->body.nodes[static_cast<std::size_t>(m)].psi.m0(Eigen::all, keep_) * q).norm());
    }
    return largest;
  };
  using Run = std::tuple<bool, const FlexibleBody*>;
  for (const auto& [large_rotations, body] : {Run{false, plain}, Run{true, plain}, Run{false, &stiff}, Run{true, &stiff}}) {
    State s = RandomState(82);
    // Large: the random shape scaled to a largest node rotation of kLargeRotation, where the
    // rotation's second order is ~(0.6)^2 / 2 of its first (independent of how the solver picked
    // the basis of the beam's repeated bending pairs).
    if (large_rotations) s.x.tail(n()) *= kLargeRotation / largest_rotation(s.x.tail(n()));
    const VectorXd udot = 100.0 * VectorXd::NullaryExpr(6 + n(), [&] { return uniform(rng); });
    VectorXd xdot(7 + n());
    PositionDerivative(s.x, s.u, xdot);
    const double deformation = Nodal(Phi_ * s.x.tail(n())).colwise().norm().maxCoeff();
    for (int m = 0; m < origin + 1; ++m) {
      const MarkerKinematics K = body->Marker(m, s.x, s.u);
      Eigen::Matrix<double, 6, 1> velocity;
      velocity << K.v_WM_W, K.w_WM_W;
      EXPECT_LT(RelativeError(K.jacobian * s.u, velocity), kRoundOff) << "marker " << m;
      EXPECT_LT((K.R_WM.transpose() * K.R_WM - Matrix3d::Identity()).norm(), kRoundOff) << "marker " << m;

      const MarkerKinematics plus = body->Marker(m, s.x + kTimeStep * xdot, s.u);
      const MarkerKinematics minus = body->Marker(m, s.x - kTimeStep * xdot, s.u);
      Eigen::Matrix<double, 6, 1> pose_rate;
      pose_rate << (plus.p_WM_W - minus.p_WM_W) / (2.0 * kTimeStep),
          Axial(plus.R_WM * minus.R_WM.transpose()) / (2.0 * kTimeStep);
      EXPECT_LT(RelativeError(pose_rate, velocity), kDifferenceTolerance) << "marker " << m << ", deformation " << deformation << ", stiffening " << body->geometric_stiffening();

      const MarkerKinematics ahead = body->Marker(m, s.x + kTimeStep * xdot, s.u + kTimeStep * udot);
      const MarkerKinematics behind = body->Marker(m, s.x - kTimeStep * xdot, s.u - kTimeStep * udot);
      Eigen::Matrix<double, 6, 1> acceleration;
      acceleration << (ahead.v_WM_W - behind.v_WM_W) / (2.0 * kTimeStep), (ahead.w_WM_W - behind.w_WM_W) / (2.0 * kTimeStep);
      EXPECT_LT(RelativeError(K.jacobian * udot + K.bias, acceleration), kDifferenceTolerance)
          << "marker " << m << ", deformation " << deformation << ", stiffening " << body->geometric_stiffening();
    }
    if (!large_rotations) {
      EXPECT_LT(largest_rotation(s.x.tail(n())), 0.2 * kLargeRotation);  // measured: 0.066 to 0.086 rad
    }
  }
}

// Stiffening on adds exactly the K0 terms of docs/sid.md to the elastic row and the stiffening
// field's torques to the rotational row (mbs/stiffening_inertia.h): M_b stays the kinematic
// one; h_b gains dCt R^T g - sum_l w_q,l K0omega_l q (dCt = [K0t_a q]_a, dCr likewise) in the
// elastic row and dc x R^T g - dJ' w - w x dJ w in the rotational row, with dc_a = q^T K0t_a q / 2
// and w^T dJ w = -sum_l w_q,l q^T K0omega_l q; the acceleration-dependent forces are
// -(dCt R^T v' + dCr w'); the kinetic energy gains w^T dJ w / 2, the potential -g . R dc.
TEST_P(FlexibleBodyTest, GeometricStiffeningAddsTheK0TermsAndTheirRotationalPartners) {
  const FlexibleBody stiff("beam", RestrictModes(fe_->body, keep_), true);
  const sid::GeometricStiffening& K0 = fe_->body.stiffening;
  ASSERT_FALSE(K0.empty());
  const State s = RandomState(91);
  const VectorXd q = s.x.tail(n());
  const Matrix3d R = Rotation(s);
  const Vector3d w = s.u.segment<3>(3);
  Eigen::MatrixX3d dCt(n(), 3), dCr(n(), 3);
  for (std::size_t a = 0; a < 3; ++a) {
    dCt.col(static_cast<Index>(a)) = K0.K0t[a](keep_, keep_) * q;
    dCr.col(static_cast<Index>(a)) = K0.K0r[a](keep_, keep_) * q;
  }
  const Eigen::Matrix<double, 6, 1> w_q =
      (Eigen::Matrix<double, 6, 1>() << w.x() * w.x(), w.y() * w.y(), w.z() * w.z(), w.x() * w.y(), w.y() * w.z(),
       w.z() * w.x()).finished();
  VectorXd centrifugal = VectorXd::Zero(n());
  for (std::size_t l = 0; l < 6; ++l) centrifugal += w_q(static_cast<Index>(l)) * (K0.K0omega[l](keep_, keep_) * q);
  // dJ and its rate from the quadratic forms s_l = q^T K0omega_l q, s_l' = 2 qdot^T K0omega_l q.
  const VectorXd qdot = s.u.tail(n());
  const sid::GeometricStiffening kept = RestrictModes(fe_->body, keep_).stiffening;
  const Matrix3d dJ = testing::CentrifugalInertiaChange(kept, q, q);
  const Matrix3d dJ_dot = 2.0 * testing::CentrifugalInertiaChange(kept, qdot, q);
  const Vector3d dc = 0.5 * dCt.transpose() * q;

  MatrixXd M_stiff(6 + n(), 6 + n());
  stiff.MassMatrix(s.x, M_stiff);
  EXPECT_EQ(M_stiff, MassMatrix(s.x));

  // Differences of two evaluations: round-off of h_b itself. (The free-free beam's K0t and K0r
  // vanish to round-off: inertia relief balances uniform and angular accelerations.)
  VectorXd dh = VectorXd::Zero(6 + n());
  dh.segment<3>(3) = dc.cross(R.transpose() * kGravity) - dJ_dot * w - w.cross(dJ * w);
  dh.tail(n()) = dCt * R.transpose() * kGravity - centrifugal;
  VectorXd h_stiff(6 + n());
  stiff.Forces(0.0, s.x, s.u, kGravity, h_stiff);
  const VectorXd h = Forces(s.x, s.u, kGravity);
  EXPECT_LT((h_stiff - h - dh).norm() / h.norm(), kRoundOff);
  std::cout << "|dh| / |h| = " << dh.norm() / h.norm() << "\n";

  std::mt19937 rng(17);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const VectorXd u_dot = VectorXd::NullaryExpr(6 + n(), [&] { return 100.0 * uniform(rng); });
  VectorXd h_a = VectorXd::Zero(6 + n());
  EXPECT_FALSE(body_->AddAccelerationDependentForces(s.x, s.u, u_dot, h_a));
  EXPECT_EQ(h_a.norm(), 0.0);
  ASSERT_TRUE(stiff.AddAccelerationDependentForces(s.x, s.u, u_dot, h_a));
  VectorXd expected = VectorXd::Zero(6 + n());
  expected.tail(n()) = -(dCt * R.transpose() * u_dot.head<3>() + dCr * u_dot.segment<3>(3));
  // Against the size of its terms: the free-free beam's are round-off themselves.
  EXPECT_LE((h_a - expected).norm(), kRoundOff * (dCt.norm() + dCr.norm()) * u_dot.norm());
  const double kinetic = body_->KineticEnergy(s.x, s.u) + 0.5 * w.dot(dJ * w);
  EXPECT_NEAR(stiff.KineticEnergy(s.x, s.u), kinetic, kRoundOff * kinetic);
  const double potential = body_->PotentialEnergy(s.x, kGravity) - kGravity.dot(R * dc);
  EXPECT_NEAR(stiff.PotentialEnergy(s.x, kGravity), potential, kRoundOff * std::abs(potential));
}

// With stiffening on, a node's position and rotation gain the second-order parts SID's K0
// matrices of unit nodal loads imply (docs/sid.md, nodes: phi.m1[j](a, i) = -K0F_a(i, j), psi.m1
// likewise with K0M_a): s = o0 + Phi q - 1/2 [q^T K0F_a q]_a, theta = Psi q - 1/2 [q^T K0M_a q]_a,
// R_WK = R exp(theta~) AP0; K0F_a, K0M_a are built here from the blocks, transposed.
TEST_P(FlexibleBodyTest, StiffenedNodeMovesBySecondOrderFieldOfTheK0Matrices) {
  const sid::ReducedBody data = RestrictModes(fe_->body, keep_);
  const FlexibleBody stiff("beam", data, true);
  const State s = RandomState(101);
  const VectorXd q = s.x.tail(n());
  // -1/2 [q^T K0_a q]_a of a node's order-1 blocks (zero for a node without them).
  const auto second_order = [&](const std::vector<MatrixXd>& blocks) {
    Vector3d out = Vector3d::Zero();
    if (blocks.empty()) return out;
    for (Index a = 0; a < 3; ++a) {
      MatrixXd K0(n(), n());
      for (Index j = 0; j < n(); ++j) K0.col(j) = -blocks[static_cast<std::size_t>(j)].row(a).transpose();
      out(a) = -0.5 * q.dot(K0 * q);
    }
    return out;
  };
  int stiffened_nodes = 0;
  for (const sid::Node& node : data.nodes) {
    const Vector3d u2 = second_order(node.phi.m1), theta2 = second_order(node.psi.m1);
    if (u2.norm() > 0.0 && theta2.norm() > 0.0) ++stiffened_nodes;
    const MarkerKinematics plain = body_->Marker(body_->FindMarker(node.name), s.x, s.u);
    const MarkerKinematics K = stiff.Marker(stiff.FindMarker(node.name), s.x, s.u);
    EXPECT_LT(RelativeError(K.p_WM_W, plain.p_WM_W + Rotation(s) * u2), kRoundOff) << node.name;
    const Vector3d theta = node.psi.m0 * q + theta2;
    const Matrix3d expected = Rotation(s) * Eigen::AngleAxisd(theta.norm(), theta.normalized()).toRotationMatrix() * node.AP.m0;
    EXPECT_LT((K.R_WM - expected).norm(), kRoundOff) << node.name;
  }
  EXPECT_GT(stiffened_nodes, 0);
}

// The generalised force of a load at a node is J^T [f; tau]; its derivative in q at q = 0, with
// stiffening on less off, is the load's geometric stiffness -K0F(f_B) - K0M(tau_B): symmetric and
// nonzero (both parts). Central differences of a function of q whose second derivative is
// O(|Phi|^2 |load|): step 1e-4 of a unit q, truncation ~1e-8 of the term.
TEST_P(FlexibleBodyTest, NodeLoadStiffnessIsTheSymmetricK0OfTheLoad) {
  const FlexibleBody stiff("beam", RestrictModes(fe_->body, keep_), true);
  const State s = RandomState(102);
  const int mid = stiff.FindMarker("mid");
  const Vector3d f_W(30.0, -20.0, 50.0), tau_W(2.0, 1.0, -3.0);
  constexpr double kStep = 1e-4, kDifferenceError = 1e-6;
  const auto stiffness = [&](const Vector3d& f, const Vector3d& tau) {
    MatrixXd A(n(), n());
    for (Index j = 0; j < n(); ++j) {
      VectorXd plus = s.x, minus = s.x;
      plus.tail(n()) = kStep * VectorXd::Unit(n(), j);
      minus.tail(n()) = -kStep * VectorXd::Unit(n(), j);
      const auto stiffening = [&](const VectorXd& x) {
        return VectorXd(stiff.MarkerLoad(mid, x, f, tau) - body_->MarkerLoad(mid, x, f, tau));
      };
      A.col(j) = (stiffening(plus) - stiffening(minus)).tail(n()) / (2.0 * kStep);
    }
    return A;
  };
  const MatrixXd A = stiffness(f_W, tau_W), A_force = stiffness(f_W, Vector3d::Zero());
  const MatrixXd A_moment = stiffness(Vector3d::Zero(), tau_W);
  ASSERT_GT(A_force.norm(), 0.0);
  ASSERT_GT(A_moment.norm(), 0.0);
  EXPECT_LT((A - A.transpose()).norm() / A.norm(), kDifferenceError);
  EXPECT_LT((A_moment - A_moment.transpose()).norm() / A_moment.norm(), kDifferenceError);

  const sid::Node& node = fe_->body.nodes[static_cast<std::size_t>(mid)];
  const Vector3d f_B = Rotation(s).transpose() * f_W, tau_B = Rotation(s).transpose() * tau_W;
  MatrixXd expected = MatrixXd::Zero(n(), n());
  for (Index j = 0; j < n(); ++j) {
    const std::size_t column = static_cast<std::size_t>(keep_[static_cast<std::size_t>(j)]);
    const Matrix3Xd phi1 = node.phi.m1[column](Eigen::all, keep_), psi1 = node.psi.m1[column](Eigen::all, keep_);
    expected.col(j) = (phi1.transpose() * f_B + psi1.transpose() * tau_B);
  }
  EXPECT_LT(RelativeError(A, expected), kDifferenceError);
}

INSTANTIATE_TEST_SUITE_P(Beams, FlexibleBodyTest,
                         ::testing::Values(Case{"CraigBampton", &testing::CraigBamptonBeam},
                                           Case{"FreeFreeElastic", &testing::FreeFreeBeam}),
                         [](const auto& param_info) { return std::string(param_info.param.name); });

// The rigid tip interface of the Craig-Bampton beam: every tip node moves by t + theta x (x_k - o)
// with the marker's translation t = origin(q) - o and rotation theta = Psi q.
TEST(FlexibleBodyMarkers, RigidInterfaceMarkerMovesWithItsNodes) {
  const FeReducedBody& fe = testing::CraigBamptonBeam();
  const FlexibleBody body("beam", fe.body, false);
  std::mt19937 rng(111);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const VectorXd q = 1e-3 * VectorXd::NullaryExpr(body.num_modes(), [&] { return uniform(rng); });
  VectorXd x(7 + body.num_modes());
  x << Vector3d::Zero(), 1.0, 0.0, 0.0, 0.0, q;
  const int tip = body.FindMarker("tip");
  const sid::Node& node = fe.body.nodes[static_cast<std::size_t>(tip)];
  const Vector3d o = node.origin.m0.col(0);
  const Vector3d t = body.Marker(tip, x, VectorXd::Zero(6 + body.num_modes())).p_WM_W - o;
  const Vector3d theta = node.psi.m0 * q;
  const Matrix3Xd u = Nodal(fe.basis.Phi * q);
  double worst = 0.0;
  for (int k : fe.mesh.node_sets.at("tip")) {
    worst = std::max(worst, (u.col(k) - t - theta.cross(fe.mesh.nodes.col(k) - o)).norm());
  }
  EXPECT_LT(worst / u.colwise().norm().maxCoeff(), kRoundOff);
}

}  // namespace
}  // namespace flexmbs::mbs
