// Moreau-Jean time stepping (mbs/moreau_jean.h) on the bouncing ball: impact times against the
// closed form, rest at the analytic accumulation time without a Zeno hang, step-by-step agreement
// with Siconos' own MoreauJeanOSI on the same data (tests/mbs/siconos_bouncing_ball.py), energy
// through impacts, and e = 0 sticking at the first impact.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <tuple>
#include <vector>

#include "mbs/moreau_jean.h"
#include "mbs/rigid_body.h"
#include "mbs/simulation.h"
#include "mbs/unilateral_contact.h"
#include "tests/mbs/moreau_jean_support.h"

namespace flexmbs::mbs {
namespace {

using testing::BallOnFloor;
using testing::RunMoreauJean;
using testing::StepHistory;

constexpr double kMass = 1.0, kRadius = 0.1, kGap0 = 1.0, kG = 9.81, kRestitution = 0.9;

/// The steps (by their end time) whose normal impulse ends a flight: the first active step
/// after inactive ones.
std::vector<double> ImpactTimes(const StepHistory& history) {
  std::vector<double> times;
  for (std::size_t k = 1; k < history.steps.size(); ++k) {
    if (history.steps[k].contacts[0].P_N > 0.0 && !(history.steps[k - 1].contacts[0].P_N > 0.0)) {
      times.push_back(history.t[k]);
    }
  }
  return times;
}

TEST(MoreauJean, BouncingBallImpactTimesMatchTheClosedFormToOrderH) {
  const double v1 = std::sqrt(2.0 * kG * kGap0), t1 = std::sqrt(2.0 * kGap0 / kG);
  std::array<double, 2> errors{};
  const std::array<double, 2> steps{2e-3, 1e-3};
  for (std::size_t run = 0; run < steps.size(); ++run) {
    const double h = steps[run];
    testing::ContactScene scene = BallOnFloor(kMass, kRadius, kGap0, kG, kRestitution, 0.0);
    const StepHistory history = RunMoreauJean(scene, h, 4.0);
    const std::vector<double> impacts = ImpactTimes(history);
    // Closed form: t_1 = sqrt(2 h0 / g), t_k+1 = t_k + 2 e^k v_1 / g. The impact falls inside
    // the step that ends at the recorded time: compare its middle.
    double t_exact = t1, speed = v1, worst = 0.0;
    std::size_t compared = 0;
    for (const double t_step_end : impacts) {
      if (t_exact > 3.5) break;
      worst = std::max(worst, std::abs(t_step_end - 0.5 * h - t_exact));
      ++compared;
      speed *= kRestitution;
      t_exact += 2.0 * speed / kG;
    }
    ASSERT_GE(compared, 5u);
    errors[run] = worst;
    std::printf("h = %g s: %zu impacts up to 3.5 s, largest impact-time error %.3e s (%.2f h)\n", h, compared, worst,
                worst / h);
  }
  // Measured over the first 5 impacts: 6.5e-3 s (3.2 h) at h = 2e-3 s, 4.0e-3 s (4.0 h) at
  // 1e-3 s. First order: each impact acts at a step (within h of the exact time), and its rebound
  // speed -e v_k takes v_k up to a step before the touch, so every bounce adds an error of O(h)
  // to the next flight; the errors add up over the impacts.
  constexpr double kErrorPerStep = 40.0;  // x h, 10x the measured 4.0 h
  EXPECT_LT(errors[0], kErrorPerStep * steps[0]);
  EXPECT_LT(errors[1], kErrorPerStep * steps[1]);
  EXPECT_LT(errors[1], 0.75 * errors[0]) << "not converging with h";
}

TEST(MoreauJean, BouncingBallComesToRestAtTheAccumulationTime) {
  const double h = 1e-3;
  const double v1 = std::sqrt(2.0 * kG * kGap0), t1 = std::sqrt(2.0 * kGap0 / kG);
  const double t_inf = t1 + 2.0 * kRestitution * v1 / (kG * (1.0 - kRestitution));
  testing::ContactScene scene = BallOnFloor(kMass, kRadius, kGap0, kG, kRestitution, 0.0);
  const StepHistory history = RunMoreauJean(scene, h, t_inf + 1.0);  // ends: no Zeno hang
  ASSERT_NEAR(history.t.back(), t_inf + 1.0, 1e-9);
  // The rest time: the end of the last step with an empty index set (the contact stays closed
  // from there on). In persistent contact Newton's law still acts at every step,
  // U_N,k+1 = -e U_N,k while the weight's impulse keeps P_N > 0, so the last bounce's velocity
  // decays geometrically, by e per step, down to round-off.
  std::size_t rest = history.t.size() - 1;
  while (rest > 0 && history.steps[rest].contacts[0].active) --rest;
  const double t_rest = history.t[rest];
  std::size_t still = rest;
  while (still < history.t.size() && std::abs(history.y[still](9)) > 1e-12) ++still;
  ASSERT_LT(still, history.t.size());
  const double final_gap = history.steps.back().contacts[0].g_N;
  std::printf("analytic accumulation time %.6f s, contact closed for good from %.6f s (error %.3e s = %.1f h), "
              "|v_z| < 1e-12 m/s from %.4f s; at the end gap %.3e m, v_z %.3e m/s\n",
              t_inf, t_rest, t_rest - t_inf, (t_rest - t_inf) / h, history.t[still], final_gap, history.y.back()(9));
  // Measured: closed for good 0.016 s (16 h) before t_inf (O(h) errors of the rebound speeds
  // shorten the last flights); |v_z| < 1e-12 m/s 0.17 s after t_inf (e^n decay from ~1e-2 m/s),
  // then +-7e-18 m/s; the gap at rest -1.08e-6 m (the last bounces' O(h v) penetration, kept).
  constexpr double kRestTimeTolerance = 0.16;  // [s], 10x the measured 0.016 s
  constexpr double kSettleTime = 0.5;          // [s], 3x the measured 0.17 s
  constexpr double kRestGapTolerance = 1e-5;   // [m], 10x the measured 1.08e-6 m
  EXPECT_NEAR(t_rest, t_inf, kRestTimeTolerance);
  EXPECT_LT(history.t[still], t_inf + kSettleTime);
  for (std::size_t k = still; k < history.t.size(); ++k) ASSERT_LT(std::abs(history.y[k](9)), 1e-12) << history.t[k];
  EXPECT_LT(std::abs(final_gap), kRestGapTolerance);
  // Resting: the impulse of each step carries the weight, m g h (the last step is shorter).
  const double last_step = history.t.back() - history.t[history.t.size() - 2];
  EXPECT_NEAR(history.steps.back().contacts[0].P_N, kMass * kG * last_step, 1e-14);
}

TEST(MoreauJean, EnergyNeverIncreasesThroughImpacts) {
  // With theta = 1/2 the free flight keeps E = T + V exactly, and a step's energy change is the
  // work of its impulses on the mean velocity (v_k + v_k+1) / 2. For the normal impulse with
  // Newton's law (U_N,k+1 = -e U_N,k when P_N > 0) that is P_N U_N,k (1 - e) / 2: <= 0 through an
  // impact (U_N,k <= 0) for every e in [0, 1]. A contact kept active while it separates slowly
  // (U_N,k > 0, predicted gap still closed: the settling of the last bounces) does positive work
  // of the order m (g h)^2 / 8 (1 - e)^2: the known energy defect of the scheme's midpoint
  // positions, the same in Siconos (which this scheme matches step by step).
  double worst_impact_gain = 0.0, worst_settling_gain = 0.0;
  for (const double e : {0.0, 0.5, 0.9, 1.0}) {
    for (const double mu : {0.0, 0.3}) {
      // An oblique, spinning ball: with friction the impacts also stop the slip.
      testing::ContactScene scene =
          BallOnFloor(kMass, kRadius, 0.2, kG, e, mu, Eigen::Vector3d(1.0, 0.5, 0.0), Eigen::Vector3d(0.0, 20.0, 3.0));
      const StepHistory history = RunMoreauJean(scene, 1e-3, 1.5);
      for (std::size_t k = 1; k < history.energy.size(); ++k) {
        const double gain = history.energy[k] - history.energy[k - 1];
        const double U_N_before = history.y[k - 1](9);  // the floor's W_N picks v_z
        const ContactStepResult& contact = history.steps[k].contacts[0];
        if (!contact.active || U_N_before <= 0.0) {
          EXPECT_LT(gain, 1e-12) << "e = " << e << ", mu = " << mu << ", t = " << history.t[k];
          worst_impact_gain = std::max(worst_impact_gain, gain);
        } else {
          const double normal_work = 0.5 * contact.P_N * U_N_before * (1.0 - e);
          if (mu == 0.0) {
            EXPECT_NEAR(gain, normal_work, 1e-12) << "e = " << e << ", t = " << history.t[k];
          }
          worst_settling_gain = std::max(worst_settling_gain, gain);
        }
      }
      EXPECT_LE(history.energy.back(), history.energy.front() + 1e-12) << "e = " << e << ", mu = " << mu;
    }
  }
  // Measured: <= 1.8e-15 J (round-off on ~3 J) over impacts and flights; settling <= 7.2e-7 J.
  std::printf("largest energy change over a step with an impact or free flight %.3e J, while settling %.3e J "
              "(m (g h)^2 / 8 = %.3e J)\n",
              worst_impact_gain, worst_settling_gain, kMass * std::pow(kG * 1e-3, 2) / 8.0);
}

TEST(MoreauJean, PerfectlyPlasticImpactSticksAtTheFirstImpact) {
  const double h = 1e-3;
  testing::ContactScene scene = BallOnFloor(kMass, kRadius, kGap0, kG, 0.0, 0.0);
  const StepHistory history = RunMoreauJean(scene, h, 1.0);
  const std::vector<double> impacts = ImpactTimes(history);
  ASSERT_EQ(impacts.size(), 1u);
  for (std::size_t k = 0; k < history.t.size(); ++k) {
    if (history.t[k] < impacts[0]) continue;
    EXPECT_TRUE(history.steps[k].contacts[0].active) << "t = " << history.t[k];
    EXPECT_EQ(history.y[k](9), 0.0) << "t = " << history.t[k];
  }
}

TEST(MoreauJean, AnOutputIntervalReportsItsLastStepsPointLoads) {
  // A ball 1 mm above the floor (e = 0) lands at 14.3 ms; with outputs every 10 steps of 1 ms the
  // interval [10, 20] ms starts in flight and ends at rest: its report's point loads (what the
  // ParaView files draw) are the last step's, the weight m g at the ball's lowest point.
  testing::ContactScene scene = BallOnFloor(kMass, kRadius, 1e-3, kG, 0.0, 0.0);
  SimulationOptions options;
  options.end_time = 0.03;
  options.output_interval = 0.01;
  options.moreau_jean = MoreauJeanOptions{1e-3};
  std::vector<MoreauJeanStepReport> intervals;
  Simulate(*scene.system, options, scene.y0, [](double, const Eigen::VectorXd&, const Eigen::VectorXd&) {},
           [&](double, const MoreauJeanStepReport& report) { intervals.push_back(report); });
  ASSERT_EQ(intervals.size(), 4u);  // the initial report and three intervals
  EXPECT_TRUE(intervals[1].contacts[0].loads.empty());
  const std::vector<ContactLoad>& loads = intervals[2].contacts[0].loads;
  ASSERT_EQ(loads.size(), 1u);
  EXPECT_NEAR(loads[0].f_W.z(), kMass * kG, 1e-12);  // Lemke's one pivot: round-off
  EXPECT_NEAR(loads[0].p_W.z(), intervals[2].contacts[0].g_N, 1e-15);  // the lowest point, at the gap
}

TEST(MoreauJean, TwoSpheresCollideWithNewtonsRestitution) {
  // Two free balls (1 kg, r = 0.1 m; 2 kg, r = 0.15 m) head-on along x without gravity, e = 0.8:
  // after the impact v1' = (m1 v1 + m2 v2 - m2 e (v1 - v2)) / (m1 + m2), v2' likewise, the
  // momentum kept. W_N couples both bodies (sphere-sphere contact, normal from 2 to 1).
  constexpr double m1 = 1.0, m2 = 2.0, v1 = 1.0, v2 = -0.5, e = 0.8;
  testing::ContactScene scene{std::make_unique<MultibodySystem>(Eigen::Vector3d::Zero()), Eigen::VectorXd()};
  MultibodySystem& system = *scene.system;
  for (const auto& [name, mass, radius] : {std::tuple{"a", m1, 0.1}, std::tuple{"b", m2, 0.15}}) {
    system.AddBody(std::make_unique<RigidBody>(
        name, mass, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity() * (0.4 * mass * radius * radius),
        std::vector<RigidBodyMarker>{{"centre", Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity()}}));
  }
  system.AddUnilateralContact(std::make_unique<SphereSphereUnilateral>(
      "pair", system.Marker("b", "centre"), system.Marker("a", "centre"), 0.15, 0.1, UnilateralLaw{e, 0.0}));
  scene.y0 = system.NeutralState();
  Eigen::VectorXd x(7), u = Eigen::VectorXd::Zero(6);
  x << -0.3, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0;
  u(0) = v1;
  system.SetBodyState(0, x, u, scene.y0);
  x(0) = 0.2;
  u(0) = v2;
  system.SetBodyState(1, x, u, scene.y0);
  const StepHistory history = RunMoreauJean(scene, 1e-3, 0.2);
  const Eigen::VectorXd& y = history.y.back();
  const double v1_after = (m1 * v1 + m2 * v2 - m2 * e * (v1 - v2)) / (m1 + m2);
  const double v2_after = (m1 * v1 + m2 * v2 + m1 * e * (v1 - v2)) / (m1 + m2);
  const Eigen::Index va = system.num_positions() + system.velocity_offset(0);
  const Eigen::Index vb = system.num_positions() + system.velocity_offset(1);
  EXPECT_NEAR(y(va), v1_after, 1e-13);
  EXPECT_NEAR(y(vb), v2_after, 1e-13);
  EXPECT_NEAR(m1 * y(va) + m2 * y(vb), m1 * v1 + m2 * v2, 1e-13);
  EXPECT_GT(history.steps.back().contacts[0].g_N, 0.0);  // apart again
}

/// Runs `command`, returning its standard output and exit status.
std::string RunCommand(const std::string& command, int* status) {
  std::string output;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) {
    *status = -1;
    return output;
  }
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), static_cast<int>(buffer.size()), pipe) != nullptr) output += buffer.data();
  const int raw = ::pclose(pipe);
  *status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return output;
}

TEST(MoreauJean, BouncingBallAgreesWithSiconosStepByStep) {
  constexpr double kStep = 0.005, kEndTime = 10.0, kTheta = 0.5;  // Siconos' BouncingBallTS
  const std::filesystem::path python = "/usr/bin/python3";
  const std::filesystem::path script = std::filesystem::path(FLEXMBS_SOURCE_DIR) / "tests/mbs/siconos_bouncing_ball.py";
  if (!std::filesystem::exists(python)) GTEST_SKIP() << "no " << python;
  std::ostringstream command;
  command.precision(17);
  command << python << " " << script << " " << kGap0 << " " << kRadius << " " << kMass << " " << kG << " "
          << kRestitution << " " << kStep << " " << kTheta << " " << kEndTime << " 2>/dev/null";
  int status = 0;
  const std::string output = RunCommand(command.str(), &status);
  if (status == 77) GTEST_SKIP() << "python3-siconos is not installed";
  ASSERT_EQ(status, 0) << command.str();
  std::istringstream lines(output);
  std::vector<std::array<double, 4>> siconos;  // t, q, v, p
  for (std::array<double, 4> row{}; lines >> row[0] >> row[1] >> row[2] >> row[3];) siconos.push_back(row);

  testing::ContactScene scene = BallOnFloor(kMass, kRadius, kGap0, kG, kRestitution, 0.0);
  const StepHistory history = RunMoreauJean(scene, kStep, kEndTime, kTheta);
  ASSERT_EQ(siconos.size(), history.t.size());
  double position = 0.0, velocity = 0.0, impulse = 0.0, time = 0.0;
  int active_differences = 0;
  for (std::size_t k = 0; k < siconos.size(); ++k) {
    time = std::max(time, std::abs(siconos[k][0] - history.t[k]));
    position = std::max(position, std::abs(siconos[k][1] - history.y[k](2)));
    velocity = std::max(velocity, std::abs(siconos[k][2] - history.y[k](9)));
    impulse = std::max(impulse, std::abs(siconos[k][3] - history.steps[k].contacts[0].P_N));
    active_differences += (siconos[k][3] > 0.0) != (history.steps[k].contacts[0].P_N > 0.0);
  }
  std::printf("against Siconos over %zu steps: |dt| %.3e s, |dz| %.3e m, |dv| %.3e m/s, |dP| %.3e N s, %d steps "
              "with a different contact state\n",
              siconos.size(), time, position, velocity, impulse, active_differences);
  // The same scheme on the same data: measured 1.1e-16 m, 0 m/s, 0 N s over 2000 steps and 13
  // impacts (the same index sets, the same LCPs solved by Lemke, the same sums).
  constexpr double kRoundOff = 1e-11;
  EXPECT_LT(time, 1e-12);
  EXPECT_LT(position, kRoundOff);
  EXPECT_LT(velocity, kRoundOff);
  EXPECT_LT(impulse, kRoundOff);
  EXPECT_EQ(active_differences, 0);
}

}  // namespace
}  // namespace flexmbs::mbs
