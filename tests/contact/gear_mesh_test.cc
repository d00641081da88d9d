// contact/gears: the contact search of a rigid spur pair against the explicit involutes of its
// teeth (points, normals, the flanks' distance found by brute force), the exact transmission
// ratio, the backlash angle and the contact ratio.
#include "contact/gears/gear_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace flexmbs::contact {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

GearPair ShiftedPair(double centre_distance, double allowance) {
  GearPairSpec spec;
  spec.gear1 = SpurGearSpec{2e-3, 19, 20.0 * kDeg, 0.3, 1.0, 1.25, 0.02};
  spec.gear2 = SpurGearSpec{2e-3, 31, 20.0 * kDeg, -0.1, 1.0, 1.25, 0.02};
  spec.centre_distance = centre_distance;
  spec.backlash = allowance;
  return MakeGearPair(spec);
}

/// Wheel 2's flank point in the pair frame (its centre at (a, 0)).
Eigen::Vector2d Wheel2Point(const GearPair& pair, const ToothPair& tp, double phi2) {
  return Eigen::Vector2d(pair.centre_distance, 0.0) +
         FlankPoint(pair.gear2, tp.tooth2, tp.side, tp.roll2, phi2);
}

TEST(GearMesh, FoundPointsLieOnBothTeethsInvolutesWithTheLineOfActionAsTheirNormal) {
  const GearPair pair = ShiftedPair(0.0505, 2e-5);
  int pairs_seen = 0, corners_seen = 0;
  for (double phi1 = -0.3; phi1 < 0.3; phi1 += 0.0137) {
    const double phi2 = 0.71 - 0.5 * phi1;  // any angles: gaps of either sign
    for (const ToothPair& tp : MeshingToothPairs(pair, pair.centre_distance, phi1, phi2)) {
      const Eigen::Vector2d p1 = FlankPoint(pair.gear1, tp.tooth1, tp.side, tp.roll1, phi1);
      const Eigen::Vector2d p2 = Wheel2Point(pair, tp, phi2);
      // The two flank points (or a tip corner and its foot on the other flank) sit on the normal
      // through the contact point, g apart.
      EXPECT_LT((p2 - p1 - tp.gap * tp.n_12).norm(), 2e-16);  // measured 2.1e-17 m
      EXPECT_LT((0.5 * (p1 + p2) - tp.p_O1C).norm(), 2e-16);
      // A corner's normal is the flank's it faces (wheel 1's outward, wheel 2's inward).
      if (tp.contact == ToothContact::kTip2OnFlank1) {
        ++corners_seen;
        EXPECT_EQ(tp.roll2, pair.gear2.tip_roll);
        EXPECT_LT((FlankNormal(pair.gear1, tp.tooth1, tp.side, tp.roll1, phi1) - tp.n_12).norm(),
                  1e-14);
      }
      if (tp.contact == ToothContact::kTip1OnFlank2) {
        ++corners_seen;
        EXPECT_EQ(tp.roll1, pair.gear1.tip_roll);
        EXPECT_LT((FlankNormal(pair.gear2, tp.tooth2, tp.side, tp.roll2, phi2) + tp.n_12).norm(),
                  1e-14);
      }
      if (tp.contact != ToothContact::kFlanks) continue;
      ++pairs_seen;
      // Each flank's outward normal is the line: wheel 1's along n_12, wheel 2's against it.
      EXPECT_LT((FlankNormal(pair.gear1, tp.tooth1, tp.side, tp.roll1, phi1) - tp.n_12).norm(),
                1e-14);  // measured 1.1e-15
      EXPECT_LT((FlankNormal(pair.gear2, tp.tooth2, tp.side, tp.roll2, phi2) + tp.n_12).norm(),
                1e-14);  // measured 1.1e-15
      // The line of action is tangent to both base circles.
      const Eigen::Vector2d t(-tp.n_12.y(), tp.n_12.x());
      EXPECT_NEAR(std::abs(t.dot(tp.p_O1C)), pair.gear1.base_radius, 2e-16);
      EXPECT_NEAR(std::abs(t.dot(tp.p_O1C - Eigen::Vector2d(pair.centre_distance, 0.0))),
                  pair.gear2.base_radius, 2e-16);
    }
  }
  EXPECT_GT(pairs_seen, 100);
  EXPECT_GT(corners_seen, 50);
}

/// The least distance [m] between wheel 1's and wheel 2's flank curves of `tp`, by brute force:
/// a grid over both roll ranges, then nested golden-section searches (for each t1 the nearest
/// point of wheel 2's flank) around the grid's best.
double FlankDistance(const GearPair& pair, const ToothPair& tp, double phi1, double phi2) {
  const auto p1 = [&](double t) { return FlankPoint(pair.gear1, tp.tooth1, tp.side, t, phi1); };
  const auto p2 = [&](double t) {
    return Eigen::Vector2d(Eigen::Vector2d(pair.centre_distance, 0.0) +
                           FlankPoint(pair.gear2, tp.tooth2, tp.side, t, phi2));
  };
  double best = 1e9, t1 = 0.0, t2 = 0.0;
  const int n = 300;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      const double a = pair.gear1.tip_roll * i / n, b = pair.gear2.tip_roll * j / n;
      const double d = (p1(a) - p2(b)).norm();
      if (d < best) best = d, t1 = a, t2 = b;
    }
  }
  const auto golden = [](auto f, double lo, double hi) {
    const double r = (std::sqrt(5.0) - 1.0) / 2.0;
    for (int k = 0; k < 100; ++k) {
      const double x1 = hi - r * (hi - lo), x2 = lo + r * (hi - lo);
      if (f(x1) < f(x2)) {
        hi = x2;
      } else {
        lo = x1;
      }
    }
    return 0.5 * (lo + hi);
  };
  const double w1 = 2.0 * pair.gear1.tip_roll / n, w2 = 2.0 * pair.gear2.tip_roll / n;
  const auto nearest = [&](double a) {
    const double b = golden([&](double t) { return (p1(a) - p2(t)).norm(); }, t2 - w2, t2 + w2);
    return (p1(a) - p2(b)).norm();
  };
  return nearest(golden(nearest, t1 - w1, t1 + w1));
}

TEST(GearMesh, PositiveGapIsTheLeastDistanceOfTheTwoFlanksFoundByBruteForce) {
  const GearPair pair = ShiftedPair(0.0505, 2e-5);
  const double phi1 = 0.05;
  const double phi2 = TouchingAngle2(pair, pair.centre_distance, phi1, 0.0, FlankSide::kPositive);
  int checked = 0;
  for (const ToothPair& tp : MeshingToothPairs(pair, pair.centre_distance, phi1, phi2)) {
    // The flanks on the backlash side (g = j_bn = 1.01e-4 m); a corner's gap is along the other
    // flank's normal, not the two curves' least distance (gear_corner_test.cc).
    if (tp.side != FlankSide::kNegative || tp.contact != ToothContact::kFlanks) continue;
    const double distance = FlankDistance(pair, tp, phi1, phi2);
    std::printf("[measured] brute-force flank distance - gap: %.3g m of %.3g m\n",
                distance - tp.gap, tp.gap);
    EXPECT_NEAR(distance, tp.gap, 1e-16);  // measured 9.6e-18 m of 1.0e-4 m
    ++checked;
  }
  EXPECT_GE(checked, 1);
}

// Turning wheel 1 through three mesh cycles with wheel 2 at the touching angle keeps
// phi2 = phi2_0 - (z1 / z2) (phi1 - phi1_0), across every change of the tooth pairs in contact.
TEST(GearMesh, RigidPairWithoutLoadKeepsTheExactRatio) {
  for (const FlankSide side : {FlankSide::kPositive, FlankSide::kNegative}) {
    const GearPair pair = ShiftedPair(0.0, 0.0);
    const double phi1_0 = 0.2;
    const double phi2_0 = TouchingAngle2(pair, pair.centre_distance, phi1_0, 0.0, side);
    double phi2 = phi2_0, worst = 0.0, nearest_corner = 1.0;
    const int steps = 3000;
    for (int i = 1; i <= steps; ++i) {
      const double phi1 = phi1_0 + 3.0 * (2.0 * std::numbers::pi / 19) * i / steps;
      phi2 = TouchingAngle2(pair, pair.centre_distance, phi1, phi2, side);
      worst = std::max(worst, std::abs(phi2 - phi2_0 + 19.0 / 31.0 * (phi1 - phi1_0)));
      // No backlash at a_0: the other side touches too (to round-off), nothing penetrates; the
      // tip corners off the line stand off the mating flanks.
      for (const ToothPair& tp : MeshingToothPairs(pair, pair.centre_distance, phi1, phi2)) {
        if (tp.contact == ToothContact::kFlanks) {
          EXPECT_NEAR(tp.gap, 0.0, 2e-16);  // measured 2.6e-17 m
        } else {
          EXPECT_GT(tp.gap, 0.0);
          nearest_corner = std::min(nearest_corner, tp.gap);
        }
      }
    }
    std::printf(
        "[measured] phi2 + (z1/z2) phi1 drift over 3 mesh cycles: %.3g rad; nearest corner %.3g "
        "m\n",
        worst, nearest_corner);
    EXPECT_LT(worst, 7e-15);  // measured 6.7e-16 rad
  }
}

// With wheel 2 held, wheel 1 turns from touching on one side to touching on the other through
// j_bn / r_b1: the backlash along the line of action, j_bn = 2 (r_b1 + r_b2) (inv(alpha_w) -
// inv(alpha_w0)) + j, evaluated here from the involute function (alpha_w0 from SciPy, spur test).
TEST(GearMesh, DriverHeldWheelTurnsExactlyTheBacklashAngleBeforeContact) {
  const double allowance = 2e-5;
  const GearPair pair = ShiftedPair(0.0505, allowance);
  const double r_b = pair.gear1.base_radius + pair.gear2.base_radius;
  const double j_bn =
      2.0 * r_b * (Involute(std::acos(r_b / 0.0505)) - Involute(0.36968718266775086)) + allowance;
  const double phi2 = 0.3;  // held
  const double phi1_start = 0.1;
  // Wheel 1's own touching angles on each side from the gaps (dg/dphi1 = -sigma r_b1).
  const auto pairs = MeshingToothPairs(pair, pair.centre_distance, phi1_start, phi2);
  const double forward =
      phi1_start + SmallestGap(pairs, FlankSide::kPositive) / pair.gear1.base_radius;
  const double reverse =
      phi1_start - SmallestGap(pairs, FlankSide::kNegative) / pair.gear1.base_radius;
  std::printf("[measured] backlash angle - j_bn / r_b1: %.3g rad of %.3g rad\n",
              forward - reverse - j_bn / pair.gear1.base_radius, j_bn / pair.gear1.base_radius);
  EXPECT_NEAR(forward - reverse, j_bn / pair.gear1.base_radius,
              5e-15);  // measured 5.2e-16 rad of 5.65e-3
  // Between them no tooth touches; at either end one side does.
  const int steps = 500;
  for (int i = 1; i < steps; ++i) {
    const double phi1 = reverse + (forward - reverse) * i / steps;
    for (const ToothPair& tp : MeshingToothPairs(pair, pair.centre_distance, phi1, phi2))
      EXPECT_GT(tp.gap, 0.0);
  }
  EXPECT_NEAR(SmallestGap(MeshingToothPairs(pair, pair.centre_distance, forward, phi2),
                          FlankSide::kPositive),
              0.0, 2e-17);  // measured 1.7e-18 m
  EXPECT_NEAR(SmallestGap(MeshingToothPairs(pair, pair.centre_distance, reverse, phi2),
                          FlankSide::kNegative),
              0.0, 2e-17);
}

// Counting the pairs in contact over 20 mesh cycles: 1 or 2, and the share of double contact is
// epsilon_alpha - 1, epsilon_alpha from the textbook's square roots computed here.
TEST(GearMesh, PairsInContactSwitchBetweenOneAndTwoAsTheContactRatioSays) {
  const GearPair pair = ShiftedPair(0.0505, 0.0);
  const auto root = [](const SpurGear& g) {
    return std::sqrt(std::pow(g.tip_radius, 2) - std::pow(g.base_radius, 2));
  };
  const double epsilon =
      (root(pair.gear1) + root(pair.gear2) - 0.0505 * std::sin(pair.working_pressure_angle)) /
      (std::numbers::pi * 2e-3 * std::cos(20.0 * kDeg));
  const int cycles = 20, per_cycle = 5000;
  int double_contact = 0;
  double phi2 = 0.0;
  for (int i = 0; i < cycles * per_cycle; ++i) {
    const double phi1 = (2.0 * std::numbers::pi / 19) * (i + 0.5) / per_cycle;
    phi2 = TouchingAngle2(pair, pair.centre_distance, phi1, phi2, FlankSide::kPositive);
    int touching = 0;
    for (const ToothPair& tp : MeshingToothPairs(pair, pair.centre_distance, phi1, phi2)) {
      if (tp.side == FlankSide::kPositive && tp.gap <= 1e-15) ++touching;
    }
    ASSERT_TRUE(touching == 1 || touching == 2) << touching << " at phi1 = " << phi1;
    double_contact += touching == 2;
  }
  const double measured = 1.0 + static_cast<double>(double_contact) / (cycles * per_cycle);
  std::printf("[measured] contact ratio counted %.6f, formula %.6f\n", measured, epsilon);
  EXPECT_NEAR(measured, epsilon, 2.0 / per_cycle);  // the sampling's resolution; measured 7.2e-5
}

// Tip relief C_a over L_Ca along the line of action (wheel 2 linear, wheel 1 parabolic), pair
// turned without load: an entering pair's gap is wheel 2's relief, C_a2 ((s_A + L_Ca2 - s) /
// L_Ca2)^1 at its place s on the line (the other pair touches, off any relief), so contact starts
// L_Ca2 later than at the path's start s_A = T1T2 - sqrt(r_a2^2 - r_b2^2), and ends L_Ca1 before
// its end s_E = sqrt(r_a1^2 - r_b1^2); double contact shrinks to epsilon_alpha - 1 - (L_Ca1 +
// L_Ca2) / p_b of the cycle (ISO 21771's radii from m, z, x; no flexmbs geometry).
TEST(GearMesh, TipReliefDelaysContactByItsLengthAlongTheLine) {
  constexpr double kCa1 = 15e-6, kLength1 = 0.8e-3, kCa2 = 20e-6, kLength2 = 1.0e-3;
  GearPairSpec spec;
  spec.gear1 = SpurGearSpec{2e-3, 19, 20.0 * kDeg, 0.3, 1.0, 1.25, 0.02, kCa1, kLength1, 2};
  spec.gear2 = SpurGearSpec{2e-3, 31, 20.0 * kDeg, -0.1, 1.0, 1.25, 0.02, kCa2, kLength2, 1};
  spec.centre_distance = 0.0505;
  const GearPair pair = MakeGearPair(spec);
  const double r_b1 = 19e-3 * std::cos(20.0 * kDeg), r_b2 = 31e-3 * std::cos(20.0 * kDeg);
  const double r_a1 = 19e-3 + 2e-3 * 1.3, r_a2 = 31e-3 + 2e-3 * 0.9;
  const double line = 0.0505 * std::sin(std::acos((r_b1 + r_b2) / 0.0505));
  const double s_A = line - std::sqrt(r_a2 * r_a2 - r_b2 * r_b2);
  const double s_E = std::sqrt(r_a1 * r_a1 - r_b1 * r_b1);
  const double p_b = std::numbers::pi * 2e-3 * std::cos(20.0 * kDeg);
  const int cycles = 4, per_cycle = 20000;
  int double_contact = 0;
  double phi2 = 0.0, first = 1.0, last = 0.0, worst_relief = 0.0;
  for (int i = 0; i < cycles * per_cycle; ++i) {
    const double phi1 = (2.0 * std::numbers::pi / 19) * (i + 0.5) / per_cycle;
    phi2 = TouchingAngle2(pair, pair.centre_distance, phi1, phi2, FlankSide::kPositive);
    int touching = 0;
    for (const ToothPair& tp : MeshingToothPairs(pair, pair.centre_distance, phi1, phi2)) {
      if (tp.side != FlankSide::kPositive) continue;
      if (tp.contact != ToothContact::kFlanks) {  // no load: a relieved corner stands off
        EXPECT_GT(tp.gap, 0.0);
        continue;
      }
      const double s = r_b1 * tp.roll1;
      if (tp.gap <= 1e-15) {
        ++touching;
        first = std::min(first, s);
        last = std::max(last, s);
      } else if (s < s_A + kLength2) {
        worst_relief = std::max(worst_relief,
                                std::abs(tp.gap - kCa2 * (s_A + kLength2 - s) / kLength2));
      }
    }
    ASSERT_TRUE(touching == 1 || touching == 2) << touching << " at phi1 = " << phi1;
    double_contact += touching == 2;
  }
  const double share = static_cast<double>(double_contact) / (cycles * per_cycle);
  const double expected = pair.contact_ratio - 1.0 - (kLength1 + kLength2) / p_b;
  const double step = r_b1 * 2.0 * std::numbers::pi / 19 / per_cycle;  // s between samples
  std::printf(
      "[measured] tip relief: contact from %.7g (s_A + L_Ca2 = %.7g) to %.7g (s_E - L_Ca1 = "
      "%.7g) m; entering gap against the relief %.3g m; double contact %.6f against %.6f\n",
      first, s_A + kLength2, last, s_E - kLength1, worst_relief, share, expected);
  // Within the sampling's resolution (step 2.95e-7 m): measured 1.2e-7 and 2.3e-7 m.
  EXPECT_NEAR(first, s_A + kLength2, 1.5 * step);
  EXPECT_NEAR(last, s_E - kLength1, 1.5 * step);
  EXPECT_LT(worst_relief, 2e-16);  // measured 1.6e-17 m
  EXPECT_NEAR(share, expected, 2.0 / per_cycle);  // measured 8e-6
}

}  // namespace
}  // namespace flexmbs::contact
