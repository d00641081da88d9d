// The restitution each compliant law gives on a single-DOF impact, m delta'' = -F_N(delta,
// delta'), delta(0) = 0, delta'(0) = v0, integrated by classical Runge-Kutta with a fine fixed
// step, against the e it was built for, and against the exact restitution of the hysteresis
// form from its first integral (contact::ImpactRestitution: a function of chi v0 alone).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <utility>

#include "contact/laws/hertz.h"
#include "contact/laws/normal_law.h"

namespace flexmbs::contact {
namespace {

// A 10 mm steel sphere (rho = 7850 kg/m^3) on a rigid steel flat at 1 m/s.
constexpr double kRadius = 0.01, kDensity = 7850.0, kSpeed = 1.0;
const double kMass = 4.0 / 3.0 * std::numbers::pi * kRadius * kRadius * kRadius * kDensity;
const double kStiffness = HertzStiffness(EffectiveModulusOnRigid({210e9, 0.3}), kRadius);

struct Impact {
  double rebound_speed = 0.0;   ///< v_out [m/s], when delta returns to 0
  double max_energy_rise = 0.0; ///< largest step-to-step rise of m v^2/2 + spring energy [J]
  double duration = 0.0;        ///< [s]
};

// Classical RK4 over ~20000 steps of the contact (h ~ 1e-8 s here; its error ~(h / t_c)^4 is
// far below the 1e-7 checked); the crossing of delta = 0 is interpolated linearly.
Impact Integrate(const NormalLaw& law) {
  const auto acceleration = [&](double delta, double rate) { return -Evaluate(law, delta, rate).force / kMass; };
  // Contact time scales: a half period pi sqrt(m / k) (linear), ~3 delta_max / v0 (Hertz).
  const double scale = law.exponent == 1.0
                           ? std::numbers::pi * std::sqrt(kMass / law.stiffness)
                           : 3.0 * std::pow(5.0 * kMass * kSpeed * kSpeed / (4.0 * law.stiffness), 0.4) / kSpeed;
  const double h = scale / 20000.0;
  double delta = 0.0, rate = kSpeed, t = 0.0;
  const auto energy = [&] { return 0.5 * kMass * rate * rate + ElasticEnergy(law, delta); };
  Impact impact;
  double e_before = energy();
  for (int step = 0; step < 1000000; ++step) {
    const double k1x = rate, k1v = acceleration(delta, rate);
    const double k2x = rate + 0.5 * h * k1v, k2v = acceleration(delta + 0.5 * h * k1x, k2x);
    const double k3x = rate + 0.5 * h * k2v, k3v = acceleration(delta + 0.5 * h * k2x, k3x);
    const double k4x = rate + h * k3v, k4v = acceleration(delta + h * k3x, k4x);
    const double next_delta = delta + h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
    const double next_rate = rate + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
    if (next_delta <= 0.0 && step > 0) {
      const double s = delta / (delta - next_delta);
      impact.rebound_speed = -(rate + s * (next_rate - rate));
      impact.duration = t + s * h;
      return impact;
    }
    delta = next_delta;
    rate = next_rate;
    t += h;
    const double e_after = energy();
    impact.max_energy_rise = std::max(impact.max_energy_rise, e_after - e_before);
    e_before = e_after;
  }
  ADD_FAILURE() << "the impact did not end";
  return impact;
}

// The integrator against the exact first integral: measured |e_RK4 - e_exact| <= 1.7e-11
// (printed); tolerance 2e-10.
constexpr double kIntegrationTolerance = 2e-10;

using Factory = std::function<NormalLaw(double)>;

// Measured e_eff of a law built for e, printed beside the exact value.
double MeasuredRestitution(const char* name, const Factory& make, double e) {
  const NormalLaw law = make(e);
  const Impact impact = Integrate(law);
  const double measured = impact.rebound_speed / kSpeed;
  const double exact = ImpactRestitution(law, kSpeed);
  EXPECT_NEAR(measured, exact, kIntegrationTolerance) << name << " e = " << e;
  EXPECT_LE(impact.max_energy_rise, 1e-12 * 0.5 * kMass * kSpeed * kSpeed) << name;
  std::printf("[ numbers  ] %-20s built for e = %.2f: measured %.6f (measured - e %+.4f; RK4 - exact %.1e)\n", name, e,
              measured, measured - e, measured - exact);
  return measured;
}

const Factory kHuntCrossley = [](double e) { return HuntCrossleyLaw(kStiffness, e, kSpeed); };
const Factory kLankaraniNikravesh = [](double e) { return LankaraniNikraveshLaw(kStiffness, e, kSpeed); };
const Factory kFlores = [](double e) { return FloresLaw(kStiffness, e, kSpeed); };

TEST(Restitution, HertzIsElasticAndLastsHertzsImpactTime) {
  const Impact impact = Integrate(HertzLaw(kStiffness));
  EXPECT_NEAR(impact.rebound_speed, kSpeed, kIntegrationTolerance);
  // t_c = 2 I delta_max / v0, I = (2/5) B(2/5, 1/2) = 1.4716 (Johnson 1985, sec. 11.4).
  const double delta_max = std::pow(5.0 * kMass * kSpeed * kSpeed / (4.0 * kStiffness), 0.4);
  const double t_c = 2.0 * 0.4 * std::tgamma(0.4) * std::tgamma(0.5) / std::tgamma(0.9) * delta_max / kSpeed;
  EXPECT_NEAR(impact.duration, t_c, 5e-12 * t_c);  // measured 4.4e-13 (printed)
  std::printf("[ numbers  ] hertz: e = %.12f, t_c %.6e s (relative error %.1e)\n", impact.rebound_speed / kSpeed,
              impact.duration, impact.duration / t_c - 1.0);
}

constexpr std::array kRestitutions{1.0, 0.99, 0.95, 0.9, 0.8, 0.7, 0.5, 0.3, 0.2, 0.1};

// Hunt & Crossley and Lankarani & Nikravesh derived chi to first order in 1 - e: near e = 1
// they give e. Measured |e_eff - e|: HC 0.0001 / 0.0024 / 0.0090 at e = 0.99 / 0.95 / 0.9,
// LN 0.0001 / 0.0035 / 0.0132; tolerance 0.1 (1 - e) + 0.004 (at 0.9: 0.014). Below, both
// overestimate e, more as e falls (HC 0.66, LN 0.73 at e = 0.5; 0.52 and 0.67 at 0.1): the
// papers' stated limitation, asserted as e_eff > e.
TEST(Restitution, HuntCrossleyAndLankaraniNikraveshHoldNearOneOnly) {
  for (const double e : kRestitutions) {
    for (const auto& [name, make] : {std::pair{"hunt_crossley", kHuntCrossley},
                                     std::pair{"lankarani_nikravesh", kLankaraniNikravesh}}) {
      const double measured = MeasuredRestitution(name, make, e);
      if (e >= 0.9) {
        EXPECT_NEAR(measured, e, 0.1 * (1.0 - e) + 0.004) << name;
      } else {
        EXPECT_GT(measured, e + 0.03) << name;
      }
    }
  }
}

// Flores et al. 2011 claim their chi holds over the whole range of e. Measured |e_eff - e| at
// most 0.0445 (at e = 0.2) for e in [0.1, 1]; tolerance 0.05.
TEST(Restitution, FloresHoldsForAnyRestitution) {
  double worst = 0.0;
  for (const double e : kRestitutions) {
    const double measured = MeasuredRestitution("flores", kFlores, e);
    EXPECT_NEAR(measured, e, 0.05);
    worst = std::max(worst, std::abs(measured - e));
  }
  std::printf("[ numbers  ] flores: largest |e_eff - e| %.4f\n", worst);
}

// The linear spring-dashpot, clipped at 0, separates when k delta + c delta' = 0, before delta
// returns to 0: it dissipates, never gains (its e has no closed form here; printed).
TEST(Restitution, LinearSpringDashpotDissipates) {
  const double k = 2e7, zeta = 0.1;
  const Impact impact = Integrate(LinearLaw(k, 2.0 * zeta * std::sqrt(k * kMass)));
  EXPECT_LT(impact.rebound_speed, kSpeed);
  EXPECT_GT(impact.rebound_speed, 0.0);
  EXPECT_LE(impact.max_energy_rise, 1e-12 * 0.5 * kMass * kSpeed * kSpeed);
  std::printf("[ numbers  ] linear, zeta %.2f: e = %.6f (unclipped exp(-zeta pi / sqrt(1 - zeta^2)) = %.6f)\n", zeta,
              impact.rebound_speed / kSpeed, std::exp(-zeta * std::numbers::pi / std::sqrt(1.0 - zeta * zeta)));
}

}  // namespace
}  // namespace flexmbs::contact
