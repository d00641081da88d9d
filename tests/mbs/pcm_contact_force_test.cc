// mbs/pcm_contact_force.h: a rigid icosphere on a rigid flat through elastic layers loads its
// body with the foundation law's force c pi d^2 (R - d/3) and the moment of that force about the
// body's origin; on two free bodies the loads are equal and opposite; a damped ball dropped on
// the ground settles at the closed form's rest depth under explicit and implicit integration,
// an undamped one keeps its energy through an impact; a tilted block rocks and settles on its
// footprint, carrying its weight under its centre of mass; the Jacobian against central
// differences; bad surfaces and layers are one-line errors naming the element.
#include "mbs/pcm_contact_force.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <memory>
#include <vector>

#include "mbs/multibody_system.h"
#include "mbs/rigid_body.h"
#include "mbs/simulation.h"
#include "tests/contact/pcm_meshes.h"
#include "tests/input_error.h"

namespace flexmbs::mbs {
namespace {

using Eigen::Vector3d;
using Eigen::VectorXd;

constexpr double kRadius = 0.02, kDepth = 1e-3, kMaxDepth = 5e-3;  // [m]
const contact::ElasticLayer kLayer{1e7, 2e-3};                     // c = 2.5e9 N/m^3 for two
const Vector3d kMarkerOffset(0.004, -0.002, 0.0);                   // the sphere's centre from the ball's origin [m]

std::unique_ptr<RigidBody> Body(const std::string& name, const Vector3d& p_BoM_B, double mass = 0.5) {
  return std::make_unique<RigidBody>(name, mass, Vector3d::Zero(), (0.4 * mass * kRadius * kRadius * Eigen::Matrix3d::Identity()).eval(),
                                     std::vector<RigidBodyMarker>{{"surface", p_BoM_B, Eigen::Matrix3d::Identity()}});
}

PcmSurface Ball(const MultibodySystem& system, int level) {
  return {"ball", system.Marker("ball", "surface"), contact::testing::Icosphere(Vector3d::Zero(), kRadius, level), kLayer,
          true};
}
PcmSurface Flat(MarkerRef marker) { return {"flat", marker, contact::testing::FlatGrid(0.03, 8, 0.0), kLayer, false}; }

/// The state with the ball's origin at p_ball and the table's (if any) at p_table, at rest.
VectorXd State(const MultibodySystem& system, const Vector3d& p_ball, const Vector3d& p_table) {
  VectorXd y = system.NeutralState(), x(7);
  for (int b = 0; b < system.num_bodies(); ++b) {
    const Vector3d p = b == 0 ? p_ball : p_table;
    x << p, 1.0, 0.0, 0.0, 0.0;
    system.SetBodyState(b, x, VectorXd::Zero(6), y);
  }
  return y;
}

TEST(PcmContactForce, ABallPressedIntoTheGroundTakesTheFoundationForceAndItsMoment) {
  MultibodySystem system(Vector3d::Zero());
  system.AddBody(Body("ball", kMarkerOffset));
  system.AddForceElement(std::make_unique<PcmContactForce>("press", Ball(system, 6), Flat(MarkerRef::Ground(Vector3d::Zero())),
                                                           0.0, contact::RegularisedCoulomb{0.0, 1e-3}, kMaxDepth));
  // The sphere's lowest point kDepth under the flat z = 0.
  const Vector3d p_ball = Vector3d(0.01, 0.003, kRadius - kDepth) - kMarkerOffset;
  const VectorXd h = system.Forces(0.0, State(system, p_ball, Vector3d::Zero()));
  const double c = 1.0 / (2.0 * kLayer.thickness / kLayer.modulus);
  const double exact = c * M_PI * kDepth * kDepth * (kRadius - kDepth / 3.0);
  // The 81920-triangle sphere's cap volume: -1.85e-3 (tests/contact/pcm_foundation_test.cc).
  EXPECT_NEAR(h(2) / exact, 1.0, 0.01);
  EXPECT_LT(h.head<2>().norm(), 1e-12 * exact);
  // The force acts under the sphere's centre: its moment about the ball's origin (the centre of
  // mass) is (kMarkerOffset - (R - d) z) x F.
  const Vector3d moment = (kMarkerOffset - (kRadius - kDepth) * Vector3d::UnitZ()).cross(Vector3d(0.0, 0.0, h(2)));
  EXPECT_LT((h.segment<3>(3) - moment).norm(), 1e-12 * exact * kRadius);
  // The ParaView loads: one per element, on the sphere under the flat, summing to the force.
  const std::vector<ContactLoad> loads = system.force_element(0).ContactLoads(0.0, system, State(system, p_ball, Vector3d::Zero()));
  ASSERT_GT(loads.size(), 1000u);
  Vector3d total = Vector3d::Zero();
  for (const ContactLoad& load : loads) {
    total += load.f_W;
    EXPECT_EQ(load.n_W, Vector3d::UnitZ());
    EXPECT_LE(load.p_W.z(), 0.0);
    EXPECT_GE(load.p_W.z(), -kDepth);
    const Vector3d centre = p_ball + kMarkerOffset;
    EXPECT_NEAR((load.p_W - centre).norm(), kRadius, 1e-5);  // on a facet: within its sag, measured 1.4e-6 m
  }
  EXPECT_LT((total - h.head<3>()).norm(), 1e-12 * exact);
}

TEST(PcmContactForce, OnTwoFreeBodiesTheLoadsAreEqualAndOpposite) {
  MultibodySystem system(Vector3d::Zero());
  system.AddBody(Body("ball", kMarkerOffset));
  system.AddBody(Body("table", Vector3d(0.0, 0.0, 0.01)));
  system.AddForceElement(std::make_unique<PcmContactForce>("press", Ball(system, 4), Flat(system.Marker("table", "surface")),
                                                           0.0, contact::RegularisedCoulomb{0.0, 1e-3}, kMaxDepth));
  const Vector3d p_table(0.002, 0.001, -0.01);  // the flat at z = 0
  const Vector3d p_ball = Vector3d(0.003, 0.0, kRadius - kDepth) - kMarkerOffset;
  const VectorXd h = system.Forces(0.0, State(system, p_ball, p_table));
  const Vector3d f_ball = h.segment<3>(0), f_table = h.segment<3>(6);
  EXPECT_GT(f_ball.z(), 100.0);
  EXPECT_LT((f_ball + f_table).norm(), 1e-12 * f_ball.norm());
  const Vector3d total_moment = h.segment<3>(3) + p_ball.cross(f_ball) + h.segment<3>(9) + p_table.cross(f_table);
  EXPECT_LT(total_moment.norm(), 1e-12 * f_ball.norm() * kRadius);
}

/// The element's Jacobian and its central differences (steps 1e-7) on a ball pressed into a free
/// table, both moving with velocities u: the relative errors in u (all of dh/du) and in x (the
/// translations' columns 0-2, 6-8 on the force rows).
struct JacobianErrors {
  double u = 0.0, x = 0.0;
};
JacobianErrors CompareJacobian(double areal_damping, const VectorXd& u) {
  MultibodySystem system(Vector3d::Zero());
  system.AddBody(Body("ball", kMarkerOffset));
  system.AddBody(Body("table", Vector3d(0.0, 0.0, 0.01)));
  system.AddForceElement(std::make_unique<PcmContactForce>("press", Ball(system, 4), Flat(system.Marker("table", "surface")),
                                                           areal_damping, contact::RegularisedCoulomb{0.4, 1e-3}, kMaxDepth));
  VectorXd y = State(system, Vector3d(0.003, 0.0, kRadius - kDepth) - kMarkerOffset, Vector3d(0.002, 0.001, -0.01));
  system.SetBodyState(0, system.BodyPositions(y, 0), u.head(6), y);
  system.SetBodyState(1, system.BodyPositions(y, 1), u.tail(6), y);
  const ForceElement& press = system.force_element(0);
  const Eigen::Index n = system.num_velocities();
  Eigen::MatrixXd dh_dx = Eigen::MatrixXd::Zero(n, n), dh_du = dh_dx;
  press.AddForceJacobian(0.0, system, y, dh_dx, dh_du);
  const auto forces = [&](const VectorXd& state) {
    VectorXd h = VectorXd::Zero(n);
    press.AddForces(0.0, system, state, h);
    return h;
  };
  const double step = 1e-7;  // [m/s], [m]
  Eigen::MatrixXd fd_u(n, n), fd_x(n, n);
  for (Eigen::Index k = 0; k < n; ++k) {
    VectorXd plus = y, minus = y;
    plus(system.num_positions() + k) += step;
    minus(system.num_positions() + k) -= step;
    fd_u.col(k) = (forces(plus) - forces(minus)) / (2.0 * step);
    plus = y;
    minus = y;
    system.DisplacePositions(VectorXd::Unit(n, k) * step, plus);
    system.DisplacePositions(-VectorXd::Unit(n, k) * step, minus);
    fd_x.col(k) = (forces(plus) - forces(minus)) / (2.0 * step);
  }
  const std::array<Eigen::Index, 6> translation{0, 1, 2, 6, 7, 8};
  Eigen::MatrixXd analytic(6, 6), central(6, 6);
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) {
      analytic(i, j) = dh_dx(translation[i], translation[j]);
      central(i, j) = fd_x(translation[i], translation[j]);
    }
  }
  return {(dh_du - fd_u).norm() / fd_u.norm(), (analytic - central).norm() / central.norm()};
}

TEST(PcmContactForce, TheJacobianIsTheLoadsDerivativeInVelocityAndInTranslation) {
  VectorXd u(12);
  u << 0.002, -0.001, -0.01, 0.3, -0.2, 0.1, -0.001, 0.0005, 0.002, -0.1, 0.05, 0.2;  // slip of the order of eps
  const JacobianErrors full = CompareJacobian(2e5, u);
  // Without damping and rotation the translations' derivative is exact: the areas held leave out
  // only the damping's d_A v_N dA/dx, the pressure centres held only the rotation's w x dP/dx.
  VectorXd sliding = u;
  sliding.segment<3>(3).setZero();
  sliding.segment<3>(9).setZero();
  const JacobianErrors elastic = CompareJacobian(0.0, sliding);
  std::printf("[ numbers  ] dh/du %.3e; dh/dx (translations) %.3e, undamped without rotation %.3e (relative)\n",
              full.u, full.x, elastic.x);
  EXPECT_LT(full.u, 1e-9);     // measured 1.2e-10
  EXPECT_LT(full.x, 5e-2);     // measured 5.1e-3: the parts held
  EXPECT_LT(elastic.x, 5e-9);  // measured 4.4e-10
}

TEST(PcmContactForce, ADampedBallDroppedOnTheGroundSettlesWhereTheFoundationCarriesItsWeight) {
  constexpr double kMass = 20.0, kG = 9.81;
  const double c = 1.0 / (2.0 * kLayer.thickness / kLayer.modulus);
  // The closed form's rest depth: c pi d^2 (R - d/3) = m g, by bisection.
  double lo = 0.0, hi = kMaxDepth;
  for (int i = 0; i < 100; ++i) {
    const double d = 0.5 * (lo + hi);
    (c * M_PI * d * d * (kRadius - d / 3.0) < kMass * kG ? lo : hi) = d;
  }
  const double rest = 0.5 * (lo + hi);
  // Critical damping of the contact linearised at rest: k = c pi (2 R d - d^2) = c A.
  const double area = M_PI * (2.0 * kRadius * rest - rest * rest);
  const double areal_damping = 2.0 * std::sqrt(c * area * kMass) / area;
  MultibodySystem system(Vector3d(0.0, 0.0, -kG));
  system.AddBody(Body("ball", Vector3d::Zero(), kMass));  // centred: no moment to tip it
  system.AddForceElement(std::make_unique<PcmContactForce>("press", Ball(system, 4), Flat(MarkerRef::Ground(Vector3d::Zero())),
                                                           areal_damping, contact::RegularisedCoulomb{0.0, 1e-3}, kMaxDepth));
  for (const OdeMethod method : {OdeMethod::kExplicit, OdeMethod::kImplicit}) {
    SimulationOptions options;
    options.integrator.method = method;  // implicit: Newton on the element's Jacobian
    options.end_time = 0.15;  // 20 periods of the linearised contact (omega = 130 rad/s)
    options.output_interval = 0.01;
    options.integrator.relative_tolerance = 1e-7;
    options.integrator.absolute_tolerance = 1e-10;
    VectorXd last;
    Simulate(system, options, State(system, Vector3d(0.0, 0.0, kRadius), Vector3d::Zero()),
             [&](double, const VectorXd& y, const VectorXd&) { last = y; });
    const double depth = kRadius - last(2);
    std::printf("[ numbers  ] %s: rest depth %.6e m, closed form %.6e m (%.3e), speed %.3e m/s\n",
                std::string(OdeMethodName(method)).c_str(), depth, rest, depth / rest - 1.0, last(7 + 2));
    // Measured +1.33 % (both methods): the 5120-triangle sphere's cap is shallower than the
    // sphere's (its force is 3 % low at 1 mm, tests/contact/pcm_foundation_test.cc), so it sinks
    // deeper; at rest to 9.4e-9 m/s (explicit) and 9.9e-9 m/s (implicit).
    EXPECT_NEAR(depth / rest, 1.0, 0.03);
    EXPECT_LT(std::abs(last(7 + 2)), 1e-7);
  }
}

TEST(PcmContactForce, ATiltedBlockDroppedOnTheGroundRocksAndSettlesOnItsFootprint) {
  constexpr double kMass = 2.0, kG = 9.81, kTilt = 0.05;  // [kg], [m/s^2], [rad] about x
  const Vector3d half(0.05, 0.04, 0.02);                   // [m]
  const contact::ElasticLayer soft{1e5, 2e-3};             // c = 1 / (2 h / E) = 2.5e7 N/m^3
  const double c = 1.0 / (2.0 * soft.thickness / soft.modulus), footprint = 4.0 * half.x() * half.y();
  MultibodySystem system(Vector3d(0.0, 0.0, -kG));
  const Eigen::Matrix3d inertia =
      (kMass / 3.0 * Vector3d(half.y() * half.y() + half.z() * half.z(), half.x() * half.x() + half.z() * half.z(),
                              half.x() * half.x() + half.y() * half.y()))
          .asDiagonal();
  system.AddBody(std::make_unique<RigidBody>("block", kMass, Vector3d::Zero(), inertia,
                                             std::vector<RigidBodyMarker>{{"surface", Vector3d::Zero(), Eigen::Matrix3d::Identity()}}));
  // Critical damping of the block's bounce on its footprint (k = c A).
  const double areal_damping = 2.0 * std::sqrt(c * footprint * kMass) / footprint;
  system.AddForceElement(std::make_unique<PcmContactForce>(
      "rest", PcmSurface{"block", system.Marker("block", "surface"), contact::testing::Box(half), soft, true},
      PcmSurface{"ground", MarkerRef::Ground(Vector3d::Zero()), contact::testing::FlatGrid(0.2, 4, 0.0), soft, false},
      areal_damping, contact::RegularisedCoulomb{0.0, 1e-3}, 0.01));
  // Tilted about x with its lowest edge on the ground, at rest.
  VectorXd y = system.NeutralState(), x(7);
  x << 0.01, -0.02, half.y() * std::sin(kTilt) + half.z() * std::cos(kTilt), std::cos(kTilt / 2.0), std::sin(kTilt / 2.0),
      0.0, 0.0;
  system.SetBodyState(0, x, VectorXd::Zero(6), y);
  SimulationOptions options;
  options.integrator.method = OdeMethod::kExplicit;
  options.end_time = 0.5;
  options.output_interval = 0.01;
  options.integrator.relative_tolerance = 1e-8;
  options.integrator.absolute_tolerance = 1e-11;
  VectorXd last;
  double tilt_seen = 0.0;
  Simulate(system, options, y, [&](double, const VectorXd& state, const VectorXd&) {
    last = state;
    tilt_seen = std::max(tilt_seen, 2.0 * std::abs(state(4)));
  });
  // At rest flat on its footprint, sunk by m g / (c A) (flat faces: no discretisation error).
  const double depth = half.z() - last(2), rest = kMass * kG / (c * footprint);
  // The angle between the block's z axis and W's (R_zz = 1 - 2 (e1^2 + e2^2)), and its yaw.
  const double tilt = 2.0 * last.segment<2>(4).norm(), yaw = 2.0 * std::abs(last(6));
  const std::vector<ContactLoad> loads = system.force_element(0).ContactLoads(0.0, system, last);
  double normal_force = 0.0;
  Eigen::Vector2d moment = Eigen::Vector2d::Zero();
  for (const ContactLoad& load : loads) {
    normal_force += load.f_W.z();
    moment += load.f_W.z() * load.p_W.head<2>();
  }
  const Eigen::Vector2d pressure_centre = moment / normal_force;
  std::printf("[ numbers  ] depth %.6e m (m g / c A %.6e, %.2e), tilt %.2e rad (yaw %.2e), N - m g %.2e N, "
              "pressure centre off the centre of mass %.2e m, x drift %.2e m\n",
              depth, rest, depth / rest - 1.0, tilt, yaw, normal_force - kMass * kG,
              (pressure_centre - last.head<2>()).norm(), last(0) - 0.01);
  EXPECT_GT(tilt_seen, 0.04);  // it started tilted
  // Measured: depth -2.8e-10 relative, tilt 3.4e-16 rad, N - m g 5.6e-9 N, pressure centre
  // 4.3e-15 m off (the yaw, 1.8e-6 rad, independent of the tolerances, is not explained yet:
  // docs/contact.md).
  EXPECT_NEAR(depth / rest, 1.0, 3e-9);
  EXPECT_LT(tilt, 3e-15);
  EXPECT_NEAR(normal_force, kMass * kG, 5e-8);
  EXPECT_LT((pressure_centre - last.head<2>()).norm(), 4e-14);
  EXPECT_EQ(last(0), 0.01) << "no friction: no horizontal force";
}

TEST(PcmContactForce, AnUndampedBallBouncesOnTheGroundWithoutGainingEnergy) {
  MultibodySystem system(Vector3d(0.0, 0.0, -9.81));
  system.AddBody(Body("ball", Vector3d::Zero(), 20.0));
  system.AddForceElement(std::make_unique<PcmContactForce>("press", Ball(system, 3), Flat(MarkerRef::Ground(Vector3d::Zero())),
                                                           0.0, contact::RegularisedCoulomb{0.0, 1e-3}, kMaxDepth));
  VectorXd y0 = State(system, Vector3d(0.0, 0.0, kRadius + 1e-4), Vector3d::Zero());
  y0(7 + 2) = -0.3;  // falling at 0.3 m/s, 0.1 mm above the flat: one impact in 5 ms
  SimulationOptions options;
  options.integrator.method = OdeMethod::kExplicit;
  options.end_time = 0.01;
  options.output_interval = 2e-4;
  options.integrator.relative_tolerance = 1e-10;
  options.integrator.absolute_tolerance = 1e-13;
  const auto energy = [&](const VectorXd& y) { return system.KineticEnergy(y) + system.PotentialEnergy(0.0, y); };
  const double start = energy(y0);
  double largest = 0.0, deepest = 0.0;
  Simulate(system, options, y0, [&](double, const VectorXd& y, const VectorXd&) {
    largest = std::max(largest, std::abs(energy(y) - start));
    deepest = std::max(deepest, kRadius - y(2));
  });
  std::printf("[ numbers  ] deepest %.4e m, energy drift %.3e of %.4e J\n", deepest, largest, start);
  EXPECT_GT(deepest, 2e-4);  // it went into the layers
  EXPECT_LT(largest, 2e-7);  // [J], measured 1.9e-8 of 4.8 J (the integration's tolerance)
}

TEST(PcmContactForce, BadLayersSurfacesAndDepthAreOneLineErrorsNamingTheElement) {
  MultibodySystem system(Vector3d::Zero());
  system.AddBody(Body("ball", kMarkerOffset));
  const MarkerRef ground = MarkerRef::Ground(Vector3d::Zero());
  const contact::RegularisedCoulomb no_friction{0.0, 1e-3};
  const auto make = [&](PcmSurface A, PcmSurface B, double max_depth) {
    PcmContactForce("press", std::move(A), std::move(B), 0.0, no_friction, max_depth);
  };
  PcmSurface thin = Ball(system, 1);
  thin.layer.thickness = 0.0;
  EXPECT_EQ(testing::InputErrorMessage([&] { make(thin, Flat(ground), kMaxDepth); }),
            "force element 'press': layer thickness of surface 'ball' 0 must be finite and > 0");
  PcmSurface flipped = Ball(system, 1);
  std::swap(flipped.mesh_M.face_vertices[4], flipped.mesh_M.face_vertices[5]);
  EXPECT_NE(testing::InputErrorMessage([&] { make(flipped, Flat(ground), kMaxDepth); })
                .find("force element 'press': surface 'ball': triangles "),
            std::string::npos);
  PcmSurface open_flat = Flat(ground);
  open_flat.closed = true;
  EXPECT_NE(testing::InputErrorMessage([&] { make(Ball(system, 1), open_flat, kMaxDepth); }).find("a hole"),
            std::string::npos);
  EXPECT_EQ(testing::InputErrorMessage([&] { make(Ball(system, 1), Flat(ground), 0.0); }),
            "force element 'press': max depth [m] 0 must be finite and > 0");
}

}  // namespace
}  // namespace flexmbs::mbs
