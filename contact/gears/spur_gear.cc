#include "contact/gears/spur_gear.h"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "contact/laws/law_checks.h"
#include "core/error.h"

namespace flexmbs::contact {
namespace {

/// Prefixes an InputError's message with "<item>: ".
template <typename Check>
void ForItem(const char* item, Check check) {
  try {
    check();
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", item, e.what()));
  }
}

void CheckSpec(const SpurGearSpec& spec) {
  RequirePositive("module [m]", spec.module);
  if (spec.teeth < 3) throw InputError(fmt::format("teeth {} must be >= 3", spec.teeth));
  if (!(spec.pressure_angle > 0.0 && spec.pressure_angle <= std::numbers::pi / 4)) {
    throw InputError(
        fmt::format("pressure angle {} rad must be in (0, pi/4]", spec.pressure_angle));
  }
  if (!std::isfinite(spec.profile_shift))
    throw InputError(fmt::format("profile shift {} must be finite", spec.profile_shift));
  RequirePositive("addendum coefficient", spec.addendum_coefficient);
  RequirePositive("dedendum coefficient", spec.dedendum_coefficient);
  RequirePositive("face width [m]", spec.face_width);
  RequireNonNegative("tip relief C_a [m]", spec.tip_relief);
  if (spec.tip_relief > 0.0) {
    RequirePositive("tip relief length L_Ca [m]", spec.tip_relief_length);
    if (spec.tip_relief_exponent != 1 && spec.tip_relief_exponent != 2) {
      throw InputError(fmt::format("tip relief exponent {} must be 1 (linear) or 2 (parabolic)",
                                   spec.tip_relief_exponent));
    }
  }
}

/// A tip relief that starts at or below the base circle (L_Ca >= r_b tan(alpha_a)).
void CheckTipRelief(const SpurGear& gear) {
  if (gear.spec.tip_relief > 0.0 &&
      !(gear.spec.tip_relief_length < gear.base_radius * gear.tip_roll)) {
    throw InputError(fmt::format(
        "tip relief length L_Ca {} m must be < r_b tan(alpha_a) = {:.6g} m (the relief would "
        "start below the base circle)",
        gear.spec.tip_relief_length, gear.base_radius * gear.tip_roll));
  }
}

/// Undercut: the generating rack's tip line cuts below the base tangent point when
/// z < 2 (h_a* - x) / sin^2(alpha) (ISO 21771 sec. 5.4).
void CheckUndercut(const SpurGearSpec& spec) {
  const double sin2 = std::pow(std::sin(spec.pressure_angle), 2);
  const double z_min = 2.0 * (spec.addendum_coefficient - spec.profile_shift) / sin2;
  if (spec.teeth < z_min) {
    const double x_min = spec.addendum_coefficient - spec.teeth * sin2 / 2.0;
    throw InputError(
        fmt::format("teeth {} < z_min = 2 (h_a* - x) / sin^2(alpha) = {:.4g} undercut the flank "
                    "(a profile shift x >= {:.4g} avoids it)",
                    spec.teeth, z_min, x_min));
  }
}

SpurGear Derive(const SpurGearSpec& spec) {
  SpurGear gear;
  gear.spec = spec;
  const double m = spec.module;
  const double alpha = spec.pressure_angle;
  gear.pitch_radius = m * spec.teeth / 2.0;
  gear.base_radius = gear.pitch_radius * std::cos(alpha);
  gear.tip_radius = gear.pitch_radius + m * (spec.addendum_coefficient + spec.profile_shift);
  gear.root_radius = gear.pitch_radius - m * (spec.dedendum_coefficient - spec.profile_shift);
  gear.base_pitch = std::numbers::pi * m * std::cos(alpha);
  const double thickness =
      m * (std::numbers::pi / 2.0 + 2.0 * spec.profile_shift * std::tan(alpha));
  gear.base_half_angle = thickness / (2.0 * gear.pitch_radius) + Involute(alpha);
  if (gear.tip_radius > gear.base_radius) {
    gear.tip_roll = std::sqrt(std::pow(gear.tip_radius / gear.base_radius, 2) - 1.0);
  }
  return gear;
}

void CheckShape(const SpurGear& gear) {
  if (!(gear.root_radius > 0.0)) {
    throw InputError(fmt::format(
        "root radius {:.6g} m must be > 0 (dedendum m (h_f* - x) too deep)", gear.root_radius));
  }
  if (!(gear.tip_radius > gear.base_radius)) {
    throw InputError(
        fmt::format("tip radius {:.6g} m must exceed the base radius {:.6g} m (no involute flank)",
                    gear.tip_radius, gear.base_radius));
  }
  const double tip_half_angle = gear.base_half_angle - Involute(std::atan(gear.tip_roll));
  if (!(tip_half_angle > 0.0)) {
    throw InputError(fmt::format(
        "tip thickness {:.4g} m must be > 0 (pointed teeth: lower the profile shift {} or "
        "the addendum coefficient {})",
        2.0 * gear.tip_radius * tip_half_angle, gear.spec.profile_shift,
        gear.spec.addendum_coefficient));
  }
}

/// True when two parameters differ by more than round-off.
bool Differ(double a, double b) {
  return std::abs(a - b) > 1e-12 * std::max(std::abs(a), std::abs(b));
}

void CheckCanMesh(const SpurGearSpec& gear1, const SpurGearSpec& gear2) {
  if (Differ(gear1.module, gear2.module)) {
    throw InputError(
        fmt::format("gears cannot mesh: module {} m of gear 1 differs from {} m of gear 2",
                    gear1.module, gear2.module));
  }
  if (Differ(gear1.pressure_angle, gear2.pressure_angle)) {
    throw InputError(fmt::format(
        "gears cannot mesh: pressure angle {} rad of gear 1 differs from {} rad of gear 2",
        gear1.pressure_angle, gear2.pressure_angle));
  }
}

void CheckPairGeometry(const GearPair& pair, double allowance) {
  const double a = pair.centre_distance;
  for (const SpurGear* gear : {&pair.gear1, &pair.gear2}) {
    const double tip_half_angle = gear->base_half_angle - Involute(std::atan(gear->tip_roll));
    if (!(tip_half_angle > 0.0)) {
      throw InputError(fmt::format(
          "backlash {} m thins the teeth of gear {} to a tip thickness of {:.4g} m "
          "(must stay > 0)",
          allowance, gear == &pair.gear1 ? 1 : 2, 2.0 * gear->tip_radius * tip_half_angle));
    }
  }
  if (pair.path_start < 0.0) {
    throw InputError(fmt::format(
        "centre distance {:.6g} m: the tip of gear 2 meets gear 1 below its base circle "
        "(interference; s_A = {:.4g} m < 0)",
        a, pair.path_start));
  }
  if (pair.path_end > pair.line_length) {
    throw InputError(fmt::format(
        "centre distance {:.6g} m: the tip of gear 1 meets gear 2 below its base circle "
        "(interference; s_E = {:.6g} m > T1T2 = {:.6g} m)",
        a, pair.path_end, pair.line_length));
  }
  const double clearance1 = a - pair.gear1.tip_radius - pair.gear2.root_radius;
  const double clearance2 = a - pair.gear2.tip_radius - pair.gear1.root_radius;
  if (!(clearance1 > 0.0) || !(clearance2 > 0.0)) {
    throw InputError(
        fmt::format("centre distance {:.6g} m: a tip reaches the other wheel's root circle (tip "
                    "clearances {:.4g} m and {:.4g} m must be > 0; lower an addendum coefficient)",
                    a, clearance1, clearance2));
  }
  if (!(pair.contact_ratio >= 1.0)) {
    throw InputError(fmt::format(
        "centre distance {:.6g} m is too large: contact ratio {:.4g} < 1, the teeth lose mesh "
        "(a_0 = {:.6g} m)",
        a, pair.contact_ratio, pair.zero_backlash_distance));
  }
}

}  // namespace

double Involute(double alpha) { return std::tan(alpha) - alpha; }

double InverseInvolute(double value) {
  FLEXMBS_CHECK(value >= 0.0 && std::isfinite(value),
                "InverseInvolute of a negative or non-finite value");
  if (value == 0.0) return 0.0;
  double alpha = std::min(std::cbrt(3.0 * value), 1.5);
  for (int i = 0; i < 100; ++i) {
    const double t = std::tan(alpha);
    const double step = (t - alpha - value) / (t * t);
    alpha = std::min(alpha - step, (alpha + std::numbers::pi / 2.0) / 2.0);  // stays below pi/2
    if (std::abs(step) <= 1e-16 * alpha) break;
  }
  return alpha;
}

SpurGear MakeSpurGear(const SpurGearSpec& spec, const char* item) {
  SpurGear gear;
  ForItem(item, [&] {
    CheckSpec(spec);
    CheckUndercut(spec);
    gear = Derive(spec);
    CheckShape(gear);
    CheckTipRelief(gear);
  });
  return gear;
}

double TipRelief(const SpurGear& gear, double roll) {
  const SpurGearSpec& spec = gear.spec;
  if (!(spec.tip_relief > 0.0)) return 0.0;
  const double span = spec.tip_relief_length / gear.base_radius;  // t_a - t_Ca
  const double into = roll - (gear.tip_roll - span);
  if (!(into > 0.0)) return 0.0;
  return spec.tip_relief * std::pow(into / span, spec.tip_relief_exponent);
}

double PairBacklash(const GearPair& pair, double centre_distance) {
  const SpurGear& g1 = pair.gear1;
  const SpurGear& g2 = pair.gear2;
  const double r_b = g1.base_radius + g2.base_radius;
  const double alpha_w = std::acos(r_b / centre_distance);
  // The gaps along the two lines of action of a tooth in its space add up to a base pitch less the
  // two teeth's base thicknesses, plus what the lines gain from the base circles (docs/contact.md).
  return g1.base_pitch -
         2.0 * (g1.base_radius * g1.base_half_angle + g2.base_radius * g2.base_half_angle) +
         2.0 * r_b * Involute(alpha_w);
}

GearPair MakeGearPair(const GearPairSpec& spec) {
  GearPair pair;
  pair.gear1 = MakeSpurGear(spec.gear1, "gear 1");
  pair.gear2 = MakeSpurGear(spec.gear2, "gear 2");
  CheckCanMesh(spec.gear1, spec.gear2);
  RequireNonNegative("backlash [m]", spec.backlash);
  const double alpha = spec.gear1.pressure_angle;
  const double r_b = pair.gear1.base_radius + pair.gear2.base_radius;
  const double inv_w0 =
      Involute(alpha) + 2.0 * std::tan(alpha) *
                            (spec.gear1.profile_shift + spec.gear2.profile_shift) /
                            (spec.gear1.teeth + spec.gear2.teeth);
  pair.zero_backlash_distance = r_b / std::cos(InverseInvolute(inv_w0));
  pair.centre_distance =
      spec.centre_distance > 0.0 ? spec.centre_distance : pair.zero_backlash_distance;
  const double a = pair.centre_distance;
  if (!std::isfinite(a) || a < pair.zero_backlash_distance * (1.0 - 1e-12)) {
    throw InputError(
        fmt::format("centre distance {:.9g} m < a_0 = {:.9g} m (zero backlash): the teeth would "
                    "interpenetrate",
                    a, pair.zero_backlash_distance));
  }
  pair.gear1.base_half_angle -= spec.backlash / (4.0 * pair.gear1.base_radius);
  pair.gear2.base_half_angle -= spec.backlash / (4.0 * pair.gear2.base_radius);
  pair.working_pressure_angle = std::acos(r_b / a);
  pair.backlash = std::max(0.0, PairBacklash(pair, a));  // >= -1e-12 a by the check above
  pair.circumferential_backlash = pair.backlash / std::cos(pair.working_pressure_angle);
  pair.line_length = a * std::sin(pair.working_pressure_angle);
  pair.path_start = pair.line_length - pair.gear2.base_radius * pair.gear2.tip_roll;
  pair.path_end = pair.gear1.base_radius * pair.gear1.tip_roll;
  pair.contact_ratio = (pair.path_end - pair.path_start) / pair.gear1.base_pitch;
  pair.tip_corners = spec.tip_corners;
  CheckPairGeometry(pair, spec.backlash);
  return pair;
}

}  // namespace flexmbs::contact
