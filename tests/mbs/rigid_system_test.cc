// Rigid multibody systems integrated by Simulate: a physical pendulum against its exact period,
// joint loads against Newton's law, consistent initial conditions, energy balances of force
// elements, and singular configurations reported with the time and the joints.
#include "mbs/simulation.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "mbs/constraint_projection.h"
#include "mbs/force_element.h"
#include "mbs/joint.h"
#include "mbs/multibody_system.h"
#include "mbs/rigid_body.h"
#include "mbs/simulation_error.h"
#include "rigid_test_support.h"
#include "tests/input_error.h"

namespace flexmbs::mbs {
namespace {

using testing::PoseFromMarker;
using testing::PositionRate;
using testing::RandomRigidBody;
using testing::RandomRotation;
using testing::RandomVector;
using testing::RigidPositions;

constexpr double kPi = std::numbers::pi;
constexpr double kGravity = 9.81;

Eigen::Matrix3d Rotation(const Eigen::Vector3d& axis, double angle) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

// ---------------------------------------------------------------------------------------------
// A physical pendulum: a body on a revolute joint to the ground about the horizontal W y axis,
// its body origin neither at the pivot nor at the centre of mass, its inertia with products.

struct Pendulum {
  static constexpr double kMass = 2.0;
  static constexpr double kArm = 0.9;  // distance of the centre of mass from the axis [m]
  MultibodySystem system{Eigen::Vector3d(0.0, 0.0, -kGravity)};
  Eigen::Vector3d p_WP_W{0.3, -0.2, 1.5};  // pivot
  Eigen::Vector3d p_BoP_B{0.1, 0.2, 0.5};
  double axis_inertia = 0.0;  // about the joint axis [kg m^2]

  Pendulum() {
    // Markers with z along W y when the body hangs unrotated (R_WB = 1).
    const Eigen::Matrix3d R_axis = Rotation(Eigen::Vector3d::UnitX(), -kPi / 2);
    const Eigen::Vector3d p_BoCm_B = p_BoP_B + Eigen::Vector3d(0.0, 0.07, -kArm);
    const Eigen::Matrix3d R = Rotation(Eigen::Vector3d(1.0, 2.0, 0.5), 0.7);
    const Eigen::Matrix3d I_Cm_B = R * Eigen::Vector3d(0.02, 0.03, 0.04).asDiagonal() * R.transpose();
    axis_inertia = I_Cm_B(1, 1) + kMass * kArm * kArm;
    system.AddBody(std::make_unique<RigidBody>("pendulum", kMass, p_BoCm_B, I_Cm_B,
                                               std::vector<RigidBodyMarker>{{"pivot", p_BoP_B, R_axis}}));
    system.AddJoint(Joint("pivot", JointType::kRevolute, MarkerRef::Ground(p_WP_W, R_axis), system.Marker("pendulum", "pivot")));
  }

  // The state at angle theta [rad] about W y from hanging, at rate theta_dot [rad/s].
  Eigen::VectorXd State(double theta, double theta_dot) const {
    const Eigen::Matrix3d R_WB = Rotation(Eigen::Vector3d::UnitY(), theta);
    Eigen::VectorXd y = system.NeutralState();
    Eigen::VectorXd u(6);
    // w_WB_B = R^T (theta_dot y_W); v_WBo = w x (p_WBo - p_WP).
    const Eigen::Vector3d w_W = theta_dot * Eigen::Vector3d::UnitY();
    const Eigen::Vector3d p_WBo_W = p_WP_W - R_WB * p_BoP_B;
    u << w_W.cross(p_WBo_W - p_WP_W), R_WB.transpose() * w_W;
    system.SetBodyState(0, RigidPositions(p_WBo_W, R_WB), u, y);
    return y;
  }

  static double Angle(const Eigen::VectorXd& y) {
    const Eigen::Matrix3d R = RotationFromEulerParameters(y.segment<4>(3));
    return std::atan2(R(0, 2), R(0, 0));
  }
  static double Rate(const Eigen::VectorXd& y) {
    return (RotationFromEulerParameters(y.segment<4>(3)) * y.segment<3>(10)).y();
  }
};

TEST(Pendulum, PeriodMatchesTheEllipticIntegral) {
  Pendulum pendulum;
  const double theta0 = 2.0;  // [rad], a large swing
  const double omega0 = std::sqrt(Pendulum::kMass * kGravity * Pendulum::kArm / pendulum.axis_inertia);
  // T = 4 K(k) / omega0 with k = sin(theta0 / 2) (e.g. Landau & Lifshitz, Mechanics, sec. 11).
  const double period = 4.0 * std::comp_ellint_1(std::sin(theta0 / 2)) / omega0;
  SimulationOptions options;
  options.end_time = period;
  options.output_interval = period / 8;
  options.integrator.relative_tolerance = 1e-12;
  options.integrator.absolute_tolerance = 1e-12;
  double energy0 = 0.0, energy_drift = 0.0;
  Eigen::VectorXd y_end;
  const SimulationStatistics statistics =
      Simulate(pendulum.system, options, pendulum.State(theta0, 0.0), [&](double t, const Eigen::VectorXd& y, const Eigen::VectorXd&) {
        const double energy = pendulum.system.KineticEnergy(y) + pendulum.system.PotentialEnergy(t, y);
        if (t == 0.0) energy0 = energy;
        energy_drift = std::max(energy_drift, std::abs(energy - energy0));
        y_end = y;
      });
  // Back at the turning point after one period: the rate left is the period error times the
  // angular acceleration there, omega0^2 sin(theta0).
  const double period_error = std::abs(Pendulum::Rate(y_end)) / (omega0 * omega0 * std::sin(theta0));
  std::printf("pendulum: T = %.12f s, relative period error %.2e, angle error %.2e rad, energy drift %.2e J, "
              "%ld steps, %ld rhs\n",
              period, period_error / period, Pendulum::Angle(y_end) - theta0, energy_drift, statistics.integrator.steps,
              statistics.integrator.rhs_evaluations);
  // Measured 1.7e-13 (period, relative) and 1.1e-12 rad (angle); both were asserted at 1e-8.
  constexpr double kPeriodTolerance = 2e-12, kAngleTolerance = 1e-11;
  EXPECT_LE(period_error / period, kPeriodTolerance);
  EXPECT_NEAR(Pendulum::Angle(y_end), theta0, kAngleTolerance);
  // Energy: conserved to the integrator's tolerance (1e-12 relative of a ~20 J swing, with
  // a few hundred steps).
  EXPECT_LE(energy_drift, 1e-9 * pendulum.axis_inertia * omega0 * omega0);
}

TEST(Pendulum, JointLoadIsNewtonsLawForTheBody) {
  Pendulum pendulum;
  const Eigen::VectorXd y = pendulum.State(0.8, -1.3);
  Eigen::VectorXd u_dot(6), lambda(5);
  pendulum.system.Accelerations(0.0, y, u_dot, lambda);
  const JointLoad load = pendulum.system.ConstraintLoad(0, 0.0, y, lambda);
  const auto& body = dynamic_cast<const RigidBody&>(pendulum.system.body(0));
  const Eigen::Matrix3d R = RotationFromEulerParameters(y.segment<4>(3));
  const Eigen::Vector3d c = body.p_BoCm_B(), w = y.segment<3>(10), alpha = u_dot.tail<3>();
  const Eigen::Vector3d a_C = u_dot.head<3>() + R * (alpha.cross(c) + w.cross(w.cross(c)));
  // Gravity and the joint are the only loads: f = m a_C - m g.
  const Eigen::Vector3d expected = Pendulum::kMass * (a_C - pendulum.system.gravity());
  EXPECT_LE((load.f_W - expected).norm(), 1e-12 * expected.norm());
  // A revolute joint transmits no torque about its axis; and the angular acceleration is the
  // pendulum equation's, J theta'' = -m g L sin(theta).
  EXPECT_NEAR(load.tau_W.y(), 0.0, 1e-12 * expected.norm());
  EXPECT_NEAR((R * alpha).y(), -Pendulum::kMass * kGravity * Pendulum::kArm * std::sin(0.8) / pendulum.axis_inertia, 1e-12);
}

TEST(InitialConditions, SmallViolationsAreProjectedLargeOnesRefused) {
  Pendulum pendulum;
  ConsistencyOptions options;
  // 1e-6 m off the pivot and 1e-6 m/s along the axis: projected, with the report.
  Eigen::VectorXd y = pendulum.State(0.5, 0.2);
  y(0) += 1e-6;
  y(8) += 1e-6;
  const ConsistencyReport report = MakeConsistent(pendulum.system, 0.0, y, options);
  EXPECT_TRUE(report.projected);
  EXPECT_NEAR(report.before.position, 1e-6, 1e-12);
  EXPECT_NEAR(report.before.velocity, 1e-6, 1e-12);
  EXPECT_LE(report.after.position, options.projection.position_tolerance);
  EXPECT_LE(report.after.velocity, 1e-14);
  EXPECT_NE(report.Describe(pendulum.system).find("joint 'pivot'"), std::string::npos);
  // The projection moves the body as little as it can: the angle stays (to the size of the
  // violation).
  EXPECT_NEAR(Pendulum::Angle(y), 0.5, 2e-6);
  // 0.1 m off: refused.
  Eigen::VectorXd far = pendulum.State(0.5, 0.2);
  far(2) += 0.1;
  EXPECT_NE(flexmbs::testing::InputErrorMessage([&] { MakeConsistent(pendulum.system, 0.0, far, options); })
                .find("inconsistent initial conditions at t = 0 s: positions violate joint 'pivot' by 0.1"),
            std::string::npos);
  Eigen::VectorXd fast = pendulum.State(0.5, 0.2);
  fast(8) += 0.5;
  EXPECT_NE(flexmbs::testing::InputErrorMessage([&] { MakeConsistent(pendulum.system, 0.0, fast, options); })
                .find("velocities violate joint 'pivot' by 0.5"),
            std::string::npos);
}

// ---------------------------------------------------------------------------------------------
// Force elements.

// The loads of an element on two bodies are in equilibrium: total force and total moment about
// the world origin vanish (generalised forces: v rows are forces in W, w rows moments about Bo
// in B).
void ExpectEquilibrated(const MultibodySystem& system, const Eigen::VectorXd& y, const Eigen::VectorXd& h, double scale) {
  Eigen::Vector3d force = Eigen::Vector3d::Zero(), moment = Eigen::Vector3d::Zero();
  for (int b = 0; b < system.num_bodies(); ++b) {
    const Eigen::Index u = system.velocity_offset(b);
    const Eigen::Matrix3d R = RotationFromEulerParameters(y.segment<4>(system.position_offset(b) + 3));
    force += h.segment<3>(u);
    moment += R * h.segment<3>(u + 3) + y.segment<3>(system.position_offset(b)).cross(h.segment<3>(u));
  }
  EXPECT_LE(force.norm(), 1e-12 * scale);
  EXPECT_LE(moment.norm(), 1e-12 * scale);
}

TEST(ForceElements, StiffnessIsTheGradientOfTheEnergyAndLoadsAreEquilibrated) {
  std::mt19937 rng(31);
  MultibodySystem system(Eigen::Vector3d::Zero());
  system.AddBody(RandomRigidBody(rng, "i"));
  system.AddBody(RandomRigidBody(rng, "j"));
  Eigen::Matrix<double, 6, 1> stiffness, no_damping = Eigen::Matrix<double, 6, 1>::Zero();
  // Translational stiffness exact; rotational isotropic, for which k theta is the exact gradient.
  stiffness << 100.0, 200.0, 300.0, 40.0, 40.0, 40.0;
  const Bushing bushing("bushing", MarkerRef::OnBody(0, 0), MarkerRef::OnBody(1, 1), stiffness, no_damping);
  const SpringDamper spring("spring", MarkerRef::OnBody(0, 1), MarkerRef::OnBody(1, 0), 0.3, 150.0, 0.0);
  Eigen::VectorXd y = system.NeutralState();
  for (int b = 0; b < 2; ++b) {
    Eigen::VectorXd u(6);
    u << RandomVector(rng, 2.0), RandomVector(rng, 2.0);
    system.SetBodyState(b, RigidPositions(RandomVector(rng, 0.3), RandomRotation(rng)), u, y);
  }
  Eigen::VectorXd y_dot = Eigen::VectorXd::Zero(y.size());
  y_dot.head(system.num_positions()) = PositionRate(system, y);
  const Eigen::VectorXd u = y.tail(system.num_velocities());
  for (const ForceElement* element : {static_cast<const ForceElement*>(&bushing), static_cast<const ForceElement*>(&spring)}) {
    Eigen::VectorXd h = Eigen::VectorXd::Zero(system.num_velocities());
    element->AddForces(0.0, system, y, h);
    constexpr double kStep = 1e-6;  // central difference: truncation 1e-12, round-off 1e-10
    const double dV = (element->PotentialEnergy(0.0, system, y + kStep * y_dot) -
                       element->PotentialEnergy(0.0, system, y - kStep * y_dot)) / (2 * kStep);
    EXPECT_NEAR(dV, -h.dot(u), 1e-7 * (1.0 + std::abs(dV))) << element->name();
    ExpectEquilibrated(system, y, h, h.norm());
  }
}

TEST(ForceElements, DampingVanishesUnderACommonRigidMotionAndDissipatesOtherwise) {
  std::mt19937 rng(32);
  MultibodySystem system(Eigen::Vector3d::Zero());
  system.AddBody(RandomRigidBody(rng, "i"));
  system.AddBody(RandomRigidBody(rng, "j"));
  Eigen::Matrix<double, 6, 1> damping;
  damping << 10.0, 20.0, 30.0, 4.0, 5.0, 6.0;
  const Bushing bushing("bushing", MarkerRef::OnBody(0, 0), MarkerRef::OnBody(1, 1), Eigen::Matrix<double, 6, 1>::Zero(), damping);
  const SpringDamper damper("damper", MarkerRef::OnBody(0, 1), MarkerRef::OnBody(1, 0), 0.3, 0.0, 7.0);
  // Both bodies turn with w_W about the world origin and translate with v0.
  const Eigen::Vector3d w_W = RandomVector(rng, 2.0), v0 = RandomVector(rng, 1.0);
  Eigen::VectorXd y = system.NeutralState();
  for (int b = 0; b < 2; ++b) {
    const Eigen::Matrix3d R = RandomRotation(rng);
    const Eigen::Vector3d p = RandomVector(rng, 0.5);
    Eigen::VectorXd u(6);
    u << v0 + w_W.cross(p), R.transpose() * w_W;
    system.SetBodyState(b, RigidPositions(p, R), u, y);
  }
  for (const ForceElement* element : {static_cast<const ForceElement*>(&bushing), static_cast<const ForceElement*>(&damper)}) {
    Eigen::VectorXd h = Eigen::VectorXd::Zero(system.num_velocities());
    element->AddForces(0.0, system, y, h);
    EXPECT_LE(h.norm(), 1e-12) << element->name();
    // A relative motion: the power of the damping loads is negative.
    Eigen::VectorXd moving = y;
    moving.tail(6) += Eigen::VectorXd::Constant(6, 0.3);
    h.setZero();
    element->AddForces(0.0, system, moving, h);
    EXPECT_LT(h.dot(moving.tail(system.num_velocities())), 0.0) << element->name();
    ExpectEquilibrated(system, moving, h, h.norm());
  }
}

TEST(ForceElements, SpringDamperEnergyBalance) {
  // A free body hanging from the ground by a spring-damper at an off-centre marker, thrown with
  // a spin: E(t) + (dissipated work) = E(0), the work integrated from c (dl/dt)^2 at the outputs
  // (composite Simpson, 1 ms steps: error ~ h^4 |P''''| / 180 ~ 1e-10 of E here).
  for (const double damping : {0.0, 1.5}) {
    std::mt19937 rng(33);
    MultibodySystem system(Eigen::Vector3d(0.0, 0.0, -kGravity));
    system.AddBody(RandomRigidBody(rng, "body"));
    const MarkerRef top = MarkerRef::Ground(Eigen::Vector3d(0.0, 0.0, 2.0));
    const MarkerRef end = MarkerRef::OnBody(0, 0);
    system.AddForceElement(std::make_unique<SpringDamper>("spring", top, end, 0.5, 200.0, damping));
    Eigen::VectorXd y = system.NeutralState(), u(6);
    u << 0.3, -0.2, 0.5, 2.0, -1.0, 3.0;
    system.SetBodyState(0, RigidPositions(Eigen::Vector3d(0.2, 0.1, 1.0), RandomRotation(rng)), u, y);
    SimulationOptions options;
    options.end_time = 2.0;
    options.output_interval = 1e-3;
    options.integrator.relative_tolerance = 1e-11;
    options.integrator.absolute_tolerance = 1e-11;
    std::vector<double> energy, power;
    Simulate(system, options, y, [&](double t, const Eigen::VectorXd& state, const Eigen::VectorXd&) {
      energy.push_back(system.KineticEnergy(state) + system.PotentialEnergy(t, state));
      const MarkerKinematics a = system.MarkerState(top, state), b = system.MarkerState(end, state);
      const double rate = (b.p_WM_W - a.p_WM_W).normalized().dot(b.v_WM_W - a.v_WM_W);
      power.push_back(damping * rate * rate);
    });
    ASSERT_EQ(energy.size(), 2001u);
    double work = 0.0, worst = 0.0;
    for (std::size_t k = 2; k < energy.size(); k += 2) {
      work += options.output_interval / 3.0 * (power[k - 2] + 4.0 * power[k - 1] + power[k]);
      worst = std::max(worst, std::abs(energy[k] + work - energy[0]));
    }
    std::printf("spring-damper c = %.1f: dissipated %.6f J of %.6f J, balance error %.2e J\n", damping, work,
                energy[0], worst);
    if (damping > 0.0) {
      EXPECT_GT(work, 0.1 * energy[0]);
    }
    EXPECT_LE(worst, 1e-8 * energy[0]);
  }
}

TEST(ForceElements, FollowerForceTurnsWithASpinningBody) {
  // A force F along the marker's x at the centre of mass of a body spinning at w about its
  // principal z axis: no torque, so w stays, and a_C = F/m (cos wt, sin wt, 0), whence
  // v_C(t) = F/(m w) (sin wt, 1 - cos wt, 0).
  const double mass = 2.0, force = 3.0, w = 4.0;
  MultibodySystem system(Eigen::Vector3d::Zero());
  const Eigen::Vector3d c(0.1, -0.2, 0.3);
  system.AddBody(std::make_unique<RigidBody>("body", mass, c, Eigen::Vector3d(0.5, 0.6, 0.7).asDiagonal(),
                                             std::vector<RigidBodyMarker>{{"centre", c, Eigen::Matrix3d::Identity()}}));
  system.AddForceElement(std::make_unique<PointLoad>("thrust", system.Marker("body", "centre"),
                                                     std::array<TimeFunctionPtr, 3>{MakeConstant(force), nullptr, nullptr},
                                                     std::array<TimeFunctionPtr, 3>{}, LoadFrame::kMarker));
  Eigen::VectorXd y = system.NeutralState(), u(6);
  const Eigen::Vector3d w_B(0.0, 0.0, w);
  u << -w_B.cross(c), w_B;  // the centre of mass at rest
  system.SetBodyState(0, RigidPositions(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity()), u, y);
  SimulationOptions options;
  options.end_time = 1.3;
  options.output_interval = 1.3;
  options.integrator.relative_tolerance = 1e-11;
  options.integrator.absolute_tolerance = 1e-11;
  Eigen::VectorXd y_end;
  Simulate(system, options, y, [&](double, const Eigen::VectorXd& state, const Eigen::VectorXd&) { y_end = state; });
  const Eigen::Matrix3d R = RotationFromEulerParameters(y_end.segment<4>(3));
  const Eigen::Vector3d v_C = y_end.segment<3>(7) + R * y_end.segment<3>(10).cross(c);
  const double t = options.end_time;
  const Eigen::Vector3d expected = force / (mass * w) * Eigen::Vector3d(std::sin(w * t), 1.0 - std::cos(w * t), 0.0);
  EXPECT_LE((v_C - expected).norm(), 1e-8 * expected.norm());
}

// ---------------------------------------------------------------------------------------------
// Singular configurations.

// A planar loop of revolute joints in 3-D is redundant, not singular: its repeated rows are
// dropped at t0 (tests/mbs/redundant_constraints_test.cc).

// A slider-crank: crank r = 0.1 m on a revolute joint, rod L = 0.3 m between spherical joints (a
// spherical-spherical link: no redundant equations in 3-D; its spin about its axis is idle),
// slider on a prismatic joint along W x whose displacement is driven: s(t) = s0 + v t passes
// the dead centre s = r + L at t* = (r + L - s0) / v, beyond which the loop cannot close. The
// run must stop there with a SimulationError that names the time, the loop's joints and
// `origin`, after outputs that were all finite.
void ExpectDeadCentreReported(double singular_pivot, long max_steps, const std::string& origin) {
  const double r = 0.1, L = 0.3, v = 0.2;
  const double s0 = std::sqrt(L * L - r * r), t_dead = (r + L - s0) / v;
  MultibodySystem system;
  const Eigen::Vector3d x = Eigen::Vector3d::UnitX();
  const Eigen::Matrix3d I3 = Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d R_x_axis = Rotation(Eigen::Vector3d::UnitY(), kPi / 2);  // marker z along B x
  system.AddBody(std::make_unique<RigidBody>("crank", 1.0, 0.5 * r * x, Eigen::Vector3d(1e-3, 2e-3, 2e-3).asDiagonal(),
                                             std::vector<RigidBodyMarker>{{"pivot", Eigen::Vector3d::Zero(), I3},
                                                                          {"tip", r * x, I3}}));
  system.AddBody(std::make_unique<RigidBody>("rod", 0.5, 0.5 * L * x, Eigen::Vector3d(1e-4, 4e-3, 4e-3).asDiagonal(),
                                             std::vector<RigidBodyMarker>{{"a", Eigen::Vector3d::Zero(), I3},
                                                                          {"b", L * x, I3}}));
  system.AddBody(std::make_unique<RigidBody>("slider", 2.0, Eigen::Vector3d::Zero(), Eigen::Vector3d(1e-3, 1e-3, 1e-3).asDiagonal(),
                                             std::vector<RigidBodyMarker>{{"pin", Eigen::Vector3d::Zero(), I3},
                                                                          {"guide", Eigen::Vector3d::Zero(), R_x_axis}}));
  system.AddJoint(Joint("crank_pivot", JointType::kRevolute, MarkerRef::Ground(Eigen::Vector3d::Zero()), system.Marker("crank", "pivot")));
  system.AddJoint(Joint("crank_rod", JointType::kSpherical, system.Marker("crank", "tip"), system.Marker("rod", "a")));
  system.AddJoint(Joint("rod_slider", JointType::kSpherical, system.Marker("rod", "b"), system.Marker("slider", "pin")));
  system.AddJoint(Joint("slider_guide", JointType::kPrismatic, MarkerRef::Ground(Eigen::Vector3d::Zero(), R_x_axis),
                        system.Marker("slider", "guide"), MakeRamp(s0, v)));
  // At t = 0 the crank stands at 90 degrees, turning at -v / r: its tip, the rod and the slider
  // all move at v along x.
  Eigen::VectorXd y = system.NeutralState(), u(6);
  u << 0.0, 0.0, 0.0, 0.0, 0.0, -v / r;
  system.SetBodyState(0, RigidPositions(Eigen::Vector3d::Zero(), Rotation(Eigen::Vector3d::UnitZ(), kPi / 2)), u, y);
  u << v, 0.0, 0.0, 0.0, 0.0, 0.0;
  system.SetBodyState(1, RigidPositions(Eigen::Vector3d(0.0, r, 0.0), Rotation(Eigen::Vector3d::UnitZ(), -std::asin(r / L))), u, y);
  u << v, 0.0, 0.0, 0.0, 0.0, 0.0;
  system.SetBodyState(2, RigidPositions(s0 * x, I3), u, y);
  SimulationOptions options;
  options.end_time = 1.0;
  options.output_interval = 0.01;
  options.integrator.relative_tolerance = 1e-8;
  options.integrator.absolute_tolerance = 1e-10;
  options.singular_pivot = singular_pivot;
  options.integrator.max_steps_per_call = max_steps;
  double last_output = 0.0;
  bool finite = true;
  try {
    Simulate(system, options, y, [&](double t, const Eigen::VectorXd& state, const Eigen::VectorXd& lambda) {
      last_output = t;
      finite = finite && state.allFinite() && lambda.allFinite();
    });
    ADD_FAILURE() << "no error";
  } catch (const SimulationError& error) {
    const std::string message = error.what();
    std::printf("dead centre at t* = %.9f s; %s\n", t_dead, message.c_str());
    EXPECT_TRUE(finite);
    EXPECT_GE(last_output, t_dead - 0.01 - 1e-12);
    // Stopped at the dead centre, where the pivot falls like the distance to it.
    EXPECT_NEAR(error.time(), t_dead, 1e-6);
    EXPECT_NE(message.find(origin), std::string::npos);
    EXPECT_NE(message.find("singular configuration"), std::string::npos);
    for (const char* joint : {"'crank_pivot'", "'crank_rod'", "'rod_slider'", "'slider_guide'"}) {
      EXPECT_NE(message.find(joint), std::string::npos) << joint;
    }
  }
}

TEST(SingularConfiguration, SliderCrankDrivenThroughItsDeadCentreReportsTheTime) {
  // The rank check of every evaluation stops it.
  ExpectDeadCentreReported(1e-10, 100000, "the constraint Jacobian is rank deficient");
}

TEST(SingularConfiguration, IntegratorGivingUpAtTheDeadCentreIsExplained) {
  // Without the rank check (a pivot limit below round-off) ARKODE's steps shrink to nothing at
  // the dead centre; its failure is explained from the last step's state.
  ExpectDeadCentreReported(1e-15, 1000, "integration failed");
}

}  // namespace
}  // namespace flexmbs::mbs
