// The model Jacobian of the equations of motion (mbs/system_jacobian.h) against central
// differences of the functions it differentiates, and against the constrained operator formed
// densely here; the share of df/dy it leaves out; and the stiff run it exists for.
//
// The scene: the Craig-Bampton steel beam of flexible_test_bodies.h (6 constraint + 4 normal
// modes, Rayleigh damping, geometric stiffening on) on a revolute joint to the ground at its
// body frame, a rigid block on a spherical joint at its tip, a spring-damper from the beam's mid
// node to the ground and a bushing between the block and the beam's corner node.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <complex>
#include <cstdio>
#include <string>
#include <memory>
#include <random>
#include <vector>


#include "core/rotation.h"
#include "mbs/flexible_body.h"
#include "mbs/force_element.h"
#include "mbs/joint.h"
#include "mbs/mode_selection.h"
#include "mbs/multibody_system.h"
#include "mbs/rigid_body.h"
#include "mbs/scene.h"
#include "mbs/simulation.h"
#include "mbs/simulation_error.h"
#include "mbs/system_jacobian.h"
#include "mbs/time_function.h"
#include "tests/input_error.h"
#include "tests/mbs/flexible_test_bodies.h"
#include "tests/mbs/scene_options_support.h"
#include "tests/validation/flexible_pendulum_model.h"
#include "tests/support/random_draws.h"

namespace flexmbs::mbs {
namespace {

using Eigen::Index;
using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;

// Central differences: increments of 1e-6 in every coordinate (m, rad, modal coordinates of
// 1e-5 .. 1e-3 here, m/s, rad/s). The differentiated functions are at most quadratic in the
// coordinates the tests differentiate exactly (the elastic row in q, qdot; the loads in u) or
// smooth on the scale of the scene (the spring's length, 0.3 m): truncation ~1e-12 relative,
// round-off eps |f| / 1e-6 ~ 1e-9 of the entries.
constexpr double kIncrement = 1e-6;
// The bound on the differences of entries a test claims exact, relative to the block's largest
// entry: measured 4.5e-13 .. 1.6e-8 (the force elements' u columns at any state; see the
// printouts); was 1e-6.
constexpr double kExactTolerance = 1e-7;
// The dense operator formed here against the solver's factorisations: both in double precision
// on a mass matrix of condition ~1e7 (the Craig-Bampton constraint modes).
constexpr double kOperatorTolerance = 1e-8;

const Vector3d kGravity_W(0.0, 0.0, -9.81);

struct Scene {
  std::unique_ptr<MultibodySystem> system;
  int beam = 0, block = 0;
};

Scene MakeScene() {
  Scene scene;
  scene.system = std::make_unique<MultibodySystem>(kGravity_W);
  MultibodySystem& system = *scene.system;
  scene.beam = system.AddBody(std::make_unique<FlexibleBody>("beam", testing::CraigBamptonBeam().body, true));
  const double a = 0.05;  // the block's half edge [m]
  scene.block = system.AddBody(std::make_unique<RigidBody>(
      "block", 8.0, Vector3d(0.02, 0.0, 0.0), (8.0 * a * a * 2.0 / 3.0) * Matrix3d::Identity(),
      std::vector<RigidBodyMarker>{{"hinge", Vector3d::Zero(), Matrix3d::Identity()},
                                   {"mount", Vector3d(0.04, 0.03, -0.02), Matrix3d::Identity()}}));
  system.AddJoint(Joint("hub", JointType::kRevolute, MarkerRef::Ground(Vector3d::Zero()),
                        system.Marker("beam", FlexibleBody::kOriginMarker)));
  system.AddJoint(Joint("ball", JointType::kSpherical, system.Marker("beam", "tip"), system.Marker("block", "hinge")));
  system.AddForceElement(std::make_unique<SpringDamper>("spring", system.Marker("beam", "mid"),
                                                        MarkerRef::Ground(Vector3d(0.3, 0.0, 0.4)), 0.3, 2e5, 50.0));
  Eigen::Matrix<double, 6, 1> stiffness, damping;
  stiffness << 1e6, 2e6, 3e6, 1e4, 2e4, 3e4;
  damping << 1e2, 2e2, 3e2, 1.0, 2.0, 3.0;
  system.AddForceElement(
      std::make_unique<Bushing>("mount", system.Marker("block", "mount"), system.Marker("beam", "corner"), stiffness, damping));
  system.set_constraint_settings({200.0, 1e-10});
  return scene;
}

/// A state off every equilibrium: the beam turned and deformed (|q_k| <= deformation), all
/// velocities random (w ~ 3 rad/s), the block where its bushing holds it (1 mm and 0.01 rad
/// from the beam's corner frame; the joints are not satisfied).
VectorXd GenericState(const Scene& scene, unsigned seed, double deformation = 1e-4) {
  const MultibodySystem& system = *scene.system;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  VectorXd y = system.NeutralState();
  for (int b = 0; b < system.num_bodies(); ++b) {
    const Index px = system.position_offset(b), pu = system.num_positions() + system.velocity_offset(b);
    const Index n = system.body(b).num_modes();
    y.segment<3>(px) = 0.1 * flexmbs::testing::DrawVector3(uniform, rng);
    const Eigen::Quaterniond e = Eigen::Quaterniond(Eigen::AngleAxisd(0.7 + 0.3 * b, Vector3d(1.0, 2.0, -1.0 + b).normalized()));
    y.segment<4>(px + 3) << e.w(), e.x(), e.y(), e.z();
    for (Index k = 0; k < n; ++k) y(px + 7 + k) = deformation * uniform(rng);
    for (Index k = 0; k < 6 + n; ++k) y(pu + k) = (k < 6 ? 3.0 : 0.03) * uniform(rng);
  }
  const MarkerKinematics corner = system.MarkerState(system.Marker("beam", "corner"), y);
  const Matrix3d R_WB =
      corner.R_WM * Eigen::AngleAxisd(0.01, flexmbs::testing::DrawVector3(uniform, rng).normalized()).matrix();
  const Eigen::Quaterniond e(R_WB);  // the mount marker has R_BM = I
  const Index px = system.position_offset(scene.block);
  y.segment<3>(px) = corner.p_WM_W + 1e-3 * flexmbs::testing::DrawVector3(uniform, rng).normalized() -
                     R_WB * Vector3d(0.04, 0.03, -0.02);
  y.segment<4>(px + 3) << e.w(), e.x(), e.y(), e.z();
  return y;
}

/// Central differences of f (size rows) over the velocity-space coordinates: columns 0 ..
/// num_velocities() - 1 move the positions by DisplacePositions, the rest the velocities.
template <typename Function>
MatrixXd VelocitySpaceDifferences(const MultibodySystem& system, const VectorXd& y, Index rows, Function f) {
  const Index nx = system.num_positions(), nu = system.num_velocities();
  MatrixXd D(rows, 2 * nu);
  VectorXd f_plus(rows), f_minus(rows);
  for (Index j = 0; j < 2 * nu; ++j) {
    VectorXd plus = y, minus = y;
    if (j < nu) {
      system.DisplacePositions(kIncrement * VectorXd::Unit(nu, j), plus);
      system.DisplacePositions(-kIncrement * VectorXd::Unit(nu, j), minus);
    } else {
      plus(nx + j - nu) += kIncrement;
      minus(nx + j - nu) -= kIncrement;
    }
    f(plus, f_plus);
    f(minus, f_minus);
    D.col(j) = (f_plus - f_minus) / (2.0 * kIncrement);
  }
  return D;
}

/// The model's u' rows with the Euler-parameter columns mapped back to rotation increments
/// (d/dtheta = d/de L(e)): [du'/dx (velocity space), du'/du].
MatrixXd VelocitySpaceRows(const MultibodySystem& system, const VectorXd& y, const MatrixXd& dfdy) {
  const Index nx = system.num_positions(), nu = system.num_velocities();
  MatrixXd out(nu, 2 * nu);
  for (int b = 0; b < system.num_bodies(); ++b) {
    const Index px = system.position_offset(b), pu = system.velocity_offset(b), n = system.body(b).num_modes();
    Eigen::Matrix<double, 4, 3> L;
    for (int k = 0; k < 3; ++k) L.col(k) = EulerParameterRate(y.segment<4>(px + 3), Vector3d::Unit(k));
    out.middleCols(pu, 3) = dfdy.block(nx, px, nu, 3);
    out.middleCols(pu + 3, 3) = dfdy.block(nx, px + 3, nu, 4) * L;
    out.middleCols(pu + 6, n) = dfdy.block(nx, px + 7, nu, n);
  }
  out.rightCols(nu) = dfdy.bottomRightCorner(nu, nu);
  return out;
}

/// max |A - B| / max |B|.
double RelativeDifference(const MatrixXd& A, const MatrixXd& B) {
  return (A - B).cwiseAbs().maxCoeff() / B.cwiseAbs().maxCoeff();
}

TEST(SystemJacobian, PositionRowsAreExact) {
  const Scene scene = MakeScene();
  const MultibodySystem& system = *scene.system;
  const VectorXd y = GenericState(scene, 1);
  const Index n_y = system.state_size(), nx = system.num_positions();
  MatrixXd dfdy(n_y, n_y);
  SystemJacobian(system, 0.1, y, dfdy);
  // x' = PositionDerivative is linear in u and in e: central differences in the raw coordinates.
  MatrixXd D(nx, n_y);
  VectorXd f_plus(n_y), f_minus(n_y);
  for (Index j = 0; j < n_y; ++j) {
    VectorXd plus = y, minus = y;
    plus(j) += kIncrement;
    minus(j) -= kIncrement;
    system.Derivative(0.1, plus, f_plus);
    system.Derivative(0.1, minus, f_minus);
    D.col(j) = (f_plus - f_minus).head(nx) / (2.0 * kIncrement);
  }
  const double difference = RelativeDifference(dfdy.topRows(nx), D);
  std::printf("[ numbers  ] x' rows: max |model - central differences| / max |entry| = %.1e\n", difference);
  EXPECT_LT(difference, kExactTolerance);
}

// The beam's elastic row in its q and qdot columns: AddForceJacobian against central differences
// of Forces plus the acceleration-dependent forces at fixed accelerations.
TEST(SystemJacobian, FlexibleBodyElasticRowsAreExact) {
  const Scene scene = MakeScene();
  const MultibodySystem& system = *scene.system;
  const Body& beam = system.body(scene.beam);
  const VectorXd y = GenericState(scene, 2);
  const Index n = beam.num_modes(), nu_b = beam.num_velocities();
  const VectorXd x = system.BodyPositions(y, scene.beam), u = system.BodyVelocities(y, scene.beam);
  const VectorXd u_dot = 50.0 * VectorXd::Random(nu_b);
  const auto h = [&](const VectorXd& x_b, const VectorXd& u_b) {
    VectorXd out(nu_b);
    beam.Forces(0.0, x_b, u_b, kGravity_W, out);
    beam.AddAccelerationDependentForces(x_b, u_b, u_dot, out);
    return out;
  };
  MatrixXd dh_dx = MatrixXd::Zero(nu_b, nu_b), dh_du = MatrixXd::Zero(nu_b, nu_b);
  beam.AddForceJacobian(x, u, u_dot, kGravity_W, dh_dx, dh_du);
  MatrixXd Dq(n, n), Dqdot(n, n);
  for (Index j = 0; j < n; ++j) {
    VectorXd x_plus = x, x_minus = x, u_plus = u, u_minus = u;
    x_plus(7 + j) += kIncrement;
    x_minus(7 + j) -= kIncrement;
    u_plus(6 + j) += kIncrement;
    u_minus(6 + j) -= kIncrement;
    Dq.col(j) = (h(x_plus, u) - h(x_minus, u)).tail(n) / (2.0 * kIncrement);
    Dqdot.col(j) = (h(x, u_plus) - h(x, u_minus)).tail(n) / (2.0 * kIncrement);
  }
  const double in_q = RelativeDifference(dh_dx.bottomRightCorner(n, n), Dq);
  const double in_qdot = RelativeDifference(dh_du.bottomRightCorner(n, n), Dqdot);
  std::printf("[ numbers  ] elastic row: relative difference %.1e in q, %.1e in qdot\n", in_q, in_qdot);
  EXPECT_LT(in_q, kExactTolerance);
  EXPECT_LT(in_qdot, kExactTolerance);
  // What the body leaves out: its rigid rows and the elastic row's rigid columns (all zero here).
  EXPECT_TRUE(dh_dx.topRows(6).isZero(0.0) && dh_dx.leftCols(6).isZero(0.0));
  EXPECT_TRUE(dh_du.topRows(6).isZero(0.0) && dh_du.leftCols(6).isZero(0.0));
}

/// The summed loads of the scene's force elements.
VectorXd ElementForces(const MultibodySystem& system, const VectorXd& y) {
  VectorXd h = VectorXd::Zero(system.num_velocities());
  for (int k = 0; k < system.num_force_elements(); ++k) system.force_element(k).AddForces(0.0, system, y, h);
  return h;
}

// The spring-damper and the bushing: exact in u at any state; in x where they carry no load
// (what they leave out is the load times the rotation of their levers and of I).
TEST(SystemJacobian, ForceElementsMatchDifferences) {
  const Scene scene = MakeScene();
  const MultibodySystem& system = *scene.system;
  const Index nu = system.num_velocities();
  const auto element_jacobian = [&](const VectorXd& y) {
    MatrixXd dh = MatrixXd::Zero(nu, 2 * nu);
    for (int k = 0; k < system.num_force_elements(); ++k) {
      system.force_element(k).AddForceJacobian(0.0, system, y, dh.leftCols(nu), dh.rightCols(nu));
    }
    return dh;
  };
  const auto differences = [&](const VectorXd& y) {
    return VelocitySpaceDifferences(system, y, nu, [&](const VectorXd& at, VectorXd& h) { h = ElementForces(system, at); });
  };

  const VectorXd y = GenericState(scene, 3);
  const double in_u = RelativeDifference(element_jacobian(y).rightCols(nu), differences(y).rightCols(nu));

  // Unloaded: the block's mount frame on the beam's corner frame, the spring at its free length,
  // the beam and the block translating together (no rotation rates, no elastic rates).
  VectorXd y0 = GenericState(scene, 4);
  const Index nx = system.num_positions();
  const Index beam_u = nx + system.velocity_offset(scene.beam);
  const Vector3d ground_end(0.3, 0.0, 0.4);
  const MarkerKinematics mid = system.MarkerState(system.Marker("beam", "mid"), y0);
  const Vector3d along = (ground_end - mid.p_WM_W).normalized();
  y0.segment(beam_u + 3, system.body(scene.beam).num_velocities() - 3).setZero();
  y0.segment<3>(beam_u) -= along.dot(y0.segment<3>(beam_u)) * along;  // no stretch rate
  const MarkerKinematics corner = system.MarkerState(system.Marker("beam", "corner"), y0);
  const Eigen::Quaterniond e_block(corner.R_WM);  // the mount marker has R_BM = I
  VectorXd x_block(7), u_block = VectorXd::Zero(6);
  x_block << corner.p_WM_W - corner.R_WM * Vector3d(0.04, 0.03, -0.02), e_block.w(), e_block.x(), e_block.y(), e_block.z();
  u_block.head<3>() = y0.segment<3>(beam_u);
  system.SetBodyState(scene.block, x_block, u_block, y0);
  // The spring's ground end sits at its free length 0.3 m from the mid node: move both bodies so.
  const Vector3d shift = ground_end - 0.3 * along - mid.p_WM_W;
  for (const int b : {scene.beam, scene.block}) y0.segment<3>(system.position_offset(b)) += shift;
  ASSERT_LT(ElementForces(system, y0).norm(), 1e-6);  // [N]: round-off of the 1e6 N/m bushing
  const double in_x = RelativeDifference(element_jacobian(y0).leftCols(nu), differences(y0).leftCols(nu));
  std::printf("[ numbers  ] force elements: relative difference %.1e in u (any state), %.1e in x (unloaded)\n", in_u,
              in_x);
  EXPECT_LT(in_u, kExactTolerance);
  EXPECT_LT(in_x, kExactTolerance);
}

// The u' rows are A [dh/dx, dh/du] - Z [omega^2 G, 2 omega G] with A = M^-1 - Z G M^-1,
// Z = M^-1 G^T S^-1: formed here densely from the mass matrices and G, with the bodies' and
// elements' pieces, on every column but the bodies' v and w_B (differences: the next test). The
// Euler-parameter columns have no component along e.
TEST(SystemJacobian, AccelerationRowsAreTheConstrainedOperator) {
  const Scene scene = MakeScene();
  const MultibodySystem& system = *scene.system;
  const VectorXd y = GenericState(scene, 5);
  const Index n_y = system.state_size(), nu = system.num_velocities();
  MatrixXd dfdy(n_y, n_y);
  SystemJacobian(system, 0.1, y, dfdy);

  MatrixXd M = MatrixXd::Zero(nu, nu);
  for (int b = 0; b < system.num_bodies(); ++b) {
    const Index pu = system.velocity_offset(b), n = system.body(b).num_velocities();
    M.block(pu, pu, n, n) = system.BodyMassMatrix(b, y);
  }
  const MatrixXd G = system.Constraints(0.1, y).G;
  const MatrixXd M_inverse = M.inverse();
  const MatrixXd Z = M_inverse * G.transpose() * (G * M_inverse * G.transpose()).inverse();
  const MatrixXd A = M_inverse - Z * G * M_inverse;
  VectorXd u_dot(nu), lambda(system.num_constraints());
  system.Accelerations(0.1, y, u_dot, lambda);
  MatrixXd dh = MatrixXd::Zero(nu, 2 * nu);
  for (int b = 0; b < system.num_bodies(); ++b) {
    const Index pu = system.velocity_offset(b), n = system.body(b).num_velocities();
    system.body(b).AddForceJacobian(system.BodyPositions(y, b), system.BodyVelocities(y, b), u_dot.segment(pu, n),
                                    kGravity_W, dh.block(pu, pu, n, n), dh.block(pu, nu + pu, n, n));
  }
  for (int k = 0; k < system.num_force_elements(); ++k) {
    system.force_element(k).AddForceJacobian(0.1, system, y, dh.leftCols(nu), dh.rightCols(nu));
  }
  const double omega = system.constraint_settings().baumgarte_frequency;
  MatrixXd expected = A * dh;
  expected.leftCols(nu) -= omega * omega * Z * G;
  expected.rightCols(nu) -= 2.0 * omega * Z * G;
  std::vector<Index> model_columns;
  for (int b = 0; b < system.num_bodies(); ++b) {
    const Index pu = system.velocity_offset(b), n = system.body(b).num_velocities();
    for (Index k = 0; k < n; ++k) model_columns.push_back(pu + k);
    for (Index k = 6; k < n; ++k) model_columns.push_back(nu + pu + k);
  }
  const double difference = RelativeDifference(VelocitySpaceRows(system, y, dfdy)(Eigen::all, model_columns),
                                               expected(Eigen::all, model_columns));
  double across_sphere = 0.0;
  for (int b = 0; b < system.num_bodies(); ++b) {
    const Index px = system.position_offset(b);
    across_sphere = std::max(across_sphere, (dfdy.middleCols(px + 3, 4) * y.segment<4>(px + 3)).cwiseAbs().maxCoeff());
  }
  std::printf("[ numbers  ] u' rows but the v, w_B columns, against the dense operator: relative difference %.1e; "
              "Euler-parameter columns along e %.1e\n",
              difference,
              across_sphere / dfdy.cwiseAbs().maxCoeff());
  EXPECT_LT(difference, kOperatorTolerance);
  EXPECT_LT(across_sphere, kOperatorTolerance * dfdy.cwiseAbs().maxCoeff());
}

// The central-difference Jacobian of the whole rhs minus the model, relative to the largest
// model entry in the elastic columns (the stiff ones, 1.7e10 s^-2: the Craig-Bampton constraint
// modes). In the bodies' v and w_B columns the model is itself differences of u' (forward,
// sqrt(eps) increments): they agree. Elsewhere it leaves out the derivatives of A (dM/dx, dG/dx),
// of gamma, of the rigid rows' inertia and gravity terms and the loaded elements' lever
// rotations: first order in the deformation, down to a floor of the motion's own rates (w^2,
// g / L, the elements' loads), far below the stiff entries.
TEST(SystemJacobian, OmittedEntriesAreSmallAgainstTheStiffOnes) {
  const Scene scene = MakeScene();
  const MultibodySystem& system = *scene.system;
  const Index n_y = system.state_size(), nu = system.num_velocities();
  std::vector<Index> elastic, rigid_positions, rigid_velocities;
  for (int b = 0; b < system.num_bodies(); ++b) {
    const Index pu = system.velocity_offset(b), n = system.body(b).num_velocities();
    for (Index k = 0; k < n; ++k) {
      (k < 6 ? rigid_positions : elastic).push_back(pu + k);
      (k < 6 ? rigid_velocities : elastic).push_back(nu + pu + k);
    }
  }
  // The shares [elastic, rigid positions, rigid velocities] at a deformation.
  const auto shares = [&](double deformation) {
    const VectorXd y = GenericState(scene, 6, deformation);
    MatrixXd dfdy(n_y, n_y);
    SystemJacobian(system, 0.1, y, dfdy);
    const MatrixXd model = VelocitySpaceRows(system, y, dfdy);
    const MatrixXd full = VelocitySpaceDifferences(system, y, nu, [&](const VectorXd& at, VectorXd& u_dot) {
      VectorXd y_dot(n_y);
      system.Derivative(0.1, at, y_dot);
      u_dot = y_dot.tail(nu);
    });
    const double stiff = model(Eigen::all, elastic).cwiseAbs().maxCoeff();
    const auto share = [&](const std::vector<Index>& columns) {
      return (full - model)(Eigen::all, columns).cwiseAbs().maxCoeff() / stiff;
    };
    const std::array<double, 3> out{share(elastic), share(rigid_positions), share(rigid_velocities)};
    std::printf("[ numbers  ] deformation %.0e: omitted / largest stiff entry (%.3g): %.1e in the elastic columns, "
                "%.1e in the rigid position columns, %.1e in the v, w_B columns\n",
                deformation, stiff, out[0], out[1], out[2]);
    return out;
  };
  const std::array<double, 3> at_4 = shares(1e-4), at_5 = shares(1e-5), at_6 = shares(1e-6);
  for (const auto& at : {at_4, at_5, at_6}) EXPECT_LT(at[2], kExactTolerance);
  // First order: 10x less deformation, 10x less (measured 0.10), up to the floor's share.
  constexpr double kLinearShare = 0.2;
  EXPECT_LT(at_5[0], kLinearShare * at_4[0]);
  // The floor (measured 5.6e-5 in the elastic columns): w^2 ~ 10 s^-2, g / L and the loads x
  // levers through M^-1, against the constraint modes' 1.7e10 s^-2.
  constexpr double kFloorShare = 1e-4;
  EXPECT_LT(at_6[0], kFloorShare);
  for (const auto& at : {at_4, at_5, at_6}) EXPECT_LT(at[1], kFloorShare);
}

// ----- the stiff run the model Jacobian exists for

// The link of tests/validation/stiff_modes_test.cc: the slender steel link of
// flexible_pendulum_model.h with three low modes (4.3 .. 27.9 Hz) and three above 100 kHz, its
// frame carried at 2 m/s along W x by a driven prismatic joint, horizontally, under gravity; the
// ESDIRK at a fixed step of 6e-4 s (w h >= 667 on the stiff modes). With ARKODE's difference
// quotients (increments scaled by atol) Newton fails there at atol / rtol <= 1e-4.
struct TranslatingLink {
  std::unique_ptr<MultibodySystem> system;
  VectorXd y0;
};

TranslatingLink MakeTranslatingLink() {
  static const sid::ReducedBody link = [] {
    const validation::FeLink fe = validation::BuildLink(validation::LinkGeometry{});
    return RestrictModes(fe.body, {0, 1, 2, 48, 60, 204});
  }();
  TranslatingLink out;
  out.system = std::make_unique<MultibodySystem>(kGravity_W);
  MultibodySystem& system = *out.system;
  system.AddBody(std::make_unique<FlexibleBody>("link", link, false));
  Matrix3d R_WI;  // I's x (the link) along W y, y along W z, z (the slide) along W x
  R_WI << Vector3d::UnitY(), Vector3d::UnitZ(), Vector3d::UnitX();
  system.AddJoint(Joint("slide", JointType::kPrismatic, MarkerRef::Ground(Vector3d::Zero(), R_WI),
                        system.Marker("link", FlexibleBody::kOriginMarker), MakeRamp(0.0, 2.0)));
  const Index n = link.num_modes();
  VectorXd x = VectorXd::Zero(7 + n), u = VectorXd::Zero(6 + n);
  const Eigen::Quaterniond e(R_WI);
  x.segment<4>(3) << e.w(), e.x(), e.y(), e.z();
  for (Index k = 0; k < n; ++k) x(7 + k) = k < 3 ? 1e-3 : 1e-8;
  u(0) = 2.0;
  out.y0 = system.NeutralState();
  system.SetBodyState(0, x, u, out.y0);
  return out;
}

struct LinkRun {
  VectorXd y_end;
  SimulationStatistics statistics;
};

LinkRun RunLink(double relative_tolerance, double absolute_tolerance, OdeJacobian jacobian, double end_time) {
  TranslatingLink link = MakeTranslatingLink();
  SimulationOptions options;
  options.integrator.method = OdeMethod::kImplicit;
  options.integrator.fixed_step = 6e-4;
  options.integrator.relative_tolerance = relative_tolerance;
  options.integrator.absolute_tolerance = absolute_tolerance;
  options.integrator.jacobian = jacobian;
  options.end_time = end_time;
  options.output_interval = end_time;
  LinkRun run;
  run.statistics = Simulate(*link.system, options, link.y0, [&](double, const VectorXd& y, const VectorXd&) { run.y_end = y; });
  return run;
}

void Print(const char* what, const SimulationStatistics& s) {
  std::printf("[ numbers  ] %s: %ld steps, %ld rhs, %ld Newton iterations, %ld Jacobians, %.3f s\n", what,
              s.integrator.steps, s.integrator.rhs_evaluations, s.integrator.newton_iterations,
              s.integrator.jacobian_evaluations, s.wall_seconds);
}

// Newton with the model Jacobian runs at rtol 1e-12, atol 1e-15 (difference quotients fail there
// with ARK_CONV_FAILURE, at 0.037 s; at any atol / rtol <= 1e-4 too) and reaches the state of a
// run at rtol 1e-10, atol 1e-12 (both solve the same stage equations on the same fixed steps).
// atol 1e-16 fails with either Jacobian early in the run, for any rtol from 1e-10 to 1e-14 (at
// 0.0002 s with the model Jacobian, 0.0018 s with difference quotients; the time depends on the
// round-off of the operation order): below the round-off of the stage residual (eps |v| =
// 4.4e-16 m/s at 2 m/s), not a Jacobian's doing. atol 1e-15 is within a factor 2.3 of that
// floor: the run at it depends on round-off too (a Schur solve of all columns at once instead of
// one by one made it fail at 0.108 s). The three failing runs are asserted to fail as said.
TEST(SystemJacobian, StiffModesRunAtTightTolerances) {
  constexpr double kEndTime = 0.3;  // 500 steps
  const LinkRun tight = RunLink(1e-12, 1e-15, OdeJacobian::kModel, kEndTime);
  const LinkRun reference = RunLink(1e-10, 1e-12, OdeJacobian::kModel, kEndTime);
  Print("rtol 1e-12, atol 1e-15, model Jacobian", tight.statistics);
  Print("rtol 1e-10, atol 1e-12, model Jacobian", reference.statistics);
  for (const double atol : {1e-15, 1e-16}) {
    for (const OdeJacobian jacobian : {OdeJacobian::kModel, OdeJacobian::kDifferenceQuotients}) {
      if (atol == 1e-15 && jacobian == OdeJacobian::kModel) continue;
      const char* name = jacobian == OdeJacobian::kModel ? "model Jacobian" : "difference quotients";
      char what[80];
      std::snprintf(what, sizeof what, "rtol 1e-12, atol %g, %s", atol, name);
      std::string failure = "no failure";
      try {
        Print(what, RunLink(1e-12, atol, jacobian, kEndTime).statistics);
      } catch (const SimulationError& error) {
        failure = error.what();
      }
      std::printf("[ numbers  ] %s: %s\n", what, failure.c_str());
      EXPECT_NE(failure.find("ARK_CONV_FAILURE"), std::string::npos) << what << ": " << failure;
    }
  }
  // The low modes after 500 steps: the runs differ by their Newton errors (measured 2.3e-14 in q,
  // 1.1e-13 in qdot, relative to the largest; was asserted at 1e-6).
  constexpr double kRunAgreement = 1e-12;
  const Index nx = 7 + 6;
  for (const Index offset : {Index{7}, nx + 6}) {  // q, qdot of modes 1 .. 3
    const VectorXd a = tight.y_end.segment<3>(offset), b = reference.y_end.segment<3>(offset);
    const double difference = (a - b).cwiseAbs().maxCoeff();
    std::printf("[ numbers  ] low modes' %s at the end: max |tight - reference| %.2e of %.2e\n",
                offset == 7 ? "q" : "qdot", difference, b.cwiseAbs().maxCoeff());
    EXPECT_LT(difference, kRunAgreement * b.cwiseAbs().maxCoeff());
  }
}

// The scene key simulation.jacobian: model (the default) or difference_quotients.
TEST(SystemJacobian, SceneChoosesTheJacobian) {
  const auto load = [](const std::string& line) { return flexmbs::testing::LoadImplicitIntegratorOptions(line).jacobian; };
  EXPECT_EQ(load(""), OdeJacobian::kModel);
  EXPECT_EQ(load("  jacobian: model\n"), OdeJacobian::kModel);
  EXPECT_EQ(load("  jacobian: difference_quotients\n"), OdeJacobian::kDifferenceQuotients);
  const std::string message = flexmbs::testing::InputErrorMessage([&] { load("  jacobian: analytic\n"); });
  EXPECT_NE(message.find("'analytic' must be one of: model, difference_quotients"), std::string::npos) << message;
}

}  // namespace
}  // namespace flexmbs::mbs
