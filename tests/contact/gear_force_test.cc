// contact/gears: the mesh force of compliant teeth on rigid flanks: static deflection under a
// torque T/(r_b c' b n), the torques' ratio r_b2 / r_b1, the dashpot on the gap's rate.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "contact/gears/gear_mesh_force.h"
#include "tests/input_error.h"

namespace flexmbs::contact {
namespace {

using testing::InputErrorMessage;

constexpr double kDeg = std::numbers::pi / 180.0;

/// The pair; with `tip_corners` false the involutes touch on the line of action only (the
/// closed forms below are the line's; gear_corner_test.cc adds the corners).
GearPair Pair(double centre_distance, bool tip_corners = true) {
  GearPairSpec spec;
  spec.gear1 = SpurGearSpec{2e-3, 19, 20.0 * kDeg, 0.3, 1.0, 1.25, 0.02};
  spec.gear2 = SpurGearSpec{2e-3, 31, 20.0 * kDeg, -0.1, 1.0, 1.25, 0.025};  // b = min = 0.02 m
  spec.centre_distance = centre_distance;
  spec.tip_corners = tip_corners;
  return MakeGearPair(spec);
}

// Wheel 2 held, wheel 1 driven by T = 20 N m about +z: at equilibrium (found by bisection on the
// mesh torque alone) the teeth have deflected by delta = T / (r_b1 c' b n) along the line of
// action, n = 1 or 2 pairs in contact, and wheel 2 takes T r_b2 / r_b1.
TEST(GearMeshForce, StaticDeflectionUnderATorqueIsTorqueOverBaseRadiusTimesMeshStiffness) {
  const GearPair pair = Pair(0.0505, false);  // the line of action alone
  const GearMeshCompliance compliance;  // c' = 14 N/(mm um)
  const NormalLaw law = ToothPairLaw(compliance, pair);
  const double r_b1 = pair.gear1.base_radius, r_b2 = pair.gear2.base_radius;
  const double torque = 20.0;
  int seen[3] = {0, 0, 0};
  double worst_deflection = 0.0, worst_ratio = 0.0;
  for (int i = 0; i < 40; ++i) {
    const double phi2 = 0.3 + (2.0 * std::numbers::pi / 31) * i / 40.0;  // wheel 2 held here
    const double phi1_touch =
        0.1 + SmallestGap(MeshingToothPairs(pair, pair.centre_distance, 0.1, phi2),
                          FlankSide::kPositive) /
                  r_b1;
    const auto mesh_torque = [&](double phi1) {
      return EvaluateMesh(pair, law, pair.centre_distance, phi1, phi2, 0.0, 0.0).torque1;
    };
    double lo = phi1_touch, hi = phi1_touch + 1e-3;
    for (int k = 0; k < 200 && hi - lo > 0.0; ++k) {
      const double mid = 0.5 * (lo + hi);
      if (torque + mesh_torque(mid) > 0.0) {
        lo = mid;
      } else {
        hi = mid;
      }
    }
    const double phi1 = 0.5 * (lo + hi);
    const MeshLoads loads = EvaluateMesh(pair, law, pair.centre_distance, phi1, phi2, 0.0, 0.0);
    const int n = static_cast<int>(loads.pairs.size());
    ASSERT_TRUE(n == 1 || n == 2) << n;
    ++seen[n];
    const double expected = torque / (r_b1 * compliance.single_pair_stiffness * 0.02 * n);
    worst_deflection =
        std::max(worst_deflection, std::abs(r_b1 * (phi1 - phi1_touch) - expected) / expected);
    for (const ToothPairLoad& load : loads.pairs) {
      EXPECT_NEAR(-load.pair.gap, expected, 1e-11 * expected);
      EXPECT_NEAR(load.force, torque / (r_b1 * n), 1e-11 * torque / r_b1);
    }
    worst_ratio = std::max(worst_ratio, std::abs(loads.torque2 / loads.torque1 - r_b2 / r_b1));
  }
  std::printf(
      "[measured] static deflection against T / (r_b1 c' b n): %.3g relative; torque ratio %.3g\n",
      worst_deflection, worst_ratio);
  EXPECT_LT(worst_deflection, 1e-11);  // measured 1.0e-12 (the bisection's last interval)
  EXPECT_LT(worst_ratio, 1e-14);       // measured 8.9e-16
  EXPECT_GT(seen[1], 0);
  EXPECT_GT(seen[2], 0);
}

// The dashpot acts on the deflection's rate sigma (r_b1 omega1 + r_b2 omega2), here checked
// against the gap's central difference; a pair separating faster than k delta / c pulls nothing.
TEST(GearMeshForce, DampingActsOnTheRateOfTheGapAndNeverPulls) {
  const GearPair pair = Pair(0.0505);
  const double k = 1.4e10 * 0.02, c = 2e3;
  const NormalLaw law = ToothPairLaw({1.4e10, c}, pair);
  const double phi2 = 0.3;
  const double phi1 = 0.1 + (SmallestGap(MeshingToothPairs(pair, pair.centre_distance, 0.1, phi2),
                                         FlankSide::kPositive) +
                             5e-6) /
                                pair.gear1.base_radius;  // 5 um into the teeth
  const double omega1 = 3.0, omega2 = -1.0;
  const double dt = 1e-7;
  const auto gaps = [&](double t) {
    return MeshingToothPairs(pair, pair.centre_distance, phi1 + omega1 * t, phi2 + omega2 * t);
  };
  const MeshLoads loads = EvaluateMesh(pair, law, pair.centre_distance, phi1, phi2, omega1, omega2);
  ASSERT_FALSE(loads.pairs.empty());
  const auto gap_of = [](const std::vector<ToothPair>& pairs, const ToothPair& which) {
    for (const ToothPair& tp : pairs) {
      if (tp.side == which.side && tp.tooth1 == which.tooth1) return tp.gap;
    }
    return std::nan("");
  };
  for (const ToothPairLoad& load : loads.pairs) {
    const double rate = -(gap_of(gaps(dt), load.pair) - gap_of(gaps(-dt), load.pair)) / (2.0 * dt);
    std::printf("[measured] pair force - (k delta + c delta'): %.3g N of %.3g N\n",
                load.force - (k * 5e-6 + c * rate), load.force);
    EXPECT_NEAR(load.force, k * 5e-6 + c * rate,
                5e-7);  // measured 4.5e-8 N of 1.45e3 N (the difference's error)
  }
  // Separating at 1 m/s along the line: k delta = 1.4e3 N < c v = 2e3 N, so no force.
  const double separating = -1.0 / pair.gear1.base_radius;
  EXPECT_TRUE(
      EvaluateMesh(pair, law, pair.centre_distance, phi1, phi2, separating, 0.0).pairs.empty());
}

// Under a constant torque the static transmission error repeats with the mesh (a base pitch of
// wheel 1's turning, 2 pi / z1) and takes two levels, T / (r_b1 c' b) in single and half that in
// double contact, the double one for epsilon_alpha - 1 of the cycle (epsilon_alpha from
// the textbook's square roots, computed here).
TEST(GearMeshForce, StaticTransmissionErrorIsPeriodicWithTheSingleDoubleContactPattern) {
  const GearPair pair = Pair(0.0505, false);  // the line of action alone
  const NormalLaw law = ToothPairLaw({}, pair);
  const double r_b1 = pair.gear1.base_radius, torque = 20.0;
  const double single = torque / (r_b1 * 1.4e10 * 0.02);
  const auto root = [](const SpurGear& g) {
    return std::sqrt(std::pow(g.tip_radius, 2) - std::pow(g.base_radius, 2));
  };
  const double epsilon =
      (root(pair.gear1) + root(pair.gear2) - 0.0505 * std::sin(pair.working_pressure_angle)) /
      pair.gear1.base_pitch;
  const double period = 2.0 * std::numbers::pi / 19;
  const int per_cycle = 400, cycles = 5;
  int doubles = 0;
  double worst_level = 0.0, worst_period = 0.0;
  for (int i = 0; i < per_cycle; ++i) {
    const double phi1 = 0.1 + period * (i + 0.5) / per_cycle;
    const double ste = StaticTransmissionError(pair, law, 0.0505, phi1, torque);
    const bool is_double = std::abs(ste - single / 2.0) < std::abs(ste - single);
    doubles += is_double;
    worst_level = std::max(worst_level, std::abs(ste / (is_double ? single / 2.0 : single) - 1.0));
    for (int k = 1; k < cycles; ++k) {
      const double later = StaticTransmissionError(pair, law, 0.0505, phi1 + k * period, torque);
      worst_period = std::max(worst_period, std::abs(later - ste) / single);
    }
  }
  const double share = static_cast<double>(doubles) / per_cycle;
  std::printf(
      "[measured] STE levels %.3g, periodicity %.3g (of T/(r_b1 c' b) = %.4g m); double "
      "contact %.4f of the cycle against epsilon - 1 = %.4f\n",
      worst_level, worst_period, single, share, epsilon - 1.0);
  // Round-off of the angles (~1e-16 rad x r_b2) against delta = 4e-6 m: measured 5.3e-12, 6.3e-12.
  EXPECT_LT(worst_level, 5e-11);
  EXPECT_LT(worst_period, 6e-11);
  EXPECT_NEAR(share, epsilon - 1.0, 1.0 / per_cycle);  // measured 6e-4 at 1 / 400 = 2.5e-3
}

TEST(GearMeshForce, BadComplianceIsAOneLineError) {
  const GearPair pair = Pair(0.0);
  EXPECT_EQ(InputErrorMessage([&] {
              ToothPairLaw({0.0, 0.0}, pair);
            }),
            "mesh stiffness c' [N/m^2] 0 must be finite and > 0");
  EXPECT_EQ(InputErrorMessage([&] {
              ToothPairLaw({1.4e10, -5.0}, pair);
            }),
            "damping [N s/m] -5 must be finite and >= 0");
}

}  // namespace
}  // namespace flexmbs::contact
