// Moreau-Jean time stepping with Coulomb friction: a block on four corner contacts on an incline
// sticks below the friction angle and slides with the analytic acceleration g (sin a - mu cos a)
// above it; a block pushed along a level plane stops at v0^2 / (2 mu g); a contact solve that does
// not converge stops the run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "mbs/moreau_jean.h"
#include "mbs/simulation_error.h"
#include "tests/mbs/moreau_jean_support.h"

namespace flexmbs::mbs {
namespace {

constexpr double kG = 9.81, kStep = 1e-3, kEndTime = 1.0;

/// The block's velocity v_WBo_W (state entries 7..9).
Eigen::Vector3d BlockVelocity(const Eigen::VectorXd& y) { return y.segment<3>(7); }

TEST(MoreauJeanFriction, BlockSticksBelowTheFrictionAngle) {
  const double angle = 0.35, mu = 0.5;  // tan(0.35) = 0.365 < 0.5
  testing::ContactScene scene = testing::BlockOnIncline(angle, mu, kG);
  const testing::StepHistory history = testing::RunMoreauJean(scene, kStep, kEndTime);
  double fastest = 0.0, drift = 0.0;
  for (std::size_t k = 0; k < history.y.size(); ++k) {
    fastest = std::max(fastest, BlockVelocity(history.y[k]).norm());
    drift = std::max(drift, (history.y[k].head<3>() - history.y[0].head<3>()).norm());
    EXPECT_EQ(history.steps[k].active_contacts, k == 0 ? 0 : 4) << "t = " << history.t[k];
    for (const ContactStepResult& corner : history.steps[k].contacts) EXPECT_FALSE(corner.sliding) << history.t[k];
  }
  std::printf("sticking at a = %.2f rad, mu = %.2f: largest speed %.3e m/s, largest displacement %.3e m\n", angle, mu,
              fastest, drift);
  // Measured: 1.4e-13 m/s and 1.4e-13 m (the solver tolerance 1e-10 on impulses of ~m g h / 4).
  EXPECT_LT(fastest, 1e-9);
  EXPECT_LT(drift, 1e-9);
}

TEST(MoreauJeanFriction, BlockSlidesWithTheAnalyticAccelerationAboveTheFrictionAngle) {
  const double angle = 0.5, mu = 0.3;  // tan(0.5) = 0.546 > 0.3
  const double acceleration = kG * (std::sin(angle) - mu * std::cos(angle));
  const Eigen::Vector3d down_slope(std::cos(angle), 0.0, -std::sin(angle));
  testing::ContactScene scene = testing::BlockOnIncline(angle, mu, kG);
  const testing::StepHistory history = testing::RunMoreauJean(scene, kStep, kEndTime);
  double worst = 0.0, off_slope = 0.0;
  for (std::size_t k = 0; k < history.y.size(); ++k) {
    const Eigen::Vector3d v = BlockVelocity(history.y[k]);
    worst = std::max(worst, std::abs(v.dot(down_slope) - acceleration * history.t[k]));
    off_slope = std::max(off_slope, (v - v.dot(down_slope) * down_slope).norm());
    // Every corner slides from the first step on (the results' `sliding`).
    for (const ContactStepResult& corner : history.steps[k].contacts) EXPECT_EQ(corner.sliding, k > 0) << history.t[k];
  }
  const double measured = BlockVelocity(history.y.back()).dot(down_slope) / history.t.back();
  std::printf("sliding at a = %.2f rad, mu = %.2f: acceleration %.12f m/s^2 against %.12f (relative error %.2e), "
              "largest velocity error %.2e m/s, off the slope %.2e m/s\n",
              angle, mu, measured, acceleration, std::abs(measured / acceleration - 1.0), worst, off_slope);
  // Measured: relative error 1.6e-14, velocity error 6.0e-14 m/s, 2.0e-13 m/s off the slope (the
  // constant acceleration is exact in the scheme; the solver tolerance remains).
  EXPECT_LT(std::abs(measured / acceleration - 1.0), 1e-9);
  EXPECT_LT(worst, 1e-9);
  EXPECT_LT(off_slope, 1e-9);
}

TEST(MoreauJeanFriction, PushedBlockStopsAtTheAnalyticDistance) {
  // A block pushed to v0 along a level plane decelerates at mu g and stops after v0^2 / (2 mu g)
  // at v0 / (mu g), then stays.
  const double mu = 0.4, v0 = 2.0;
  testing::ContactScene scene = testing::BlockOnIncline(0.0, mu, kG);
  scene.y0.segment<3>(7) = Eigen::Vector3d(v0, 0.0, 0.0);
  const testing::StepHistory history = testing::RunMoreauJean(scene, kStep, kEndTime);
  const double distance = v0 * v0 / (2.0 * mu * kG), stop_time = v0 / (mu * kG);
  double worst_velocity = 0.0;
  for (std::size_t k = 0; k < history.y.size(); ++k) {
    const double expected = std::max(0.0, v0 - mu * kG * history.t[k]);
    worst_velocity = std::max(worst_velocity, std::abs(BlockVelocity(history.y[k]).x() - expected));
  }
  const double travelled = history.y.back().x() - history.y.front().x();
  std::printf("pushed at %.1f m/s, mu = %.1f: stops after %.9f m against %.9f m (stop at %.4f s), largest velocity "
              "error %.2e m/s\n",
              v0, mu, travelled, distance, stop_time, worst_velocity);
  // Measured: the distance within 4.2e-7 m (the stop at 0.5097 s falls inside a step of 1 ms,
  // where the theta = 1/2 positions average the last step's velocities) and the velocity within
  // 2.3e-13 m/s (the deceleration is exact in the scheme; the solver tolerance remains).
  EXPECT_NEAR(travelled, distance, 4e-6);
  EXPECT_LT(worst_velocity, 3e-12);
  EXPECT_LT(BlockVelocity(history.y.back()).norm(), 1e-9);  // at rest after the stop
}

TEST(MoreauJeanFriction, ContactSolveThatDoesNotConvergeStopsNamingStepTimeAndResidual) {
  // A tolerance below round-off cannot be met: the step must fail, not go on unconverged.
  testing::ContactScene scene = testing::BlockOnIncline(0.5, 0.3, kG);
  MoreauJeanOptions options{kStep, 0.5};
  options.solver_tolerance = 1e-300;
  options.solver_max_iterations = 2;
  MoreauJeanStepper stepper(*scene.system, options);
  Eigen::VectorXd y = scene.y0;
  try {
    stepper.Step(0.25, kStep, y);
    FAIL() << "no error";
  } catch (const SimulationError& e) {
    const std::string message = e.what();
    EXPECT_EQ(e.time(), 0.25);
    EXPECT_NE(message.find("t = 0.25 s: Moreau-Jean step 1 (0.25 -> 0.251 s): the contact solve of 4 active contacts "
                           "did not converge: residual"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("> tolerance 1e-300"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace flexmbs::mbs
