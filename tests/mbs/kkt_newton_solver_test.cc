// The sparse Newton solve of the implicit integrator (mbs/kkt_newton_solver.h): against the dense
// solve of I - gamma J with the model Jacobian (SystemJacobian, its v and w_B columns formed
// densely here as the sparse solve models them: the constrained operator on differences of each
// body's forces and of the joints' terms), on a loop of flexible links with a rigid body and
// force elements; those columns against central differences of the accelerations; then whole runs
// with the sparse Newton against the dense one, on a chain of flexible links and on the stiff-mode
// link of tests/validation/stiff_modes_test.cc; the option's choice and the scene key.
//
// The loop: three Craig-Bampton beams of flexible_test_bodies.h (6 constraint + 4 normal modes,
// Rayleigh damping, geometric stiffening on) hinged to the ground and to each other, the third
// on a ball joint and closed to the ground by another; a rigid block on a universal joint at the
// first beam's mid node; a spring-damper between the first and third beams' mid nodes (bodies
// that share no joint) and a bushing between the block and the second beam's corner node.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <vector>


#include "mbs/flexible_body.h"
#include "mbs/force_element.h"
#include "mbs/joint.h"
#include "mbs/kkt_newton_solver.h"
#include "mbs/mode_selection.h"
#include "mbs/multibody_system.h"
#include "mbs/ode_integrator.h"
#include "mbs/rigid_body.h"
#include "mbs/simulation.h"
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

const Vector3d kGravity_W(0.0, 0.0, -9.81);

/// The loop of the file comment, Baumgarte frequency 300 rad/s.
std::unique_ptr<MultibodySystem> MakeLoop(bool stiffening = true) {
  auto system = std::make_unique<MultibodySystem>(kGravity_W);
  const sid::ReducedBody& beam = testing::CraigBamptonBeam().body;
  for (const char* name : {"link0", "link1", "link2"}) {
    system->AddBody(std::make_unique<FlexibleBody>(name, beam, stiffening));
  }
  const double a = 0.05;  // the block's half edge [m]
  system->AddBody(std::make_unique<RigidBody>(
      "block", 8.0, Vector3d(0.02, 0.0, 0.0), (8.0 * a * a * 2.0 / 3.0) * Matrix3d::Identity(),
      std::vector<RigidBodyMarker>{{"hinge", Vector3d::Zero(), Matrix3d::Identity()},
                                   {"mount", Vector3d(0.04, 0.03, -0.02), Matrix3d::Identity()}}));
  const std::string origin(FlexibleBody::kOriginMarker);
  system->AddJoint(Joint("hinge0", JointType::kRevolute, MarkerRef::Ground(Vector3d::Zero()), system->Marker("link0", origin)));
  system->AddJoint(Joint("hinge1", JointType::kRevolute, system->Marker("link0", "tip"), system->Marker("link1", origin)));
  system->AddJoint(Joint("ball2", JointType::kSpherical, system->Marker("link1", "tip"), system->Marker("link2", origin)));
  system->AddJoint(Joint("close", JointType::kSpherical, system->Marker("link2", "tip"),
                         MarkerRef::Ground(Vector3d(0.9, 0.3, -0.2))));
  system->AddJoint(Joint("cardan", JointType::kUniversal, system->Marker("link0", "mid"), system->Marker("block", "hinge")));
  system->AddForceElement(
      std::make_unique<SpringDamper>("spring", system->Marker("link0", "mid"), system->Marker("link2", "mid"), 0.3, 2e5, 50.0));
  Eigen::Matrix<double, 6, 1> stiffness, damping;
  stiffness << 1e6, 2e6, 3e6, 1e4, 2e4, 3e4;
  damping << 1e2, 2e2, 3e2, 1.0, 2.0, 3.0;
  system->AddForceElement(
      std::make_unique<Bushing>("mount", system->Marker("block", "mount"), system->Marker("link1", "corner"), stiffness, damping));
  system->set_constraint_settings({300.0, 1e-10});
  return system;
}

/// A state off every equilibrium and joint: bodies placed and turned at random, deformed by up
/// to `deformation` per modal coordinate, angular velocities ~3 rad/s, elastic rates ~0.03.
VectorXd GenericState(const MultibodySystem& system, unsigned seed, double deformation = 1e-4) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  VectorXd y = system.NeutralState();
  for (int b = 0; b < system.num_bodies(); ++b) {
    const Index px = system.position_offset(b), pu = system.num_positions() + system.velocity_offset(b);
    const Index n = system.body(b).num_modes();
    y.segment<3>(px) = 0.3 * flexmbs::testing::DrawVector3(uniform, rng);
    const double angle = 1.5 * uniform(rng);
    const Eigen::Quaterniond e(Eigen::AngleAxisd(angle, flexmbs::testing::DrawVector3(uniform, rng).normalized()));
    y.segment<4>(px + 3) << e.w(), e.x(), e.y(), e.z();
    for (Index k = 0; k < n; ++k) y(px + 7 + k) = deformation * uniform(rng);
    for (Index k = 0; k < 6 + n; ++k) y(pu + k) = (k < 6 ? 3.0 : 0.03) * uniform(rng);
  }
  return y;
}

/// The forward-difference increment of velocity u_j: SystemJacobian's, sqrt(eps) max(|u_j|, 1).
double Increment(double u_j) { return std::sqrt(std::numeric_limits<double>::epsilon()) * std::max(std::abs(u_j), 1.0); }

/// The u' rows' v and w_B columns the sparse solve models (num_velocities() x 6 per body, in the
/// bodies' order): A dh/du + Z (dgamma_c/du - 2 omega G), formed densely here (A = M^-1 - Z G M^-1,
/// Z = M^-1 G^T S^-1 over the kept rows, from the mass matrices and G), with dh/du the force
/// elements' and, in these columns, forward differences of each body's forces, and dgamma_c/du
/// forward differences of the stacked joint terms (system.Constraints at moved velocities).
MatrixXd ModelledVelocityColumns(const MultibodySystem& system, double t, const VectorXd& y) {
  const Index nx = system.num_positions(), nu = system.num_velocities();
  MatrixXd M = MatrixXd::Zero(nu, nu);
  for (int b = 0; b < system.num_bodies(); ++b) {
    const Index pu = system.velocity_offset(b), n = system.body(b).num_velocities();
    M.block(pu, pu, n, n) = system.BodyMassMatrix(b, y);
  }
  const std::vector<Index> kept = system.KeptConstraints();
  const SystemConstraints c = system.Constraints(t, y);
  const MatrixXd G = c.G(kept, Eigen::all);
  const MatrixXd M_inverse = M.inverse();
  const MatrixXd Z = M_inverse * G.transpose() * (G * M_inverse * G.transpose()).inverse();
  const MatrixXd A = M_inverse - Z * G * M_inverse;
  VectorXd u_dot(nu), lambda(system.num_constraints());
  system.Accelerations(t, y, u_dot, lambda);
  MatrixXd dh_dx = MatrixXd::Zero(nu, nu), dh_du = MatrixXd::Zero(nu, nu);
  for (int k = 0; k < system.num_force_elements(); ++k) system.force_element(k).AddForceJacobian(t, system, y, dh_dx, dh_du);
  MatrixXd dgamma_du = MatrixXd::Zero(static_cast<Index>(kept.size()), nu);
  for (int b = 0; b < system.num_bodies(); ++b) {
    const Body& body = system.body(b);
    const Index pu = system.velocity_offset(b), n = body.num_velocities();
    const VectorXd x_b = system.BodyPositions(y, b), u_b = system.BodyVelocities(y, b);
    const auto h = [&](const VectorXd& u) {
      VectorXd out(n);
      body.Forces(t, x_b, u, system.gravity(), out);
      body.AddAccelerationDependentForces(x_b, u, u_dot.segment(pu, n), out);
      return out;
    };
    for (Index k = 0; k < 6; ++k) {
      const double increment = Increment(u_b(k));
      VectorXd u_moved = u_b, y_moved = y;
      u_moved(k) += increment;
      y_moved(nx + pu + k) += increment;
      dh_du.block(pu, pu + k, n, 1) += (h(u_moved) - h(u_b)) / increment;
      dgamma_du.col(pu + k) = (system.Constraints(t, y_moved).gamma(kept) - c.gamma(kept)) / increment;
    }
  }
  const double omega = system.constraint_settings().baumgarte_frequency;
  const MatrixXd du_dot_du = A * dh_du + Z * (dgamma_du - 2.0 * omega * G);
  MatrixXd out(nu, 6 * system.num_bodies());
  for (int b = 0; b < system.num_bodies(); ++b) out.middleCols(6 * b, 6) = du_dot_du.middleCols(system.velocity_offset(b), 6);
  return out;
}

/// I - gamma J with the J the sparse solve models: SystemJacobian, its u' rows' v and w_B columns
/// (forward differences of the whole u' there) replaced by ModelledVelocityColumns.
MatrixXd DenseNewtonMatrix(const MultibodySystem& system, double t, const VectorXd& y, double gamma) {
  const Index n_y = system.state_size(), nx = system.num_positions(), nu = system.num_velocities();
  MatrixXd J(n_y, n_y);
  SystemJacobian(system, t, y, J);
  const MatrixXd columns = ModelledVelocityColumns(system, t, y);
  for (int b = 0; b < system.num_bodies(); ++b) {
    J.block(nx, nx + system.velocity_offset(b), nu, 6) = columns.middleCols(6 * b, 6);
  }
  return MatrixXd::Identity(n_y, n_y) - gamma * J;
}

/// max |modelled - central differences of u'| / max |central differences| over the u' rows' v,
/// w_B columns. Increments of 1e-4 m/s, rad/s: what u' does in these columns is at most quadratic
/// in u (gyroscopic, centrifugal and the joints' velocity terms), so central differences are exact
/// but for round-off, eps |u'| / 1e-4 ~ 1e-5 s^-1 against entries of 1e4 s^-1.
double VelocityColumnsDifference(const MultibodySystem& system, const VectorXd& y) {
  constexpr double kCentralIncrement = 1e-4, kTime = 0.1;
  const Index nx = system.num_positions(), nu = system.num_velocities();
  MatrixXd central(nu, 6 * system.num_bodies());
  VectorXd u_dot_plus(nu), u_dot_minus(nu), lambda(system.num_constraints());
  for (int b = 0; b < system.num_bodies(); ++b) {
    for (Index k = 0; k < 6; ++k) {
      VectorXd plus = y, minus = y;
      plus(nx + system.velocity_offset(b) + k) += kCentralIncrement;
      minus(nx + system.velocity_offset(b) + k) -= kCentralIncrement;
      system.Accelerations(kTime, plus, u_dot_plus, lambda);
      system.Accelerations(kTime, minus, u_dot_minus, lambda);
      central.col(6 * b + k) = (u_dot_plus - u_dot_minus) / (2.0 * kCentralIncrement);
    }
  }
  return (ModelledVelocityColumns(system, kTime, y) - central).cwiseAbs().maxCoeff() / central.cwiseAbs().maxCoeff();
}

// The v, w_B columns the sparse solve models (differences of each body's forces and each joint's
// terms, put through the constrained operator) are du'/du there: against central differences of
// the accelerations. (SystemJacobian's forward differences of u' in these columns are further
// from them: 2.4e-5 at the first state, their round-off.) What neither local difference sees is
// the geometric stiffening's acceleration corrector: u' takes h_a = -N u'_0 at the first solve's
// u'_0, which moves with u too (A N du'_0/du), first order in the deformation (N ~ q): without
// stiffening the columns agree to the differences' accuracy, with it the gap falls with the
// deformation.
TEST(KktNewtonSolver, VelocityColumnsAreTheAccelerationsDerivative) {
  // 1e-6 of the largest entry for differenced entries. The modelled columns' own
  // forward differences (sqrt(eps) increments) round off eps |h| / increment, |h| carrying the
  // stiff elastic forces Ke q: measured 1e-5 of the largest entry at q ~ 1e-3, 1e-6 at 1e-4,
  // 1e-7 at 1e-5 (proportional to q, down to 2e-8): compared at q ~ 1e-5.
  constexpr double kDifferenceTolerance = 1e-6, kDeformation = 1e-5;
  const auto unstiffened = MakeLoop(false);
  for (const unsigned seed : {1u, 2u}) {
    const double difference =
        VelocityColumnsDifference(*unstiffened, GenericState(*unstiffened, seed, kDeformation));
    std::printf("[ numbers  ] no stiffening, state %u: v, w_B columns, max |modelled - central| / max |entry| = %.1e\n",
                seed, difference);
    EXPECT_LT(difference, kDifferenceTolerance);
  }
  const auto stiffened = MakeLoop(true);
  const double at_4 = VelocityColumnsDifference(*stiffened, GenericState(*stiffened, 1, 10.0 * kDeformation));
  const double at_5 = VelocityColumnsDifference(*stiffened, GenericState(*stiffened, 1, kDeformation));
  std::printf("[ numbers  ] stiffening: max |modelled - central| / max |entry| = %.1e at deformation 1e-4, %.1e at "
              "1e-5\n",
              at_4, at_5);
  // First order: 10x less deformation, about 10x less (bounded at 0.2 against the floor above).
  EXPECT_LT(at_5, 0.2 * at_4);
}

struct SolveComparison {
  double difference = 0.0;  ///< max |x_sparse - x_dense| / max |x_dense|
  double residual = 0.0;    ///< max |N x_sparse - r| / (max |N| max |x_sparse|), N the dense matrix
  double condition = 0.0;   ///< sigma_max / sigma_min of N
};

/// Both solves of N x = r for a random r (every component, the Euler parameters' along e too).
SolveComparison CompareSolves(const MultibodySystem& system, const VectorXd& y, double gamma, unsigned seed) {
  constexpr double kTime = 0.1;
  const MatrixXd N = DenseNewtonMatrix(system, kTime, y, gamma);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  VectorXd r(N.rows());
  for (Index i = 0; i < r.size(); ++i) r(i) = uniform(rng);
  const VectorXd dense = N.partialPivLu().solve(r);
  KktNewtonSolver solver(system);
  solver.Evaluate(kTime, y);
  solver.Factorize(gamma);
  VectorXd sparse = r;
  solver.Solve(sparse);
  const Eigen::JacobiSVD<MatrixXd> svd(N);
  SolveComparison out;
  out.difference = (sparse - dense).cwiseAbs().maxCoeff() / dense.cwiseAbs().maxCoeff();
  out.residual = (N * sparse - r).cwiseAbs().maxCoeff() / (N.cwiseAbs().maxCoeff() * sparse.cwiseAbs().maxCoeff());
  out.condition = svd.singularValues()(0) / svd.singularValues()(svd.singularValues().size() - 1);
  return out;
}

// The two solves agree to round-off (the sparse solve's differences are the same ones, of the
// same functions, at the same increments): the sparse solution's residual in the dense matrix is a
// small multiple of eps (a backward-stable solve of an equivalent system), and the solutions
// differ by at most that times the condition number. Gammas from 1e-6 s (N ~ I) to 0.3 s (the
// stiff entries, 1.7e10 s^-2, times gamma^2 ~ 1.5e9; gamma |w_B| / 2 ~ 0.5 in the quaternion
// block).
TEST(KktNewtonSolver, SolveEqualsTheDenseSolveOfTheModelJacobian) {
  const auto system = MakeLoop();
  // Backward error of an LU solve: a modest multiple of eps (Higham: n eps times the growth).
  constexpr double kBackwardTolerance = 1e3 * std::numeric_limits<double>::epsilon();
  for (const double gamma : {1e-6, 1e-4, 1e-2, 0.3}) {
    for (const unsigned seed : {1u, 2u}) {
      const VectorXd y = GenericState(*system, seed);
      const SolveComparison c = CompareSolves(*system, y, gamma, seed + 10);
      std::printf("[ numbers  ] gamma %.0e s, state %u: difference %.1e, residual %.1e, condition %.1e\n", gamma, seed,
                  c.difference, c.residual, c.condition);
      EXPECT_LT(c.residual, kBackwardTolerance);
      EXPECT_LT(c.difference, kBackwardTolerance * c.condition);
    }
  }
}

// With a row of the closing joint dropped (as a redundancy found at t0 would be): the equations
// of motion, SystemJacobian's operator and the sparse solve all leave it out.
TEST(KktNewtonSolver, DroppedRowsAreLeftOut) {
  const auto system = MakeLoop();
  const Index close_row = system->constraint_offset(3) + 2;
  system->set_dropped_constraints({close_row});
  const VectorXd y = GenericState(*system, 3);
  constexpr double kBackwardTolerance = 1e3 * std::numeric_limits<double>::epsilon();
  const SolveComparison c = CompareSolves(*system, y, 1e-3, 7);
  std::printf("[ numbers  ] row %ld dropped: difference %.1e, residual %.1e, condition %.1e\n",
              static_cast<long>(close_row), c.difference, c.residual, c.condition);
  EXPECT_LT(c.residual, kBackwardTolerance);
  EXPECT_LT(c.difference, kBackwardTolerance * c.condition);
}

// The augmented matrix is sparse: per body its mass block, per joint row its bodies' columns,
// per force element the blocks of the bodies it couples.
TEST(KktNewtonSolver, AugmentedMatrixHasTheMechanismsPattern) {
  const auto system = MakeLoop();
  KktNewtonSolver solver(*system);
  solver.Evaluate(0.0, GenericState(*system, 4));
  solver.Factorize(1e-3);
  const Eigen::SparseMatrix<double>& kkt = solver.augmented_matrix();
  const Index nu = system->num_velocities(), m = system->num_constraints();
  ASSERT_EQ(kkt.rows(), nu + m);
  // Upper bound on the nonzeros: the body blocks, the spring's and the bushing's couplings
  // (link0-link2 and block-link1, both ways), and G and its transform (two bodies per row).
  const Index flexible = 16, rigid = 6;
  const Index bodies = 3 * flexible * flexible + rigid * rigid;
  const Index elements = 2 * flexible * flexible + 2 * rigid * flexible;
  Index rows = 0;
  for (int k = 0; k < system->num_joints(); ++k) {
    const Joint& joint = system->joint(k);
    Index columns = 0;
    for (const MarkerRef* marker : {&joint.marker_i(), &joint.marker_j()}) {
      if (!marker->is_ground()) columns += system->body(marker->body).num_velocities();
    }
    rows += 2 * joint.num_equations() * columns;
  }
  std::printf("[ numbers  ] augmented matrix %ld x %ld: %ld nonzeros (bound %ld, dense %ld)\n", static_cast<long>(kkt.rows()),
              static_cast<long>(kkt.cols()), static_cast<long>(kkt.nonZeros()), static_cast<long>(bodies + elements + rows),
              static_cast<long>(kkt.rows() * kkt.cols()));
  EXPECT_LE(kkt.nonZeros(), bodies + elements + rows);
}

// ----- whole runs

/// A chain of `count` Craig-Bampton beams hinged end to end (the first to the ground), all along
/// W x and at rest at t = 0, falling under gravity; Rayleigh damping overdamps the stiff
/// constraint modes.
std::unique_ptr<MultibodySystem> MakeChain(int count, VectorXd* y0) {
  auto system = std::make_unique<MultibodySystem>(kGravity_W);
  const sid::ReducedBody& beam = testing::CraigBamptonBeam().body;
  const std::string origin(FlexibleBody::kOriginMarker);
  const Matrix3d R_WI = Eigen::AngleAxisd(-0.5 * std::numbers::pi, Vector3d::UnitX()).toRotationMatrix();  // hinge axes along W y
  for (int k = 0; k < count; ++k) {
    const std::string name = "link" + std::to_string(k);
    system->AddBody(std::make_unique<FlexibleBody>(name, beam, true));
    const MarkerRef parent = k == 0 ? MarkerRef::Ground(Vector3d::Zero(), R_WI) : system->Marker("link" + std::to_string(k - 1), "tip");
    system->AddJoint(Joint("hinge" + std::to_string(k), JointType::kRevolute, parent, system->Marker(name, origin)));
  }
  // Each link's frame on its parent's tip marker (the tip face's centre).
  *y0 = system->NeutralState();
  const Eigen::Quaterniond e(R_WI);
  Vector3d p_W = Vector3d::Zero();
  for (int k = 0; k < count; ++k) {
    VectorXd x = VectorXd::Zero(7 + beam.num_modes());
    x.head<3>() = p_W;
    x.segment<4>(3) << e.w(), e.x(), e.y(), e.z();
    system->SetBodyState(k, x, VectorXd::Zero(6 + beam.num_modes()), *y0);
    p_W = system->MarkerState(system->Marker("link" + std::to_string(k), "tip"), *y0).p_WM_W;
  }
  return system;
}

struct ChainRun {
  VectorXd y_end;
  SimulationStatistics statistics;
};

// An implicit run of `system` from y0 to end_time [s] with the given Newton solve and tolerances.
ChainRun RunImplicit(MultibodySystem& system, const VectorXd& y0, OdeNewton newton, double relative_tolerance,
                     double absolute_tolerance, double end_time) {
  SimulationOptions options;
  options.integrator.method = OdeMethod::kImplicit;
  options.integrator.newton = newton;
  options.integrator.relative_tolerance = relative_tolerance;
  options.integrator.absolute_tolerance = absolute_tolerance;
  options.end_time = end_time;
  options.output_interval = end_time;
  ChainRun run;
  run.statistics = Simulate(system, options, y0, [&](double, const VectorXd& y, const VectorXd&) { run.y_end = y; });
  return run;
}

ChainRun RunChain(OdeNewton newton, double relative_tolerance, double absolute_tolerance, double end_time) {
  VectorXd y0;
  const auto system = MakeChain(4, &y0);
  return RunImplicit(*system, y0, newton, relative_tolerance, absolute_tolerance, end_time);
}

void Print(const char* what, const SimulationStatistics& s) {
  std::printf("[ numbers  ] %s: %ld steps, %ld rhs, %ld Newton iterations, %ld Jacobians, %ld setups, %.3f s\n", what,
              s.integrator.steps, s.integrator.rhs_evaluations, s.integrator.newton_iterations,
              s.integrator.jacobian_evaluations, s.integrator.newton_setups, s.wall_seconds);
}

// The sparse Newton against the dense one on the chain (state 132, 20 constraints): ARKODE takes
// the same steps and refreshes the same Jacobians with either (the solver plugs in as its dense
// one does), and the two runs end at the same state to the integrator's tolerance: their stage
// solutions differ only by the Newton errors (<= 0.1 rtol per stage) of two Jacobians that differ
// in the v, w_B difference columns, which the sparse solve leaves out.
TEST(KktNewtonSolver, ChainRunMatchesTheDenseNewton) {
  constexpr double kEndTime = 0.05, kRtol = 1e-6, kAtol = 1e-9;
  const ChainRun sparse = RunChain(OdeNewton::kSparse, kRtol, kAtol, kEndTime);
  const ChainRun dense = RunChain(OdeNewton::kDense, kRtol, kAtol, kEndTime);
  Print("sparse Newton", sparse.statistics);
  Print("dense Newton", dense.statistics);
  EXPECT_TRUE(sparse.statistics.integrator.sparse_newton);
  EXPECT_FALSE(dense.statistics.integrator.sparse_newton);
  const double scale = dense.y_end.cwiseAbs().maxCoeff();
  const double difference = (sparse.y_end - dense.y_end).cwiseAbs().maxCoeff() / scale;
  std::printf("[ numbers  ] at %.3g s: max |sparse - dense| / max |y| = %.1e\n", kEndTime, difference);
  EXPECT_LT(difference, kRtol);
  // Steps and Newton iterations within 2 % (measured: equal steps, 0.26 % more iterations).
  constexpr double kCountShare = 0.02;
  const auto ratio = [](long a, long b) { return static_cast<double>(a) / static_cast<double>(b); };
  EXPECT_NEAR(ratio(sparse.statistics.integrator.steps, dense.statistics.integrator.steps), 1.0, kCountShare);
  EXPECT_NEAR(ratio(sparse.statistics.integrator.newton_iterations, dense.statistics.integrator.newton_iterations), 1.0,
              kCountShare);
}

// The stiff-mode link of tests/validation/stiff_modes_test.cc (three low modes, three above
// 100 kHz, its frame driven along W x at 2 m/s) from a smooth start: with the sparse Newton the
// adaptive ESDIRK still steps over the stiff modes (mean step > 10 periods of 176.9 kHz) and ends
// where the dense Newton's run does.
TEST(KktNewtonSolver, StiffModesAreSteppedOver) {
  static const sid::ReducedBody link = [] {
    const validation::FeLink fe = validation::BuildLink(validation::LinkGeometry{});
    return RestrictModes(fe.body, {0, 1, 2, 48, 60, 204});
  }();
  constexpr double kLowestStiffHz = 176.9e3, kEndTime = 0.3, kRtol = 1e-8, kAtol = 1e-10;
  const auto run = [&](OdeNewton newton) {
    MultibodySystem system(kGravity_W);
    system.AddBody(std::make_unique<FlexibleBody>("link", link, false));
    Matrix3d R_WI;  // I's x (the link) along W y, y along W z, z (the slide) along W x
    R_WI << Vector3d::UnitY(), Vector3d::UnitZ(), Vector3d::UnitX();
    system.AddJoint(Joint("slide", JointType::kPrismatic, MarkerRef::Ground(Vector3d::Zero(), R_WI),
                          system.Marker("link", FlexibleBody::kOriginMarker), MakeRamp(0.0, 2.0)));
    VectorXd x = VectorXd::Zero(13), u = VectorXd::Zero(12);
    const Eigen::Quaterniond e(R_WI);
    x.segment<4>(3) << e.w(), e.x(), e.y(), e.z();
    x.segment<3>(7).setConstant(1e-3);  // the low modes deflected, the stiff ones at rest
    u(0) = 2.0;
    VectorXd y0 = system.NeutralState();
    system.SetBodyState(0, x, u, y0);
    return RunImplicit(system, y0, newton, kRtol, kAtol, kEndTime);
  };
  const ChainRun sparse = run(OdeNewton::kSparse);
  const ChainRun dense = run(OdeNewton::kDense);
  Print("stiff link, sparse Newton", sparse.statistics);
  Print("stiff link, dense Newton", dense.statistics);
  const double mean_step = kEndTime / static_cast<double>(sparse.statistics.integrator.steps);
  std::printf("[ numbers  ] sparse: mean step %.3g s = %.0f periods of %.4g Hz\n", mean_step, mean_step * kLowestStiffHz,
              kLowestStiffHz);
  EXPECT_TRUE(sparse.statistics.integrator.sparse_newton);
  EXPECT_GE(mean_step * kLowestStiffHz, 10.0);
  EXPECT_NEAR(static_cast<double>(sparse.statistics.integrator.steps) / static_cast<double>(dense.statistics.integrator.steps),
              1.0, 0.02);
  // The low modes' q and qdot: each run is within steps x 5 (2 rtol) of the motion, relative to
  // the mode's amplitude (the bound of stiff_modes_test's adaptive run: every accepted step's
  // error passes ARKODE's test, the oscillators do not amplify), so they are within twice that
  // of each other.
  const double bound = 2.0 * static_cast<double>(dense.statistics.integrator.steps) * 5.0 * 2.0 * kRtol;
  for (const Index offset : {Index{7}, Index{13 + 6}}) {
    const double difference = (sparse.y_end.segment<3>(offset) - dense.y_end.segment<3>(offset)).cwiseAbs().maxCoeff();
    const double scale = dense.y_end.segment<3>(offset).cwiseAbs().maxCoeff();
    std::printf("[ numbers  ] low modes' %s: max |sparse - dense| %.2e of %.2e (bound %.1e of it)\n",
                offset == 7 ? "q" : "qdot", difference, scale, bound);
    EXPECT_LT(difference, bound * scale);
  }
}

// ----- the option

OdeProblem Decay(Index size) {
  OdeProblem problem;
  problem.size = size;
  problem.rhs = [](double, Eigen::Ref<const VectorXd> y, Eigen::Ref<VectorXd> y_dot) { y_dot = -y; };
  return problem;
}

/// An OdeNewtonSolver of y' = -y: (1 + gamma) x = r.
class DecayNewton final : public OdeNewtonSolver {
 public:
  void Evaluate(double, Eigen::Ref<const VectorXd>) override { ++evaluations; }
  void Factorize(double gamma) override { gamma_ = gamma; }
  void Solve(Eigen::Ref<VectorXd> r) override { r /= 1.0 + gamma_; }
  int evaluations = 0;

 private:
  double gamma_ = 0.0;
};

// kAuto takes the problem's solver from kSparseNewtonFromSize on; kSparse needs one and the model
// Jacobian.
TEST(KktNewtonSolver, OptionChoosesTheSolver) {
  OdeOptions options;
  options.method = OdeMethod::kImplicit;
  for (const Index size : {kSparseNewtonFromSize - 1, kSparseNewtonFromSize}) {
    OdeProblem problem = Decay(size);
    auto newton = std::make_shared<DecayNewton>();
    problem.newton_solver = newton;
    OdeIntegrator integrator(std::move(problem), options, 0.0, VectorXd::Ones(size));
    integrator.Advance(1.0);
    const bool sparse = size >= kSparseNewtonFromSize;
    EXPECT_EQ(integrator.statistics().sparse_newton, sparse);
    EXPECT_EQ(newton->evaluations > 0, sparse);
    EXPECT_EQ(integrator.statistics().jacobian_evaluations > 0, true);
    // y = e^-t to the tolerances: rtol 1e-6 per step, over the run's few hundred steps.
    EXPECT_NEAR(integrator.state()(0), std::exp(-1.0), 1e-4);
  }
  options.newton = OdeNewton::kSparse;
  std::string message =
      flexmbs::testing::InputErrorMessage([&] { OdeIntegrator integrator(Decay(3), options, 0.0, VectorXd::Ones(3)); });
  EXPECT_NE(message.find("newton = sparse needs a problem with its own Newton solver"), std::string::npos) << message;
  options.jacobian = OdeJacobian::kDifferenceQuotients;
  OdeProblem problem = Decay(3);
  problem.newton_solver = std::make_shared<DecayNewton>();
  message = flexmbs::testing::InputErrorMessage([&] { OdeIntegrator integrator(std::move(problem), options, 0.0, VectorXd::Ones(3)); });
  EXPECT_NE(message.find("newton = sparse solves with the model Jacobian"), std::string::npos) << message;
}

// The scene key simulation.newton: auto (the default), dense or sparse.
TEST(KktNewtonSolver, SceneChoosesTheNewtonSolver) {
  const auto load = [](const std::string& line) { return flexmbs::testing::LoadImplicitIntegratorOptions(line).newton; };
  EXPECT_EQ(load(""), OdeNewton::kAuto);
  EXPECT_EQ(load("  newton: auto\n"), OdeNewton::kAuto);
  EXPECT_EQ(load("  newton: dense\n"), OdeNewton::kDense);
  EXPECT_EQ(load("  newton: sparse\n"), OdeNewton::kSparse);
  const std::string message = flexmbs::testing::InputErrorMessage([&] { load("  newton: klu\n"); });
  EXPECT_NE(message.find("'klu' must be one of: auto, dense, sparse"), std::string::npos) << message;
}

}  // namespace
}  // namespace flexmbs::mbs


