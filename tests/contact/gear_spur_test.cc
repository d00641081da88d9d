// contact/gears: spur gear and pair parameters against a published worked example (KHK), SciPy's
// root of the involute equation and the textbook formulas, and their one-line input errors.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "contact/gears/spur_gear.h"
#include "tests/input_error.h"

namespace flexmbs::contact {
namespace {

using testing::InputErrorMessage;

constexpr double kDeg = std::numbers::pi / 180.0;

SpurGearSpec Wheel(double module, int teeth, double shift) {
  SpurGearSpec spec;
  spec.module = module;
  spec.teeth = teeth;
  spec.pressure_angle = 20.0 * kDeg;
  spec.profile_shift = shift;
  spec.face_width = 0.02;
  return spec;
}

GearPairSpec Pair(double module, int z1, int z2, double x1, double x2) {
  return GearPairSpec{Wheel(module, z1, x1), Wheel(module, z2, x2), 0.0, 0.0};
}

TEST(InverseInvolute, InvertsTheInvoluteToRoundOff) {
  // From 0.1 rad on (below, inv(alpha) ~ alpha^3 / 3 loses digits to cancellation in the forward
  // evaluation, not in the inverse).
  for (double alpha = 0.1; alpha < 1.5; alpha += 0.001) {
    EXPECT_NEAR(InverseInvolute(Involute(alpha)), alpha, 1e-14) << alpha;  // measured <= 1.3e-15
  }
  EXPECT_EQ(InverseInvolute(0.0), 0.0);
}

// KHK Gear Technical Reference, "Calculation of profile shifted spur gears", worked example:
// m = 3 mm, alpha = 20 deg, z = 12 / 24, x = +0.6 / +0.36 gives inv(alpha_w) = 0.034316,
// alpha_w = 26.0886 deg, a = 56.4999 mm, d = 36 / 72 mm, d_b = 33.829 / 67.658 mm,
// d_w = 37.667 / 75.333 mm, d_f = 32.100 / 66.660 mm (KHK's tip diameters differ: it shortens the
// tips).
TEST(SpurGearPair, ProfileShiftedPairMatchesTheKhkWorkedExample) {
  const GearPair pair = MakeGearPair(Pair(3e-3, 12, 24, 0.6, 0.36));
  EXPECT_NEAR(Involute(pair.working_pressure_angle), 0.034316, 0.5e-6);
  EXPECT_NEAR(pair.working_pressure_angle / kDeg, 26.0886, 0.5e-4);
  EXPECT_NEAR(pair.centre_distance * 1e3, 56.4999, 0.5e-4);
  EXPECT_DOUBLE_EQ(pair.centre_distance, pair.zero_backlash_distance);
  EXPECT_DOUBLE_EQ(2e3 * pair.gear1.pitch_radius, 36.0);
  EXPECT_DOUBLE_EQ(2e3 * pair.gear2.pitch_radius, 72.0);
  EXPECT_NEAR(2e3 * pair.gear1.base_radius, 33.829, 0.5e-3);
  EXPECT_NEAR(2e3 * pair.gear2.base_radius, 67.658, 0.5e-3);
  EXPECT_NEAR(2e3 * pair.gear1.base_radius / std::cos(pair.working_pressure_angle), 37.667, 0.5e-3);
  EXPECT_NEAR(2e3 * pair.gear2.base_radius / std::cos(pair.working_pressure_angle), 75.333, 0.5e-3);
  EXPECT_NEAR(2e3 * pair.gear1.root_radius, 32.100, 1e-12);
  EXPECT_NEAR(2e3 * pair.gear2.root_radius, 66.660, 1e-12);
  EXPECT_NEAR(pair.backlash, 0.0, 1e-17);  // measured 3.5e-18 m
}

// SciPy 1.10.1, scipy.optimize.brentq on tan(t) - t = inv(20 deg) + 2 tan(20 deg) (0.3 - 0.1) / 50
// (xtol 1e-16): alpha_w0 = 0.36968718266775086 rad, a_0 = 0.050388882821418846 m for m = 2 mm,
// z = 19 / 31. The contact ratio from the textbook's square roots,
// (sqrt(r_a1^2 - r_b1^2) + sqrt(r_a2^2 - r_b2^2) - a sin(alpha_w)) / (pi m cos(alpha)), computed
// here.
TEST(SpurGearPair, WorkingPressureAngleAndContactRatioAgreeWithSciPyAndTheTextbook) {
  const GearPair pair = MakeGearPair(Pair(2e-3, 19, 31, 0.3, -0.1));
  EXPECT_NEAR(pair.working_pressure_angle, 0.36968718266775086, 2e-15);   // measured 5.6e-17
  EXPECT_NEAR(pair.zero_backlash_distance, 0.050388882821418846, 1e-16);  // measured 0
  const auto root = [](const SpurGear& g) {
    return std::sqrt(std::pow(g.tip_radius, 2) - std::pow(g.base_radius, 2));
  };
  const double a = pair.centre_distance;
  const double alpha = 20.0 * kDeg;
  const double epsilon =
      (root(pair.gear1) + root(pair.gear2) - a * std::sin(pair.working_pressure_angle)) /
      (std::numbers::pi * 2e-3 * std::cos(alpha));
  EXPECT_NEAR(pair.contact_ratio, epsilon, 1e-13);             // measured 2.2e-16
  EXPECT_NEAR(pair.contact_ratio, 1.5285818014065653, 1e-13);  // SciPy script's value
  EXPECT_NEAR(pair.path_end - pair.path_start, pair.contact_ratio * pair.gear1.base_pitch, 1e-17);
}

TEST(SpurGearPair, StandardPairMeshesAtTheSumOfPitchRadiiWithThePressureAngle) {
  const GearPair pair = MakeGearPair(Pair(2e-3, 20, 40, 0.0, 0.0));
  EXPECT_NEAR(pair.centre_distance, 0.06, 1e-17);
  EXPECT_NEAR(pair.working_pressure_angle, 20.0 * kDeg, 1e-15);  // measured 5.6e-17
  EXPECT_NEAR(pair.gear1.base_pitch, std::numbers::pi * 2e-3 * std::cos(20.0 * kDeg), 1e-18);
  EXPECT_NEAR(pair.gear1.tip_radius, 0.022, 1e-18);
  EXPECT_NEAR(pair.gear2.root_radius, 0.04 - 2.5e-3, 1e-18);
  EXPECT_NEAR(pair.contact_ratio, 1.635185963571462,
              1e-13);  // the textbook square-root formula, SciPy script
}

// Backlash from a larger centre distance: j_bn = 2 (r_b1 + r_b2) (inv(alpha_w) - inv(alpha_w0)),
// evaluated here with SciPy's alpha_w0; an allowance j adds to it; j_wt = j_bn / cos(alpha_w).
TEST(SpurGearPair, BacklashGrowsWithTheCentreDistanceAndTheAllowance) {
  GearPairSpec spec = Pair(2e-3, 19, 31, 0.3, -0.1);
  spec.centre_distance = 0.0505;
  const GearPair wide = MakeGearPair(spec);
  const double r_b = wide.gear1.base_radius + wide.gear2.base_radius;
  const double alpha_w = std::acos(r_b / 0.0505);
  const double expected = 2.0 * r_b * (Involute(alpha_w) - Involute(0.36968718266775086));
  EXPECT_NEAR(wide.backlash, expected, 1e-17);  // measured 3.4e-19 m of 8.1e-5 m
  EXPECT_NEAR(wide.circumferential_backlash, expected / std::cos(alpha_w), 1e-17);
  // The textbook's j_bn ~ 2 (a - a_0) sin(alpha_w) is its first order in a - a_0 = 1.1e-4 m.
  EXPECT_NEAR(wide.backlash, 2.0 * (0.0505 - 0.050388882821418846) * std::sin(alpha_w),
              1e-2 * expected);  // measured 7.2e-3 of it
  spec.backlash = 5e-5;
  EXPECT_NEAR(MakeGearPair(spec).backlash, expected + 5e-5, 1e-17);
}

TEST(SpurGearPair, ShiftedWheelOfFewTeethAvoidsUndercut) {
  // z_min = 2 / sin^2(20 deg) = 17.1 unshifted; 12 teeth need x >= 1 - 6 sin^2(20 deg) = 0.298.
  EXPECT_EQ(InputErrorMessage([] { MakeSpurGear(Wheel(2e-3, 12, 0.0), "gear 1"); }),
            "gear 1: teeth 12 < z_min = 2 (h_a* - x) / sin^2(alpha) = 17.1 undercut the flank "
            "(a profile shift x >= 0.2981 avoids it)");
  EXPECT_NO_THROW(MakeSpurGear(Wheel(2e-3, 12, 0.3), "gear 1"));
  EXPECT_NO_THROW(MakeSpurGear(Wheel(2e-3, 18, 0.0), "gear 1"));
}

TEST(SpurGearInput, BadWheelsAreOneLineErrorsNamingTheParameter) {
  SpurGearSpec spec = Wheel(2e-3, 20, 0.0);
  spec.face_width = 0.0;
  EXPECT_EQ(InputErrorMessage([&] { MakeSpurGear(spec, "gear 2"); }),
            "gear 2: face width [m] 0 must be finite and > 0");
  spec = Wheel(-1e-3, 20, 0.0);
  EXPECT_EQ(InputErrorMessage([&] { MakeSpurGear(spec, "gear 1"); }),
            "gear 1: module [m] -0.001 must be finite and > 0");
  spec = Wheel(2e-3, 2, 0.0);
  EXPECT_EQ(InputErrorMessage([&] { MakeSpurGear(spec, "gear 1"); }),
            "gear 1: teeth 2 must be >= 3");
  spec = Wheel(2e-3, 20, 0.0);
  spec.pressure_angle = 0.0;
  EXPECT_EQ(InputErrorMessage([&] { MakeSpurGear(spec, "gear 1"); }),
            "gear 1: pressure angle 0 rad must be in (0, pi/4]");
  spec = Wheel(2e-3, 20, 1.5);
  EXPECT_EQ(InputErrorMessage([&] { MakeSpurGear(spec, "gear 1"); }),
            "gear 1: tip thickness -0.0004544 m must be > 0 (pointed teeth: lower the profile "
            "shift 1.5 or the "
            "addendum coefficient 1)");
  spec = Wheel(2e-3, 20, 0.0);
  spec.tip_relief = -1e-5;
  EXPECT_EQ(InputErrorMessage([&] { MakeSpurGear(spec, "gear 1"); }),
            "gear 1: tip relief C_a [m] -1e-05 must be finite and >= 0");
  spec.tip_relief = 1e-5;
  EXPECT_EQ(InputErrorMessage([&] { MakeSpurGear(spec, "gear 1"); }),
            "gear 1: tip relief length L_Ca [m] 0 must be finite and > 0");
  spec.tip_relief_length = 1e-3;
  spec.tip_relief_exponent = 3;
  EXPECT_EQ(InputErrorMessage([&] { MakeSpurGear(spec, "gear 1"); }),
            "gear 1: tip relief exponent 3 must be 1 (linear) or 2 (parabolic)");
  spec.tip_relief_exponent = 2;
  spec.tip_relief_length = 0.02;  // r_b tan(alpha_a) = 9.5 mm for m 2 mm, z 20
  const std::string message = InputErrorMessage([&] { MakeSpurGear(spec, "gear 1"); });
  EXPECT_NE(message.find("gear 1: tip relief length L_Ca 0.02 m must be < r_b tan(alpha_a) = "),
            std::string::npos)
      << message;
}

TEST(SpurGearInput, PairsThatCannotMeshAreOneLineErrors) {
  GearPairSpec spec = Pair(2e-3, 19, 31, 0.0, 0.0);
  spec.gear2.module = 2.5e-3;
  EXPECT_EQ(InputErrorMessage([&] { MakeGearPair(spec); }),
            "gears cannot mesh: module 0.002 m of gear 1 differs from 0.0025 m of gear 2");
  spec = Pair(2e-3, 19, 31, 0.0, 0.0);
  spec.gear2.pressure_angle = 25.0 * kDeg;
  EXPECT_EQ(InputErrorMessage([&] { MakeGearPair(spec); }),
            "gears cannot mesh: pressure angle 0.3490658503988659 rad of gear 1 differs from "
            "0.4363323129985824 rad of gear 2");
  spec = Pair(2e-3, 19, 31, 0.0, 0.0);
  spec.backlash = -1e-5;
  EXPECT_EQ(InputErrorMessage([&] { MakeGearPair(spec); }),
            "backlash [m] -1e-05 must be finite and >= 0");
  spec.backlash = 0.0;
  spec.centre_distance = 0.0499;
  EXPECT_EQ(
      InputErrorMessage([&] { MakeGearPair(spec); }),
      "centre distance 0.0499 m < a_0 = 0.05 m (zero backlash): the teeth would interpenetrate");
  spec.centre_distance = 0.0525;
  EXPECT_EQ(InputErrorMessage([&] { MakeGearPair(spec); }),
            "centre distance 0.0525 m is too large: contact ratio 0.5313 < 1, the teeth lose mesh "
            "(a_0 = 0.05 m)");
  spec = Pair(2e-3, 19, 31, 0.0, 0.0);
  spec.gear2.addendum_coefficient =
      1.6;  // the tip of gear 2 reaches past gear 1's base tangent point
  EXPECT_NE(InputErrorMessage([&] {
              MakeGearPair(spec);
            }).find("the tip of gear 2 meets gear 1 below its base circle"),
            std::string::npos);
  spec = Pair(2e-3, 19, 31, 0.0, 0.0);
  spec.backlash = 3e-3;  // 1.5 mm off each tooth, ~1.3 mm thick at the tip
  EXPECT_EQ(InputErrorMessage([&] { MakeGearPair(spec); }),
            "backlash 0.003 m thins the teeth of gear 1 to a tip thickness of -0.0003872 m (must "
            "stay > 0)");
  spec = Pair(2e-3, 60, 61, 0.0, 0.0);
  spec.gear1.addendum_coefficient = 1.3;  // deeper than the other wheel's dedendum 1.25
  EXPECT_NE(InputErrorMessage([&] {
              MakeGearPair(spec);
            }).find("a tip reaches the other wheel's root circle"),
            std::string::npos);
}

}  // namespace
}  // namespace flexmbs::contact
