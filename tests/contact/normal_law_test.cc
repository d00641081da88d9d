// The compliant laws of contact/laws: analytic derivatives against central differences, the
// clipping that keeps a contact from pulling, Hertz's stiffness from materials against Johnson's
// formulas, regularised friction, and the parameter errors.
#include "contact/laws/normal_law.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>

#include "contact/laws/friction.h"
#include "contact/laws/hertz.h"
#include "tests/input_error.h"

namespace flexmbs::contact {
namespace {

constexpr double kStiffness = 1.3e10;  // [N/m^1.5]: a 10 mm steel sphere on a rigid flat
constexpr double kImpactSpeed = 1.0;   // [m/s]

std::array<NormalLaw, 5> AllLaws() {
  return {LinearLaw(2e7, 300.0), HertzLaw(kStiffness), HuntCrossleyLaw(kStiffness, 0.7, kImpactSpeed),
          LankaraniNikraveshLaw(kStiffness, 0.7, kImpactSpeed), FloresLaw(kStiffness, 0.7, kImpactSpeed)};
}

// Central differences of a smooth function with steps ~1e-6 of the argument: truncation
// (h^2 f''' / 6 ~ 1e-12 relative) and round-off (eps / 1e-6 ~ 2e-10 relative). Measured
// agreement 1e-11 .. 3.4e-10 (printed), tolerance 5e-9.
constexpr double kDifferenceTolerance = 5e-9;

TEST(NormalLaw, AnalyticDerivativesMatchCentralDifferences) {
  for (const NormalLaw& law : AllLaws()) {
    for (const double rate : {0.8, 0.1, -0.3}) {
      const double delta = 2e-5;
      const NormalForce at = Evaluate(law, delta, rate);
      ASSERT_GT(at.force, 0.0) << Name(law.kind);
      const double h_delta = 1e-6 * delta, h_rate = 1e-6;
      const double fd_delta =
          (Evaluate(law, delta + h_delta, rate).force - Evaluate(law, delta - h_delta, rate).force) / (2.0 * h_delta);
      const double fd_rate =
          (Evaluate(law, delta, rate + h_rate).force - Evaluate(law, delta, rate - h_rate).force) / (2.0 * h_rate);
      const double error_delta = std::abs(at.d_delta - fd_delta) / std::abs(fd_delta);
      const double error_rate = fd_rate == 0.0 ? std::abs(at.d_rate) : std::abs(at.d_rate - fd_rate) / std::abs(fd_rate);
      EXPECT_LE(error_delta, kDifferenceTolerance) << Name(law.kind) << " rate " << rate;
      EXPECT_LE(error_rate, kDifferenceTolerance) << Name(law.kind) << " rate " << rate;
      std::printf("[ numbers  ] %-20s delta' %5.2f: dF/ddelta rel. error %.1e, dF/ddelta' %.1e\n", Name(law.kind),
                  rate, error_delta, error_rate);
    }
  }
}

TEST(NormalLaw, NeverPullsAndIsZeroApart) {
  for (const NormalLaw& law : AllLaws()) {
    const NormalForce apart = Evaluate(law, -1e-6, 1.0);
    EXPECT_EQ(apart.force, 0.0);
    EXPECT_EQ(apart.d_delta, 0.0);
    EXPECT_EQ(apart.d_rate, 0.0);
    // Separating fast at a shallow penetration: a dashpot or hysteresis term would pull.
    const NormalForce separating = Evaluate(law, 1e-9, -1e3);
    EXPECT_GE(separating.force, 0.0) << Name(law.kind);
    if (law.kind != NormalLawKind::kHertz) {
      EXPECT_EQ(separating.force, 0.0) << Name(law.kind);
      EXPECT_EQ(separating.d_rate, 0.0) << Name(law.kind);
    }
  }
}

TEST(NormalLaw, HysteresisFactorsAreThePublishedOnes) {
  const double e = 0.6, v0 = 2.0;
  EXPECT_DOUBLE_EQ(HuntCrossleyLaw(1.0, e, v0).hysteresis, 3.0 * (1.0 - e) / (2.0 * v0));
  EXPECT_DOUBLE_EQ(LankaraniNikraveshLaw(1.0, e, v0).hysteresis, 3.0 * (1.0 - e * e) / (4.0 * v0));
  EXPECT_DOUBLE_EQ(FloresLaw(1.0, e, v0).hysteresis, 8.0 * (1.0 - e) / (5.0 * e * v0));
  EXPECT_EQ(FloresLaw(1.0, 1.0, v0).hysteresis, 0.0);
  // The spring part is Hertz's: k delta^(3/2) at delta' = 0, its energy k delta^(5/2) / (5/2).
  const NormalLaw law = FloresLaw(kStiffness, e, v0);
  EXPECT_DOUBLE_EQ(Evaluate(law, 1e-5, 0.0).force, kStiffness * std::pow(1e-5, 1.5));
  EXPECT_DOUBLE_EQ(ElasticEnergy(law, 1e-5), kStiffness * std::pow(1e-5, 2.5) / 2.5);
}

TEST(Hertz, StiffnessFromMaterialsAndRadii) {
  const ElasticMaterial steel{210e9, 0.3};
  // Johnson eqs. 4.22-4.23 by hand: E* = E / (1 - nu^2) on a rigid flat, half that for two
  // equal bodies; R* = R for a flat, R / 2 for two equal spheres.
  EXPECT_DOUBLE_EQ(EffectiveModulusOnRigid(steel), 210e9 / 0.91);
  EXPECT_DOUBLE_EQ(EffectiveModulus(steel, steel), 0.5 * 210e9 / 0.91);
  EXPECT_DOUBLE_EQ(EffectiveRadius(0.01, 0.01), 0.005);
  EXPECT_DOUBLE_EQ(EffectiveRadius(0.01, 0.03), 0.0075);
  EXPECT_DOUBLE_EQ(HertzStiffness(210e9 / 0.91, 0.01), 4.0 / 3.0 * 210e9 / 0.91 * 0.1);
}

TEST(RegularisedCoulomb, OpposesTheSlipUpToMuTimesTheNormalForce) {
  const RegularisedCoulomb friction = MakeRegularisedCoulomb(0.3, 1e-3);
  const Eigen::Vector3d fast(2.0, 0.0, 0.0);
  const TangentialForce sliding = Evaluate(friction, fast, 10.0);
  // |F_T| = mu F_N |v| / sqrt(|v|^2 + eps^2) = 3 (1 - eps^2 / (2 v^2) + ...).
  EXPECT_NEAR(sliding.force.x(), -3.0 / std::sqrt(1.0 + 0.25e-6), 1e-15);
  EXPECT_EQ(Evaluate(friction, Eigen::Vector3d::Zero(), 10.0).force, Eigen::Vector3d::Zero());
  // At rest it is a viscous damper mu F_N / eps.
  EXPECT_NEAR(Evaluate(friction, Eigen::Vector3d::Zero(), 10.0).d_slip(1, 1), -3.0 / 1e-3, 1e-9);
}

TEST(RegularisedCoulomb, AnalyticDerivativesMatchCentralDifferences) {
  const RegularisedCoulomb friction = MakeRegularisedCoulomb(0.4, 1e-3);
  const double normal_force = 25.0;
  for (const Eigen::Vector3d& slip : {Eigen::Vector3d(3e-4, -8e-4, 0.0), Eigen::Vector3d(0.5, 0.2, 0.0)}) {
    const TangentialForce at = Evaluate(friction, slip, normal_force);
    const double h = 1e-6 * slip.norm();
    Eigen::Matrix3d fd = Eigen::Matrix3d::Zero();
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d step = h * Eigen::Vector3d::Unit(k);
      fd.col(k) = (Evaluate(friction, slip + step, normal_force).force - Evaluate(friction, slip - step, normal_force).force) /
                  (2.0 * h);
    }
    const Eigen::Vector3d fd_normal =
        (Evaluate(friction, slip, normal_force + 1e-4).force - Evaluate(friction, slip, normal_force - 1e-4).force) / 2e-4;
    const double error = (at.d_slip - fd).norm() / fd.norm();
    const double error_normal = (at.d_normal_force - fd_normal).norm() / fd_normal.norm();
    EXPECT_LE(error, kDifferenceTolerance);
    EXPECT_LE(error_normal, kDifferenceTolerance);
    std::printf("[ numbers  ] |v_T| %.1e m/s: dF_T/dv_T rel. error %.1e, dF_T/dF_N %.1e\n", slip.norm(), error,
                error_normal);
  }
}

TEST(ContactLaws, BadParametersAreOneLineErrorsNamingTheValue) {
  using flexmbs::testing::InputErrorMessage;
  EXPECT_EQ(InputErrorMessage([] { LinearLaw(-1.0, 0.0); }), "stiffness -1 must be finite and >= 0");
  EXPECT_EQ(InputErrorMessage([] { LinearLaw(1.0, -2.0); }), "damping [N s/m] -2 must be finite and >= 0");
  EXPECT_EQ(InputErrorMessage([] { HertzLaw(-3.0); }), "stiffness -3 must be finite and >= 0");
  EXPECT_EQ(InputErrorMessage([] { HuntCrossleyLaw(1.0, 1.5, 1.0); }), "restitution 1.5 must be in (0, 1]");
  EXPECT_EQ(InputErrorMessage([] { FloresLaw(1.0, 0.0, 1.0); }), "restitution 0 must be in (0, 1]");
  EXPECT_EQ(InputErrorMessage([] { LankaraniNikraveshLaw(1.0, 0.5, 0.0); }),
            "impact speed [m/s] 0 must be finite and > 0");
  EXPECT_EQ(InputErrorMessage([] { MakeRegularisedCoulomb(-0.1, 1e-3); }),
            "friction coefficient -0.1 must be finite and >= 0");
  EXPECT_EQ(InputErrorMessage([] { MakeRegularisedCoulomb(0.1, 0.0); }),
            "friction regularisation speed [m/s] 0 must be finite and > 0");
  EXPECT_EQ(InputErrorMessage([] { CheckMaterial("sphere", {-1.0, 0.3}); }),
            "sphere: Young's modulus -1 must be finite and > 0");
  EXPECT_EQ(InputErrorMessage([] { CheckMaterial("plane", {1e9, 0.5}); }),
            "plane: Poisson's ratio 0.5 must be in (-1, 0.5)");
}

}  // namespace
}  // namespace flexmbs::contact
