// The contact algebra of event-driven integration (mbs/event_driven_contacts.h): the gap
// acceleration's velocity term (dW_N/dt) u by central differences against closed forms (two
// spheres passing each other, a sphere on a spinning body's offset marker), and the impact LCP
// of a point that touches while it separates.
#include "mbs/event_driven_contacts.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "mbs/joint.h"
#include "mbs/rigid_body.h"
#include "mbs/unilateral_contact.h"

namespace flexmbs::mbs {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Eigen::VectorXd;

constexpr double kRadius = 0.1;

int AddBall(MultibodySystem& system, const char* name, const Vector3d& p_BoM_B) {
  return system.AddBody(std::make_unique<RigidBody>(
      name, 1.0, Vector3d::Zero(), Matrix3d::Identity() * 0.004,
      std::vector<RigidBodyMarker>{{"centre", p_BoM_B, Matrix3d::Identity()}}));
}

TEST(EventDrivenContacts, AccelerationBiasOfTwoPassingSpheresIsTheCentripetalTerm) {
  MultibodySystem system(Vector3d::Zero());
  const int a = AddBall(system, "a", Vector3d::Zero()), b = AddBall(system, "b", Vector3d::Zero());
  system.AddUnilateralContact(std::make_unique<SphereSphereUnilateral>(
      "pair", system.Marker("a", "centre"), system.Marker("b", "centre"), kRadius, kRadius,
      UnilateralLaw{}));
  VectorXd y = system.NeutralState();
  const Vector3d p_a(0.3, 0.1, -0.2), v_a(1.5, -0.7, 0.4), v_b(-0.2, 0.9, 0.3);
  VectorXd x(7), u(6);
  x << p_a, 1.0, 0.0, 0.0, 0.0;
  u << v_a, 0.3, -1.1, 2.0;  // spin does not move a sphere's gap
  system.SetBodyState(a, x, u, y);
  x.head<3>().setZero();
  u << v_b, 0.0, 0.0, 0.0;
  system.SetBodyState(b, x, u, y);
  const EventDrivenContacts contacts(system, EventDrivenOptions{});
  const double bias = contacts.AccelerationBias(0.0, y, {0})(0, 0);
  // g = |d| - r1 - r2 with d = p_a - p_b moving at w = v_a - v_b: g'' = (|w|^2 - (n . w)^2) / |d|.
  const Vector3d d = p_a, w = v_a - v_b, n = d.normalized();
  const double exact = (w.squaredNorm() - n.dot(w) * n.dot(w)) / d.norm();
  std::printf("two spheres: bias %.15f, exact %.15f m/s^2, relative error %.3e\n", bias, exact,
              std::abs(bias - exact) / exact);
  EXPECT_NEAR(bias, exact, 5e-10 * exact);  // measured 5.1e-11 relative (O(eps^2) truncation)
}

TEST(EventDrivenContacts, AccelerationBiasOfASpinningOffsetMarkerIsItsCentripetalAcceleration) {
  // A body spinning at omega about its z axis (a principal axis: no gyroscopic acceleration,
  // no gravity) with a sphere on a marker at d along its x axis, against the plane x = -1 (normal
  // +x): the sphere centre's x is d cos(omega t), so g'' = -omega^2 d at t = 0.
  constexpr double d = 0.25, omega = 3.0;
  MultibodySystem system(Vector3d::Zero());
  const int body = AddBall(system, "wheel", Vector3d(d, 0.0, 0.0));
  const Matrix3d R_WP =
      Eigen::AngleAxisd(M_PI / 2.0, Vector3d::UnitY()).toRotationMatrix();  // z_P = +x
  system.AddUnilateralContact(std::make_unique<SpherePlaneUnilateral>(
      "wall", system.Marker("wheel", "centre"), MarkerRef::Ground(Vector3d(-1.0, 0.0, 0.0), R_WP),
      kRadius, UnilateralLaw{}));
  VectorXd y = system.NeutralState();
  VectorXd x(7), u(6);
  x << 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0;
  u << 0.0, 0.0, 0.0, 0.0, 0.0, omega;
  system.SetBodyState(body, x, u, y);
  const EventDrivenContacts contacts(system, EventDrivenOptions{});
  const double bias = contacts.AccelerationBias(0.0, y, {0})(0, 0);
  std::printf("offset marker: bias %.15f, exact %.15f m/s^2\n", bias, -omega * omega * d);
  EXPECT_NEAR(bias, -omega * omega * d, 6e-11 * omega * omega * d);  // measured 6.1e-12 relative
}

TEST(EventDrivenContacts, ATouchingPointThatSeparatesIsNotPushedIntoItsSurfaceByAnImpact) {
  // Ball B (2 kg) touches the floor moving up at 0.1 m/s; ball A (1 kg) strikes it from above at
  // 2 m/s (restitution: pair 0.8, floor 0.5). Newton's law on the pair, U_N+ >= 0 on the floor
  // (not U_N+ >= -e U_N-, which would let B sink at 0.05 m/s): B stops, A leaves at
  // e 2.1 m/s, P_pair = m_A (e 2.1 + 2), P_floor = P_pair - m_B 0.1.
  MultibodySystem system(Vector3d(0.0, 0.0, -9.81));
  const int a = system.AddBody(std::make_unique<RigidBody>(
      "a", 1.0, Vector3d::Zero(), Matrix3d::Identity() * 0.004,
      std::vector<RigidBodyMarker>{{"centre", Vector3d::Zero(), Matrix3d::Identity()}}));
  const int b = system.AddBody(std::make_unique<RigidBody>(
      "b", 2.0, Vector3d::Zero(), Matrix3d::Identity() * 0.008,
      std::vector<RigidBodyMarker>{{"centre", Vector3d::Zero(), Matrix3d::Identity()}}));
  system.AddUnilateralContact(std::make_unique<SpherePlaneUnilateral>(
      "floor", system.Marker("b", "centre"), MarkerRef::Ground(Vector3d::Zero()), kRadius,
      UnilateralLaw{0.5, 0.0}));
  system.AddUnilateralContact(std::make_unique<SphereSphereUnilateral>(
      "pair", system.Marker("a", "centre"), system.Marker("b", "centre"), kRadius, kRadius,
      UnilateralLaw{0.8, 0.0}));
  VectorXd y = system.NeutralState();
  VectorXd x(7), u(6);
  x << 0.0, 0.0, 3.0 * kRadius, 1.0, 0.0, 0.0, 0.0;
  u << 0.0, 0.0, -2.0, 0.0, 0.0, 0.0;
  system.SetBodyState(a, x, u, y);
  x(2) = kRadius;
  u(2) = 0.1;
  system.SetBodyState(b, x, u, y);
  const EventDrivenContacts contacts(system, EventDrivenOptions{});
  const ImpactResult impact = contacts.Impact(0.0, y, {0, 1});
  const double P_pair = 1.0 * (0.8 * 2.1 + 2.0), P_floor = P_pair - 2.0 * 0.1;
  std::printf("P_floor %.15f (%.15f), P_pair %.15f (%.15f), U_N+ floor %.3e, pair %.15f\n",
              impact.P_N(0), P_floor, impact.P_N(1), P_pair, impact.U_N_after(0),
              impact.U_N_after(1));
  // Measured: exact to 4.4e-16 (Lemke's LU on the final basis).
  EXPECT_NEAR(impact.P_N(0), P_floor, 1e-14);
  EXPECT_NEAR(impact.P_N(1), P_pair, 1e-14);
  EXPECT_NEAR(impact.U_N_after(0), 0.0, 1e-14);
  EXPECT_NEAR(impact.U_N_after(1), 0.8 * 2.1, 1e-14);
}

}  // namespace
}  // namespace flexmbs::mbs
