#include "contact/laws/normal_law.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "contact/laws/law_checks.h"
#include "core/error.h"

namespace flexmbs::contact {
namespace {

constexpr double kHertzExponent = 1.5;

/// A Hertz spring with hysteresis damping chi = factor / v0 (the three laws differ in factor(e)).
NormalLaw HysteresisLaw(NormalLawKind kind, double stiffness, double restitution, double impact_speed,
                        double factor) {
  RequireNonNegative("stiffness", stiffness);
  RequireRestitution(restitution);
  RequirePositive("impact speed [m/s]", impact_speed);
  return {kind, stiffness, kHertzExponent, 0.0, factor / impact_speed, restitution};
}

}  // namespace

const char* Name(NormalLawKind kind) {
  switch (kind) {
    case NormalLawKind::kLinear:
      return "linear";
    case NormalLawKind::kHertz:
      return "hertz";
    case NormalLawKind::kHuntCrossley:
      return "hunt_crossley";
    case NormalLawKind::kLankaraniNikravesh:
      return "lankarani_nikravesh";
    case NormalLawKind::kFlores:
      return "flores";
  }
  FLEXMBS_CHECK(false, "unknown NormalLawKind");
  return "";
}

NormalLaw LinearLaw(double stiffness, double damping, double exponent) {
  RequireNonNegative("stiffness", stiffness);
  RequireNonNegative("damping [N s/m]", damping);
  if (!(exponent >= 1.0) || !std::isfinite(exponent)) {
    throw InputError(fmt::format("exponent {} must be finite and >= 1", exponent));
  }
  return {NormalLawKind::kLinear, stiffness, exponent, damping, 0.0, 1.0};
}

NormalLaw HertzLaw(double stiffness) {
  RequireNonNegative("stiffness", stiffness);
  return {NormalLawKind::kHertz, stiffness, kHertzExponent, 0.0, 0.0, 1.0};
}

NormalLaw HuntCrossleyLaw(double stiffness, double restitution, double impact_speed) {
  return HysteresisLaw(NormalLawKind::kHuntCrossley, stiffness, restitution, impact_speed,
                       1.5 * (1.0 - restitution));
}

NormalLaw LankaraniNikraveshLaw(double stiffness, double restitution, double impact_speed) {
  return HysteresisLaw(NormalLawKind::kLankaraniNikravesh, stiffness, restitution, impact_speed,
                       0.75 * (1.0 - restitution * restitution));
}

NormalLaw FloresLaw(double stiffness, double restitution, double impact_speed) {
  return HysteresisLaw(NormalLawKind::kFlores, stiffness, restitution, impact_speed,
                       1.6 * (1.0 - restitution) / restitution);
}

NormalForce Evaluate(const NormalLaw& law, double penetration, double penetration_rate) {
  if (!(penetration > 0.0)) return {};
  const double spring = law.stiffness * std::pow(penetration, law.exponent);
  const double hysteresis = 1.0 + law.hysteresis * penetration_rate;
  const double force = spring * hysteresis + law.damping * penetration_rate;
  if (!(force > 0.0)) return {};
  // d(k delta^n)/d delta = n k delta^(n-1) = n spring / delta.
  return {force, law.exponent * spring / penetration * hysteresis, law.hysteresis * spring + law.damping};
}

double ImpactRestitution(const NormalLaw& law, double impact_speed) {
  FLEXMBS_CHECK(law.damping == 0.0, "ImpactRestitution: a linear dashpot has no closed form");
  const double a = law.hysteresis * impact_speed;
  if (a == 0.0) return 1.0;
  // g(e) = -a e - ln(1 - a e) is increasing on (0, min(1, 1/a)); bisection to round-off.
  const double target = a - std::log1p(a);
  double lo = 0.0, hi = std::min(1.0, (1.0 - 1e-15) / a);
  for (int k = 0; k < 200 && hi - lo > 1e-16; ++k) {
    const double mid = 0.5 * (lo + hi);
    (-a * mid - std::log1p(-a * mid) > target ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

double ElasticEnergy(const NormalLaw& law, double penetration) {
  if (!(penetration > 0.0)) return 0.0;
  return law.stiffness * std::pow(penetration, law.exponent + 1.0) / (law.exponent + 1.0);
}

}  // namespace flexmbs::contact
