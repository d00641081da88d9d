// Coulomb friction in event-driven integration (mbs/event_driven_contacts.h, Tangential): a ball
// launched sliding without spin rolls from the closed-form time on; a block on an incline sticks
// below the friction angle and slides with the closed-form acceleration above it; a block pushed
// across a plane stops at the closed-form distance and rests; oblique impacts with friction give
// the rigid-body impact law's velocities (sliding through the impact or rolling off it) and never
// gain energy.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "mbs/event_driven.h"
#include "mbs/multibody_system.h"
#include "tests/mbs/moreau_jean_support.h"

namespace flexmbs::mbs {
namespace {

using Eigen::Vector3d;
using Eigen::VectorXd;
using testing::BallOnFloor;
using testing::BlockOnIncline;
using testing::ContactScene;
using testing::EventRun;
using testing::RunEventDriven;

constexpr double kMass = 1.0, kRadius = 0.1, kG = 9.81;

/// The events of one kind.
std::vector<ContactEvent> EventsOf(const EventRun& run, ContactEventKind kind) {
  std::vector<ContactEvent> out;
  for (const ContactEvent& event : run.events) {
    if (event.kind == kind) out.push_back(event);
  }
  return out;
}

/// The body's translational velocity v and angular velocity in its frame w_B of a one-body state.
Vector3d Velocity(const MultibodySystem& system, const VectorXd& y) { return system.BodyVelocities(y, 0).head<3>(); }
Vector3d AngularVelocity(const MultibodySystem& system, const VectorXd& y) {
  return system.BodyVelocities(y, 0).segment<3>(3);
}
Vector3d Position(const MultibodySystem& system, const VectorXd& y) { return system.BodyPositions(y, 0).head<3>(); }

TEST(EventDrivenFriction, ABallLaunchedSlidingRollsFromTheClosedFormTimeOn) {
  // Sliding: v' = -mu g, w' = 5 mu g / (2 r); the contact point's speed v - r w falls as
  // v0 - 7/2 mu g t and reaches 0 at t* = 2 v0 / (7 mu g), where v = 5/7 v0; then it rolls.
  constexpr double mu = 0.2, v0 = 2.0;
  const double t_star = 2.0 * v0 / (7.0 * mu * kG);
  ContactScene scene = BallOnFloor(kMass, kRadius, 0.0, kG, 0.0, mu, Vector3d(v0, 0.0, 0.0));
  const EventRun run = RunEventDriven(scene, 1.0, 0.05, 1e-3);
  const std::vector<ContactEvent> sticks = EventsOf(run, ContactEventKind::kStick);
  ASSERT_EQ(sticks.size(), 1u);
  EXPECT_TRUE(EventsOf(run, ContactEventKind::kImpact).empty());
  const MultibodySystem& system = *scene.system;
  const VectorXd& end = run.y.back();
  const double v_end = Velocity(system, end).x(), w_end = AngularVelocity(system, end).y();
  const double x_star = v0 * t_star - 0.5 * mu * kG * t_star * t_star;
  const double x_end = x_star + 5.0 / 7.0 * v0 * (run.t.back() - t_star);
  // Energy lost while sliding: m v0^2 / 7 (the rest rolls on).
  const double lost = run.energy.front() - run.energy.back();
  std::printf("stick at %.15f s (closed form %.15f s), v %.15f (5/7 v0 %.15f) m/s, r w - v %.3e m/s, x %.12f "
              "(%.12f) m, energy lost %.12f (m v0^2/7 %.12f) J, %ld events, %.3f s wall\n",
              sticks[0].time, t_star, v_end, 5.0 / 7.0 * v0, kRadius * w_end - v_end, Position(system, end).x(), x_end,
              lost, kMass * v0 * v0 / 7.0, run.statistics.event_driven.events, run.wall_seconds);
  // Measured: stick time 1.5e-13 s, v 2.7e-15 m/s, x and energy exact to the printed digits.
  EXPECT_NEAR(sticks[0].time, t_star, 1e-12);
  EXPECT_NEAR(v_end, 5.0 / 7.0 * v0, 1e-12);
  EXPECT_NEAR(kRadius * w_end, v_end, 1e-12);
  EXPECT_NEAR(Position(system, end).x(), x_end, 1e-11);
  EXPECT_NEAR(lost, kMass * v0 * v0 / 7.0, 1e-11);
  // Rolling needs no friction force: the last interval's tangential impulse is 0.
  EXPECT_NEAR(run.contacts.back().contacts[0].P_T.norm(), 0.0, 1e-12);
  EXPECT_FALSE(run.contacts.back().contacts[0].sliding);
}

/// The block's displacement down the slope (cos a, 0, -sin a) and its speed along it.
struct SlopeMotion {
  double distance = 0.0, speed = 0.0;
};
SlopeMotion AlongSlope(const ContactScene& scene, const VectorXd& y, double angle) {
  const Vector3d down(std::cos(angle), 0.0, -std::sin(angle));
  const MultibodySystem& system = *scene.system;
  return {(Position(system, y) - Position(system, scene.y0)).dot(down), Velocity(system, y).dot(down)};
}

TEST(EventDrivenFriction, ABlockOnAnInclineSticksBelowTheFrictionAngleAndSlidesWithTheClosedFormAboveIt) {
  constexpr double mu = 0.3, kTime = 0.5;
  for (const double angle : {0.2, 0.4}) {  // tan 0.2 = 0.203 < mu < tan 0.4 = 0.423
    ContactScene scene = BlockOnIncline(angle, mu, kG);
    const EventRun run = RunEventDriven(scene, kTime, 0.05, 1e-3);
    const SlopeMotion motion = AlongSlope(scene, run.y.back(), angle);
    const double a = std::max(0.0, kG * (std::sin(angle) - mu * std::cos(angle)));
    std::printf("angle %.1f: after %.1f s %.15f m (closed form %.15f m), speed %.15f (%.15f) m/s; %ld slips, "
                "%ld sticks, %ld separations, %ld events, %.3f s wall\n",
                angle, kTime, motion.distance, 0.5 * a * kTime * kTime, motion.speed, a * kTime,
                run.statistics.event_driven.slips, run.statistics.event_driven.sticks,
                run.statistics.event_driven.separations, run.statistics.event_driven.events, run.wall_seconds);
    // Measured: sticking 2e-15 m and 0 m/s; sliding 4e-15 m and 1.4e-14 m/s. (With NSGS for the
    // sticking problem instead of the proximal Newton solver: 3.3e-11 m, its tolerance's drift.)
    EXPECT_NEAR(motion.distance, 0.5 * a * kTime * kTime, 5e-14) << angle;
    EXPECT_NEAR(motion.speed, a * kTime, 1e-13) << angle;
    EXPECT_EQ(run.statistics.event_driven.slips > 0, a > 0.0) << angle;
    // Four feet on a rigid block carry statically indeterminate forces; the LCP may leave one
    // unloaded and let it open (the block then slides on three; measured: none opens).
    int sliding = 0;
    for (const ContactStepResult& foot : run.contacts.back().contacts) sliding += foot.sliding ? 1 : 0;
    if (a > 0.0) {
      EXPECT_GE(sliding, 3) << angle;
    } else {
      EXPECT_EQ(sliding, 0) << angle;
    }
  }
}

TEST(EventDrivenFriction, ABlockPushedAcrossAPlaneStopsAtTheClosedFormDistanceAndRests) {
  // Sliding under mu m g alone: it stops at t = v0 / (mu g) after v0^2 / (2 mu g).
  constexpr double mu = 0.4, v0 = 1.5;
  ContactScene scene = BlockOnIncline(0.0, mu, kG);
  VectorXd u0 = VectorXd::Zero(6);
  u0(0) = v0;
  scene.system->SetBodyState(0, scene.system->BodyPositions(scene.y0, 0), u0, scene.y0);
  const EventRun run = RunEventDriven(scene, 1.0, 0.05, 1e-3);
  const std::vector<ContactEvent> sticks = EventsOf(run, ContactEventKind::kStick);
  ASSERT_FALSE(sticks.empty());
  const SlopeMotion rest = AlongSlope(scene, run.y.back(), 0.0);
  const double t_stop = v0 / (mu * kG), d_stop = v0 * v0 / (2.0 * mu * kG);
  std::printf("stopped at %.15f s (closed form %.15f s) after %.15f m (%.15f m), speed then %.3e m/s; %zu stick "
              "events\n",
              sticks.front().time, t_stop, rest.distance, d_stop, rest.speed, sticks.size());
  // Measured: 1.2e-14 s and 3e-15 m; the four feet stick at one event.
  EXPECT_NEAR(sticks.front().time, t_stop, 1e-13);
  EXPECT_NEAR(rest.distance, d_stop, 5e-14);
  EXPECT_NEAR(rest.speed, 0.0, 1e-12);
  for (const ContactEvent& stick : sticks) EXPECT_NEAR(stick.time, t_stop, 1e-13);
}

/// A ball at `gap0` above the floor without gravity, moving at (v_t, 0, -v_n) without spin, runs
/// through its impact; its velocity and spin just after.
struct ObliqueImpact {
  Vector3d v, w_B;
  double energy_before = 0.0, energy_after = 0.0;
};
ObliqueImpact RunObliqueImpact(double v_t, double v_n, double e, double mu) {
  ContactScene scene = BallOnFloor(kMass, kRadius, 1e-3, 0.0, e, mu, Vector3d(v_t, 0.0, -v_n));
  const double t_hit = 1e-3 / v_n;
  const EventRun run = RunEventDriven(scene, 2.0 * t_hit, t_hit, 1e-6);
  const std::vector<ContactEvent> impacts = EventsOf(run, ContactEventKind::kImpact);
  EXPECT_EQ(impacts.size(), 1u);
  const MultibodySystem& system = *scene.system;
  return {Velocity(system, run.y.back()), AngularVelocity(system, run.y.back()), impacts.at(0).kinetic_energy_before,
          impacts.at(0).kinetic_energy_after};
}

TEST(EventDrivenFriction, AnObliqueImpactSlidesThroughOrRollsOffAsTheRigidImpactLawSays) {
  // P_N = m (1 + e) v_n; the contact point's tangential speed changes by -7/2 P_T / m (solid
  // sphere): it rolls off (P_T = 2/7 m v_t, v+ = 5/7 v_t) if that fits in the cone, mu P_N >= 2/7
  // m v_t; otherwise it slides through with P_T = mu P_N.
  constexpr double v_n = 2.0, e = 0.5;
  for (const double mu : {0.05, 0.6}) {
    const double v_t = 1.0, P_N = kMass * (1.0 + e) * v_n;
    const bool rolls = mu * P_N >= 2.0 / 7.0 * kMass * v_t;
    const double P_T = rolls ? 2.0 / 7.0 * kMass * v_t : mu * P_N;
    const ObliqueImpact impact = RunObliqueImpact(v_t, v_n, e, mu);
    const double v_expected = v_t - P_T / kMass, w_expected = 2.5 * P_T / (kMass * kRadius);
    std::printf("mu %.2f (%s): v+ (%.15f, %.15f) m/s (expected (%.15f, %.15f)), w_y %.15f (%.15f) rad/s\n", mu,
                rolls ? "rolls off" : "slides through", impact.v.x(), impact.v.z(), v_expected, e * v_n,
                impact.w_B.y(), w_expected);
    // Measured: 1.5e-12 m/s, 1.8e-12 rad/s (the proximal Newton solver's stop at its tolerance,
    // 1e-10 of the problem's scale).
    EXPECT_NEAR(impact.v.x(), v_expected, 1e-11) << mu;
    EXPECT_NEAR(impact.v.z(), e * v_n, 1e-11) << mu;
    EXPECT_NEAR(impact.w_B.y(), w_expected, 2e-11) << mu;
  }
}

TEST(EventDrivenFriction, AnImpactWithFrictionNeverGainsEnergy) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double worst = -1e300;
  for (int trial = 0; trial < 40; ++trial) {
    const double v_t = 3.0 * unit(random), v_n = 0.2 + 2.0 * unit(random), e = unit(random), mu = unit(random);
    const ObliqueImpact impact = RunObliqueImpact(v_t, v_n, e, mu);
    worst = std::max(worst, impact.energy_after - impact.energy_before);
    EXPECT_LE(impact.energy_after, impact.energy_before + 1e-13) << trial;
  }
  std::printf("largest energy change through 40 random impacts with friction: %.3e J\n", worst);
}

}  // namespace
}  // namespace flexmbs::mbs
