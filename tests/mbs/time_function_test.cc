// Time functions: derivatives against finite differences, known values, SciPy's natural spline.
#include "mbs/time_function.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "tests/input_error.h"

namespace flexmbs::mbs {
namespace {

// Central differences with step 1e-5 of functions with derivatives up to ~100: truncation
// ~ 1e-10 x 1e3, round-off ~ 1e-16 / 1e-5.
constexpr double kStep = 1e-5;
constexpr double kDifferenceTolerance = 1e-6;
// Values of a few flops.
constexpr double kRoundOff = 1e-13;

// f' and f'' agree with central differences of f and f' at t.
void ExpectConsistentDerivatives(const TimeFunction& f, double t) {
  const TimeFunctionValue plus = f.Evaluate(t + kStep), minus = f.Evaluate(t - kStep), at = f.Evaluate(t);
  EXPECT_NEAR(at.first_derivative, (plus.value - minus.value) / (2 * kStep), kDifferenceTolerance) << "t = " << t;
  EXPECT_NEAR(at.second_derivative, (plus.first_derivative - minus.first_derivative) / (2 * kStep), kDifferenceTolerance)
      << "t = " << t;
}

TEST(TimeFunction, DerivativesAreThoseOfTheValue) {
  const std::vector<TimeFunctionPtr> functions = {
      MakeConstant(2.5),
      MakeRamp(1.0, -3.0),
      MakePolynomial({1.0, -2.0, 0.5, 0.25}, 0.3),
      MakeHarmonic(0.7, 4.0, 0.3, -1.0),
      MakeSmoothStep(0.2, 1.0, 1.4, -2.0, SmoothStepOrder::kCubic),
      MakeSmoothStep(0.2, 1.0, 1.4, -2.0, SmoothStepOrder::kQuintic),
      MakeCubicSpline({0.0, 0.5, 1.2, 2.0, 3.0}, {0.0, 1.0, -0.5, 2.0, 1.5}),
      MakeSpinUp(3.0, 1.2, 0.4),
  };
  for (const auto& f : functions) {
    for (const double t : {-0.7, 0.05, 0.45, 0.93, 1.31, 2.5, 3.6}) ExpectConsistentDerivatives(*f, t);
  }
}

TEST(TimeFunction, KnownValues) {
  EXPECT_EQ(MakeConstant(2.5)->Evaluate(7.0).value, 2.5);
  const TimeFunctionValue ramp = MakeRamp(1.0, -3.0)->Evaluate(2.0);
  EXPECT_EQ(ramp.value, -5.0);
  EXPECT_EQ(ramp.first_derivative, -3.0);
  // (t - 1)^3 at t = 3: 8, 12, 12.
  const TimeFunctionValue cubic = MakePolynomial({0.0, 0.0, 0.0, 1.0}, 1.0)->Evaluate(3.0);
  EXPECT_NEAR(cubic.value, 8.0, kRoundOff);
  EXPECT_NEAR(cubic.first_derivative, 12.0, kRoundOff);
  EXPECT_NEAR(cubic.second_derivative, 12.0, kRoundOff);
  const TimeFunctionValue harmonic = MakeHarmonic(2.0, 3.0, 0.5, 1.0)->Evaluate(0.4);
  EXPECT_NEAR(harmonic.value, 2.0 * std::sin(1.7) + 1.0, kRoundOff);
  EXPECT_NEAR(harmonic.second_derivative, -18.0 * std::sin(1.7), kRoundOff * 10);
  for (const SmoothStepOrder order : {SmoothStepOrder::kCubic, SmoothStepOrder::kQuintic}) {
    const TimeFunctionPtr step = MakeSmoothStep(1.0, 2.0, 3.0, 6.0, order);
    EXPECT_EQ(step->Evaluate(0.5).value, 2.0);
    EXPECT_EQ(step->Evaluate(3.5).value, 6.0);
    EXPECT_NEAR(step->Evaluate(2.0).value, 4.0, kRoundOff);  // symmetric about the middle
    EXPECT_NEAR(step->Evaluate(1.0).first_derivative, 0.0, kRoundOff);
    EXPECT_NEAR(step->Evaluate(3.0).first_derivative, 0.0, kRoundOff);
  }
  // The quintic step also starts and ends with zero second derivative.
  EXPECT_NEAR(MakeSmoothStep(1.0, 2.0, 3.0, 6.0, SmoothStepOrder::kQuintic)->Evaluate(1.0 + 1e-9).second_derivative, 0.0, 1e-6);
}

TEST(TimeFunction, SpinUpReachesItsRateSmoothly) {
  // Kane et al.'s profile: at the end of the ramp T the angle is rate T / 2 (the mean rate is
  // half the final one), the rate is reached and the acceleration is back to 0; half way the
  // acceleration peaks at 2 rate / T.
  constexpr double kRate = 6.0, kRamp = 15.0, kOffset = 0.5;
  const TimeFunctionPtr spin = MakeSpinUp(kRate, kRamp, kOffset);
  for (const double t : {kRamp - 1e-9, kRamp, kRamp + 1e-9}) {
    const TimeFunctionValue v = spin->Evaluate(t);
    EXPECT_NEAR(v.value, kOffset + 0.5 * kRate * kRamp, 1e-8) << t;
    EXPECT_NEAR(v.first_derivative, kRate, 1e-8) << t;
    EXPECT_NEAR(v.second_derivative, 0.0, 1e-8) << t;
  }
  EXPECT_NEAR(spin->Evaluate(0.5 * kRamp).second_derivative, 2.0 * kRate / kRamp, kRoundOff);
  EXPECT_NEAR(spin->Evaluate(0.5 * kRamp).first_derivative, 0.5 * kRate, kRoundOff);
  EXPECT_EQ(spin->Evaluate(-1.0).value, kOffset);
  EXPECT_NEAR(spin->Evaluate(1e-6).second_derivative, 0.0, 1e-9);
  EXPECT_NEAR(spin->Evaluate(20.0).value, kOffset + kRate * (20.0 - 0.5 * kRamp), kRoundOff * 100);
}

TEST(TimeFunction, CubicSplineMatchesScipyNaturalSpline) {
  // scipy.interpolate.CubicSpline([0, 0.5, 1.2, 2, 3], [0, 1, -0.5, 2, 1.5], bc_type='natural')
  // (SciPy 1.10, Debian 12): value, first and second derivative.
  const TimeFunctionPtr spline = MakeCubicSpline({0.0, 0.5, 1.2, 2.0, 3.0}, {0.0, 1.0, -0.5, 2.0, 1.5});
  struct Sample {
    double t, f, df, ddf;
  };
  for (const Sample& s : {Sample{0.3, 0.8435922697991662, 1.898503220917014, -9.134710117468739},
                          Sample{1.0, -0.22199290856926324, -2.450989281654306, 7.57023764412927},
                          Sample{2.7, 2.093631465517241, -1.6862672887457366, -2.9250426297840058}}) {
    const TimeFunctionValue v = spline->Evaluate(s.t);
    EXPECT_NEAR(v.value, s.f, kRoundOff);
    EXPECT_NEAR(v.first_derivative, s.df, kRoundOff * 10);
    EXPECT_NEAR(v.second_derivative, s.ddf, kRoundOff * 100);
  }
  // Outside the table: the tangent lines at the end knots (SciPy's end slopes).
  EXPECT_NEAR(spline->Evaluate(-1.0).value, 0.0 - 3.268709738537325, kRoundOff * 10);
  EXPECT_NEAR(spline->Evaluate(4.0).value, 1.5 - 2.125023683213338, kRoundOff * 10);
  EXPECT_EQ(spline->Evaluate(4.0).second_derivative, 0.0);
}

TEST(TimeFunction, RejectsBadParameters) {
  EXPECT_NE(flexmbs::testing::InputErrorMessage([] { MakeSmoothStep(1.0, 0.0, 1.0, 1.0, SmoothStepOrder::kCubic); })
                .find("smooth step: end time 1 must be > start time 1"),
            std::string::npos);
  EXPECT_NE(flexmbs::testing::InputErrorMessage([] { MakeCubicSpline({0.0, 1.0, 1.0}, {0.0, 1.0, 2.0}); })
                .find("times must increase strictly: times[2] = 1 after times[1] = 1"),
            std::string::npos);
  EXPECT_NE(flexmbs::testing::InputErrorMessage([] { MakeSpinUp(1.0, 0.0); }).find("spin up: ramp time 0 must be > 0"),
            std::string::npos);
  EXPECT_NE(flexmbs::testing::InputErrorMessage([] { MakeCubicSpline({0.0}, {0.0}); }).find("need >= 2"),
            std::string::npos);
  EXPECT_NE(flexmbs::testing::InputErrorMessage([] { MakeCubicSpline({0.0, 1.0}, {0.0}); }).find("2 times but 1 values"),
            std::string::npos);
}

}  // namespace
}  // namespace flexmbs::mbs
