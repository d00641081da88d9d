// The penalty sphere-on-plane contact (mbs/contact_force.h): a ball bouncing on the ground
// against the closed-form impacts (linear spring: a half period of sqrt(k / m); Hertz: Hertz's
// impact time 2 I delta_max / v0 with I = integral_0^1 (1 - s^(5/2))^(-1/2) ds), a damped ball
// settling at its static penetration, the Jacobian against central differences, the scene entry
// and its bad input.
#include "mbs/contact_force.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numbers>
#include <string>
#include <unistd.h>
#include <vector>

#include "mbs/multibody_system.h"
#include "mbs/rigid_body.h"
#include "mbs/scene.h"
#include "mbs/simulation.h"
#include "tests/input_error.h"

namespace flexmbs::mbs {
namespace {

using Eigen::Vector3d;
using Eigen::VectorXd;

constexpr double kMass = 0.5, kRadius = 0.02;  // [kg], [m]
constexpr double kGap = 1e-3;                   // the ball's start above the plane [m]
constexpr double kSpeed = 2.0;                  // its approach speed [m/s]
// Tolerances of the integration (rtol 1e-10, atol 1e-13) over a few thousand steps; the
// penetration history is smooth inside the contact (the kinks at touch-down and lift-off are
// steps of the force's derivative: the adaptive control resolves them).
constexpr double kTimeTolerance = 1e-7;    // [s] on the contact duration (~1e-4 of it)
constexpr double kSpeedTolerance = 1e-6;   // relative, the rebound speed

std::unique_ptr<RigidBody> Ball() {
  const double moment = 0.4 * kMass * kRadius * kRadius;
  return std::make_unique<RigidBody>("ball", kMass, Vector3d::Zero(), Vector3d::Constant(moment).asDiagonal().toDenseMatrix(),
                                     std::vector<RigidBodyMarker>{{"centre", Vector3d::Zero(), Eigen::Matrix3d::Identity()}});
}

struct Bounce {
  MultibodySystem system;
  VectorXd y0;
};

// The ball above the ground plane z = 0 (normal W z), moving down at kSpeed, with contact law
// (k, c, e) and gravity g_W.
std::unique_ptr<Bounce> MakeBounce(double stiffness, double damping, double exponent, const Vector3d& g_W,
                                   double speed = kSpeed) {
  auto bounce = std::make_unique<Bounce>(Bounce{MultibodySystem(g_W), VectorXd()});
  MultibodySystem& system = bounce->system;
  const int ball = system.AddBody(Ball());
  system.AddForceElement(std::make_unique<SpherePlaneContact>("ground", system.Marker("ball", "centre"),
                                                              MarkerRef::Ground(Vector3d::Zero(), Eigen::Matrix3d::Identity()),
                                                              kRadius, stiffness, damping, exponent));
  bounce->y0 = system.NeutralState();
  VectorXd x(7), u = VectorXd::Zero(6);
  x << 0.0, 0.0, kRadius + kGap, 1.0, 0.0, 0.0, 0.0;
  u(2) = -speed;
  system.SetBodyState(ball, x, u, bounce->y0);
  return bounce;
}

struct History {
  std::vector<double> t, z, vz;
};

History RunBounce(Bounce& bounce, double end_time, double output_interval,
                  OdeMethod method = OdeMethod::kExplicit) {
  SimulationOptions options;
  options.integrator.method = method;
  options.end_time = end_time;
  options.output_interval = output_interval;
  options.integrator.relative_tolerance = 1e-10;
  options.integrator.absolute_tolerance = 1e-13;
  History history;
  Simulate(bounce.system, options, bounce.y0, [&](double t, const VectorXd& y, const VectorXd&) {
    history.t.push_back(t);
    history.z.push_back(y(2));
    history.vz.push_back(y(7 + 2));
  });
  return history;
}

// Without gravity the ball leaves the plane at the approach speed after the contact time t_c and
// is back at its start height at 2 kGap / v0 + t_c; at the end it is kSpeed (T - that) above.
void ExpectElasticBounce(double stiffness, double exponent, double contact_time,
                         OdeMethod method = OdeMethod::kExplicit) {
  auto bounce = MakeBounce(stiffness, 0.0, exponent, Vector3d::Zero());
  const double end_time = 4.0 * kGap / kSpeed + contact_time;
  const History history = RunBounce(*bounce, end_time, end_time / 50.0, method);
  const double back = 2.0 * kGap / kSpeed + contact_time;
  const double expected_z = kRadius + kGap + kSpeed * (end_time - back);
  EXPECT_NEAR(history.vz.back(), kSpeed, kSpeedTolerance * kSpeed);
  // The position error is the contact time's error times the speed.
  EXPECT_NEAR(history.z.back(), expected_z, kTimeTolerance * kSpeed);
  std::printf("[ numbers  ] e = %.1f: contact time %.6e s; rebound %.9f m/s; end height error %.2e m\n", exponent,
              contact_time, history.vz.back(), history.z.back() - expected_z);
}

TEST(SpherePlaneContact, LinearBounceLastsHalfAPeriod) {
  constexpr double kStiffness = 1e6;  // [N/m]
  ExpectElasticBounce(kStiffness, 1.0, std::numbers::pi * std::sqrt(kMass / kStiffness));
}

TEST(SpherePlaneContact, HertzBounceLastsHertzsImpactTime) {
  constexpr double kStiffness = 5e8, kExponent = 1.5;  // [N/m^1.5]: steel-like for a 2 cm ball
  // m delta'' = -k delta^(3/2): delta_max = (5 m v0^2 / (4 k))^(2/5), t_c = 2 I delta_max / v0,
  // I = (2/5) B(2/5, 1/2) = 1.4716...
  const double delta_max = std::pow(5.0 * kMass * kSpeed * kSpeed / (4.0 * kStiffness), 0.4);
  const double integral = 0.4 * std::tgamma(0.4) * std::tgamma(0.5) / std::tgamma(0.9);
  ExpectElasticBounce(kStiffness, kExponent, 2.0 * integral * delta_max / kSpeed);
}

// The same bounce under the L-stable ESDIRK with the model Jacobian (the contact's stiffness
// in the Newton matrix).
TEST(SpherePlaneContact, ImplicitMethodBouncesAlike) {
  constexpr double kStiffness = 5e8, kExponent = 1.5;
  const double delta_max = std::pow(5.0 * kMass * kSpeed * kSpeed / (4.0 * kStiffness), 0.4);
  const double integral = 0.4 * std::tgamma(0.4) * std::tgamma(0.5) / std::tgamma(0.9);
  ExpectElasticBounce(kStiffness, kExponent, 2.0 * integral * delta_max / kSpeed, OdeMethod::kImplicit);
}

TEST(SpherePlaneContact, DampedBallSettlesAtItsStaticPenetration) {
  constexpr double kStiffness = 1e5, kExponent = 1.5;
  const double rest = std::pow(kMass * 9.81 / kStiffness, 1.0 / kExponent);
  // Critical damping of the contact linearised at rest (stiffness e k rest^(e-1)): the ball
  // bounces off once or twice, then settles within a few 1 / omega = 10 ms.
  const double damping = 2.0 * std::sqrt(kExponent * kStiffness * std::pow(rest, kExponent - 1.0) * kMass);
  auto bounce = MakeBounce(kStiffness, damping, kExponent, Vector3d(0.0, 0.0, -9.81), 0.5);
  const History history = RunBounce(*bounce, 1.0, 1e-3);
  EXPECT_NEAR(history.z.back(), kRadius - rest, 1e-3 * rest);
  EXPECT_NEAR(history.vz.back(), 0.0, 1e-6);
  std::printf("[ numbers  ] rest penetration %.6e m (m g / k)^(2/3) = %.6e m\n", kRadius - history.z.back(), rest);
}

TEST(SpherePlaneContact, JacobianIsTheForcesDerivativeInContact) {
  auto bounce = MakeBounce(1e6, 50.0, 1.5, Vector3d::Zero());
  MultibodySystem& system = bounce->system;
  VectorXd y = bounce->y0;
  y(2) = kRadius - 1e-4;  // 0.1 mm into the plane, approaching
  const ForceElement& contact = system.force_element(0);
  const Eigen::Index n = system.num_velocities();
  Eigen::MatrixXd dh_dx = Eigen::MatrixXd::Zero(n, n), dh_du = dh_dx;
  contact.AddForceJacobian(0.0, system, y, dh_dx, dh_du);
  const auto forces = [&](const VectorXd& state) {
    VectorXd h = VectorXd::Zero(n);
    contact.AddForces(0.0, system, state, h);
    return h;
  };
  constexpr double kStep = 1e-9;  // [m], [m/s]: within the contact, the force smooth there
  Eigen::MatrixXd fd_x(n, n), fd_u(n, n);
  for (Eigen::Index k = 0; k < n; ++k) {
    VectorXd du = VectorXd::Zero(n);
    du(k) = kStep;
    VectorXd plus = y, minus = y;
    system.DisplacePositions(du, plus);
    system.DisplacePositions(-du, minus);
    fd_x.col(k) = (forces(plus) - forces(minus)) / (2.0 * kStep);
    plus = y;
    minus = y;
    plus.tail(n) += du;
    minus.tail(n) += -du;
    fd_u.col(k) = (forces(plus) - forces(minus)) / (2.0 * kStep);
  }
  // Translations: exact; rotations of the ball about its centre do not move the contact.
  EXPECT_LE((dh_dx - fd_x).cwiseAbs().maxCoeff(), 1e-6 * fd_x.cwiseAbs().maxCoeff());
  EXPECT_LE((dh_du - fd_u).cwiseAbs().maxCoeff(), 1e-6 * fd_u.cwiseAbs().maxCoeff());
  EXPECT_GT(fd_x.cwiseAbs().maxCoeff(), 0.0);
}

TEST(SpherePlaneContact, SceneEntryAndBadInput) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("flexmbs_contact_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto scene = [&](const std::string& radius) {
    const std::filesystem::path file = dir / "scene.yaml";
    std::ofstream(file) << "bodies:\n  ball:\n    rigid: {mass: 0.5, inertia: [[8e-5, 0, 0], [0, 8e-5, 0], [0, 0, 8e-5]]}\n"
                           "    markers: {centre: {position: [0, 0, 0]}}\n    initial: {position: [0, 0, 0.05]}\n"
                           "forces:\n  - {name: floor, type: sphere_plane_contact, sphere: {body: ball, marker: centre}, "
                           "plane: {body: ground}, radius: "
                        << radius << ", stiffness: 1e6, damping: 10, exponent: 1.5}\n"
                        << "simulation: {end_time: 0.01}\n";
    return file;
  };
  const Scene loaded = LoadScene(scene("0.02"));
  ASSERT_EQ(loaded.system->num_force_elements(), 1);
  EXPECT_EQ(loaded.system->force_element(0).name(), "floor");
  const std::string message = flexmbs::testing::InputErrorMessage([&] { LoadScene(scene("0")); });
  EXPECT_NE(message.find("forces[0].radius: force element 'floor': 0 m must be > 0"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos);
  // An unknown type lists every force element, the contact elements among them.
  std::ofstream(dir / "typo.yaml") << "bodies: {}\nforces:\n  - {name: floor, type: sphere_plane_contacts}\n"
                                   << "simulation: {end_time: 0.01}\n";
  const std::string typo = flexmbs::testing::InputErrorMessage([&] { LoadScene(dir / "typo.yaml"); });
  EXPECT_NE(typo.find("forces[0].type: 'sphere_plane_contacts' must be one of: point_load, spring_damper, bushing, "
                      "sphere_plane_contact, sphere_sphere_contact, box_plane_contact, sphere_surface_contact, "
                      "surface_plane_contact, spur_gear_contact, pcm_contact"),
            std::string::npos)
      << typo;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace flexmbs::mbs
