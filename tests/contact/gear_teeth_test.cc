// contact/gears elastic teeth on plain data: the rack-cut outline meets the involute, Weber's
// flattening against the integrated Hertzian stress field (SciPy), ISO 6336-1's c' for the basic
// rack, the compliance table's interpolation, and the refused outlines.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "contact/gears/tooth_profile.h"
#include "contact/gears/tooth_stiffness.h"
#include "tests/input_error.h"

namespace flexmbs::contact {
namespace {

using testing::InputErrorMessage;

constexpr double kDeg = std::numbers::pi / 180.0;

SpurGearSpec Wheel(int teeth, double shift) {
  return SpurGearSpec{4e-3, teeth, 20.0 * kDeg, shift, 1.0, 1.25, 0.04};
}

// The fillet is the envelope of the rack's tip rounding and the involute that of its straight
// flank, derived apart (tooth_profile.cc, gear_flank.cc): where the straight flank ends, the
// envelope's last point must lie on the involute at the form circle, and its first on the root
// circle.
TEST(ToothProfile, RackFilletEndsOnTheInvoluteAndStartsOnTheRootCircle) {
  double worst_form = 0.0, worst_root = 0.0;
  for (const int teeth : {18, 20, 31, 60}) {
    for (const double shift : {-0.2, 0.0, 0.5}) {
      if (teeth < 31 && shift < 0.0) continue;  // undercut
      const SpurGear gear = MakeSpurGear(Wheel(teeth, shift), "gear");
      const ToothFlankProfile profile = RightFlankProfile(gear, kBasicRackTipRadius, 16);
      worst_form = std::max(
          worst_form, (profile.fillet.back() - ToothFlankPoint(gear, profile.form_roll)).norm());
      worst_root = std::max(worst_root, std::abs(profile.fillet.front().norm() - gear.root_radius));
      EXPECT_GT(profile.fillet.front().x(), 0.0);
      EXPECT_LT(profile.form_roll, gear.tip_roll);
    }
  }
  std::printf("[measured] form point off the involute %.2g m, root point off r_f %.2g m (m 4 mm)\n",
              worst_form, worst_root);
  EXPECT_LT(worst_form, 3e-16);  // measured 2.6e-17 m
  EXPECT_LT(worst_root, 2e-16);  // measured 1.4e-17 m
}

TEST(ToothProfile, RefusesARoundingThatUndercutsOrDoesNotFit) {
  SpurGearSpec deep = Wheel(18, 0.0);
  deep.dedendum_coefficient = 1.4;
  const SpurGear gear = MakeSpurGear(deep, "gear");
  const std::string undercut = InputErrorMessage([&] { RightFlankProfile(gear, 0.1, 16); });
  EXPECT_NE(undercut.find("teeth 18, profile shift 0: the generating rack's rounding"),
            std::string::npos)
      << undercut;
  EXPECT_NE(undercut.find("undercut"), std::string::npos) << undercut;
  const SpurGear standard = MakeSpurGear(Wheel(30, 0.0), "gear");
  const std::string wide = InputErrorMessage([&] { RightFlankProfile(standard, 0.9, 16); });
  EXPECT_NE(wide.find("rack tip radius 0.0036 m does not fit"), std::string::npos) << wide;
  const std::string negative = InputErrorMessage([&] { RightFlankProfile(standard, -0.1, 16); });
  EXPECT_NE(negative.find("rack tip radius coefficient -0.1"), std::string::npos) << negative;
}

// tests/contact/weber_flattening_reference.py: the same two teeth's approach integrated from the
// plane-strain stress field under the Hertzian pressure (SciPy 1.10 quad). Weber's closed form is
// its asymptote for h >> a (here h / a ~ 20).
TEST(WeberFlattening, MatchesTheIntegratedHertzianStressField) {
  constexpr double kSciPy = 6.006225199568774e-06;
  const double delta = WeberFlattening(3e5, 10e-3, 20e-3, 3e-3, 4e-3, ToothMaterial{});
  std::printf("[measured] Weber %.10g m, SciPy %.10g m, relative %.2g\n", delta, kSciPy,
              delta / kSciPy - 1.0);
  EXPECT_NEAR(delta / kSciPy, 1.0, 1e-3);  // measured -1.6e-4 (the (a / h)^2 terms)
}

// ISO 6336-1:2019 sec. 9.3 gives c' ~ 14 N/(mm um) for steel pairs of the basic rack; method B's
// c' = c'_th C_M C_B over the usual tooth numbers lies around it (a check of the table's
// coefficients as typed: a wrong digit in C1 ... C3 moves it out).
TEST(IsoMeshStiffness, BasicRackPairsLieAroundFourteen) {
  double lo = 1e30, hi = 0.0;
  for (const int z1 : {18, 25, 40, 80}) {
    for (const int z2 : {18, 25, 40, 80, 200}) {
      const IsoMeshStiffness iso = IsoSinglePairStiffness(Wheel(z1, 0.0), Wheel(z2, 0.0));
      EXPECT_NEAR(iso.c_b, 0.975, 1e-15);  // h_fP / m = 1.25, alpha = 20 deg
      lo = std::min(lo, iso.single_pair / 1e9);
      hi = std::max(hi, iso.single_pair / 1e9);
    }
  }
  std::printf("[measured] ISO c' of basic-rack pairs z 18...200: %.4g ... %.4g N/(mm um)\n", lo,
              hi);
  EXPECT_GT(lo, 10.5);  // measured 11.11 (z 18/18)
  EXPECT_LT(hi, 16.0);  // measured 15.46
}

TEST(ToothCompliance, InterpolatesLinearlyAndHoldsTheEnds) {
  const ToothCompliance tooth{{0.1, 0.3, 0.6}, {1.0, 2.0, 5.0}, {4.0, 3.0, 1.0}};
  EXPECT_DOUBLE_EQ(InterpolateCompliance(tooth, 0.2).compliance, 1.5);
  EXPECT_DOUBLE_EQ(InterpolateCompliance(tooth, 0.5).centre_depth, 3.0 - 2.0 * 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(InterpolateCompliance(tooth, 0.0).compliance, 1.0);
  EXPECT_DOUBLE_EQ(InterpolateCompliance(tooth, 0.9).compliance, 5.0);
  EXPECT_DOUBLE_EQ(InterpolateCompliance(tooth, 0.6).centre_depth, 1.0);
}

}  // namespace
}  // namespace flexmbs::contact
