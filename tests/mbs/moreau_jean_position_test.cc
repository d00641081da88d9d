// Moreau-Jean on position level (mbs/moreau_jean.h, ImpactLevel::kPosition; docs/contact.md,
// "Impact on position level"): the LCP on the gap the step's positions reach,
// 0 <= P_N _|_ g_N(x_k) + h U_N,k+1 >= 0 with theta = 1 (Stewart & Trinkle 1996). A dropped ball
// lands on the floor without the penetration velocity level keeps, energy never rises, Coulomb
// friction on an incline keeps its closed forms, and the laws it cannot integrate are refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/error.h"
#include "mbs/moreau_jean.h"
#include "tests/mbs/moreau_jean_support.h"

namespace flexmbs::mbs {
namespace {

using testing::BallOnFloor;
using testing::RunMoreauJean;
using testing::StepHistory;

constexpr double kMass = 1.0, kRadius = 0.1, kG = 9.81, kStep = 1e-3;

/// The smallest gap of contact 0 over the steps from the first with an impulse on.
double SmallestGapAfterLanding(const StepHistory& history) {
  double smallest = std::numeric_limits<double>::infinity();
  bool landed = false;
  for (const MoreauJeanStepReport& step : history.steps) {
    landed = landed || step.contacts[0].P_N > 0.0;
    if (landed) smallest = std::min(smallest, step.contacts[0].g_N);
  }
  return smallest;
}

TEST(MoreauJeanPositionLevel, DroppedBallLandsWithoutPenetrationAndRests) {
  // The ball falls about 1 m (4.43 m/s at the touch), from heights that put the touch at
  // different places within a step. Both levels stop it (e = 0, theta = 1); velocity level keeps
  // the penetration of the step that closed the gap, position level ends that step on the floor
  // and carries the weight from there with the gap at round-off.
  double velocity_gap = 0.0, position_gap = 0.0;
  for (const double drop : {1.0, 0.9993, 0.9986, 0.9979, 0.9972}) {
    testing::ContactScene velocity_scene = BallOnFloor(kMass, kRadius, drop, kG, 0.0, 0.0);
    const StepHistory velocity = RunMoreauJean(velocity_scene, kStep, 1.0, 1.0, ImpactLevel::kVelocity);
    testing::ContactScene position_scene = BallOnFloor(kMass, kRadius, drop, kG, 0.0, 0.0);
    const StepHistory position = RunMoreauJean(position_scene, kStep, 1.0, 1.0, ImpactLevel::kPosition);
    velocity_gap = std::min(velocity_gap, SmallestGapAfterLanding(velocity));
    position_gap = std::min(position_gap, SmallestGapAfterLanding(position));
    EXPECT_NEAR(position.steps.back().contacts[0].g_N, 0.0, 1e-14) << drop;
    EXPECT_EQ(position.y.back()(9), 0.0) << drop;
    // Resting: each step's impulse is the weight's, m g h.
    EXPECT_NEAR(position.steps.back().contacts[0].P_N, kMass * kG * kStep, 1e-14) << drop;
  }
  std::printf("ball dropped about 1 m, h = %g s, theta = 1: smallest gap after landing %.3e m on velocity level "
              "(h v = %.3e m), %.3e m on position level\n",
              kStep, velocity_gap, kStep * std::sqrt(2.0 * kG), position_gap);
  // Measured: velocity level down to -1.99e-3 m, position level 0 (never below).
  EXPECT_LT(velocity_gap, -1e-3);
  EXPECT_GT(position_gap, -1e-14);
}

TEST(MoreauJeanPositionLevel, EnergyNeverRisesThroughImpacts) {
  // With theta = 1 a step's impulse works on v_k+1: P_N U_N,k+1 = -P_N g_N(x_k) / h <= 0 while the
  // gap is open (g_N(x_k) >= 0), and friction works against the slip. An oblique, spinning ball.
  double worst_gain = -std::numeric_limits<double>::infinity();
  for (const double mu : {0.0, 0.3}) {
    testing::ContactScene scene =
        BallOnFloor(kMass, kRadius, 0.2, kG, 0.0, mu, Eigen::Vector3d(1.0, 0.5, 0.0), Eigen::Vector3d(0.0, 20.0, 3.0));
    const StepHistory history = RunMoreauJean(scene, kStep, 1.0, 1.0, ImpactLevel::kPosition);
    for (std::size_t k = 1; k < history.energy.size(); ++k) {
      const double gain = history.energy[k] - history.energy[k - 1];
      if (history.steps[k].contacts[0].active) worst_gain = std::max(worst_gain, gain);
      // Measured: <= 8.9e-16 J over the contact steps (round-off on ~2.5 J).
      EXPECT_LT(gain, 1e-14) << "mu = " << mu << ", t = " << history.t[k];
    }
  }
  std::printf("largest energy change over a step with contact on position level: %.3e J\n", worst_gain);
}

TEST(MoreauJeanPositionLevel, BlockOnAnInclineSticksBelowAndSlidesAboveTheFrictionAngle) {
  // The block on four corner spheres (moreau_jean_support.h) with theta = 1: below the friction
  // angle it stays; above it v = g (sin a - mu cos a) t exactly, the backward Euler velocity of a
  // constant acceleration.
  testing::ContactScene sticking = testing::BlockOnIncline(0.35, 0.5, kG);
  const StepHistory stuck = RunMoreauJean(sticking, kStep, 0.5, 1.0, ImpactLevel::kPosition);
  // The first step lifts the block from 1e-12 m inside the plane to its surface (1e-9 m/s along
  // the normal); from the second on it stays.
  const double push_out = stuck.y[1].segment<3>(7).norm();
  double speed = 0.0;
  for (std::size_t k = 2; k < stuck.y.size(); ++k) speed = std::max(speed, stuck.y[k].segment<3>(7).norm());
  testing::ContactScene sliding = testing::BlockOnIncline(0.5, 0.3, kG);
  const StepHistory slid = RunMoreauJean(sliding, kStep, 0.5, 1.0, ImpactLevel::kPosition);
  const double a = kG * (std::sin(0.5) - 0.3 * std::cos(0.5));
  double worst = 0.0;
  for (std::size_t k = 2; k < slid.t.size(); ++k) {
    const double along = slid.y[k](7) * std::cos(0.5) - slid.y[k](9) * std::sin(0.5);
    worst = std::max(worst, std::abs(along - a * slid.t[k]));
  }
  std::printf("incline on position level: push-out %.3e m/s, then sticking speed <= %.3e m/s; sliding velocity off "
              "g (sin a - mu cos a) t by <= %.3e m/s\n",
              push_out, speed, worst);
  // Measured: push-out 1.0e-9 m/s, then 1.1e-13 m/s; sliding off by 7.5e-14 m/s (the friction
  // solver's tolerance 1e-10 on impulses of ~m g h / 4).
  EXPECT_NEAR(push_out, 1e-9, 1e-11);
  EXPECT_LT(speed, 1e-12);
  EXPECT_LT(worst, 1e-12);
}

TEST(MoreauJeanPositionLevel, RefusesRestitutionAndThetaBelowOne) {
  testing::ContactScene bouncing = BallOnFloor(kMass, kRadius, 1.0, kG, 0.9, 0.0);
  MoreauJeanOptions options{kStep, 1.0};
  options.impact_level = ImpactLevel::kPosition;
  try {
    MoreauJeanStepper stepper(*bouncing.system, options);
    ADD_FAILURE() << "a restitution of 0.9 was taken on position level";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "contact 'floor': restitution 0.9 needs impact level velocity (on position level the "
                           "points' impacts are inelastic, e = 0)");
  }
  options.theta = 0.5;
  try {
    CheckMoreauJeanOptions(options);
    ADD_FAILURE() << "theta 0.5 was taken on position level";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "simulation: impact_level position needs theta 1 (the gap the positions reach, "
                           "x_k+1 = x_k + h v_k+1), not 0.5");
  }
}

}  // namespace
}  // namespace flexmbs::mbs
