#pragma once
// Involute spur gears and gear pairs: the basic parameters, the radii and angles derived from
// them, and the checks that a wheel can be made and a pair can mesh (docs/contact.md, "Spur
// gears"). Definitions and symbols of ISO 21771 / DIN 3960; no tip shortening (the addendum is
// m (h_a* + x)), no root fillet (the flank is the involute from the base circle up).

namespace flexmbs::contact {

/// The basic parameters of one external involute spur gear.
struct SpurGearSpec {
  double module = 0.0;          ///< m [m] > 0
  int teeth = 0;                ///< z >= 3
  double pressure_angle = 0.0;  ///< alpha [rad] in (0, pi/4]; 20 deg = 0.349066 is the standard
  double profile_shift = 0.0;   ///< x [-] (the rack's datum line moved out by x m)
  double addendum_coefficient = 1.0;   ///< h_a* [-] > 0 (addendum m (h_a* + x))
  double dedendum_coefficient = 1.25;  ///< h_f* [-] > 0 (dedendum m (h_f* - x))
  double face_width = 0.0;             ///< b [m] > 0
  /// Tip relief (TipRelief): C_a [m] >= 0 of material taken off the flank at the tip, along its
  /// normal; 0: none.
  double tip_relief = 0.0;
  /// L_Ca [m] > 0 (with C_a > 0): the relief's extent along the line of action, down from the
  /// tip: it starts at roll angle t_Ca = tan(alpha_a) - L_Ca / r_b, which must lie above 0.
  double tip_relief_length = 0.0;
  /// The relief's growth from t_Ca to the tip: 1 linear, 2 parabolic.
  int tip_relief_exponent = 1;
};

/// A wheel's derived geometry (ISO 21771 sec. 5). Radii [m], angles [rad].
struct SpurGear {
  SpurGearSpec spec;
  double pitch_radius = 0.0;  ///< r = m z / 2
  double base_radius = 0.0;   ///< r_b = r cos(alpha)
  double tip_radius = 0.0;    ///< r_a = r + m (h_a* + x)
  double root_radius = 0.0;   ///< r_f = r - m (h_f* - x)
  double base_pitch = 0.0;    ///< p_b = pi m cos(alpha) = 2 pi r_b / z
  /// tan(alpha_a), cos(alpha_a) = r_b / r_a: the involute's roll angle at the tip.
  double tip_roll = 0.0;
  /// psi_b = s / (2 r) + inv(alpha): half the tooth's thickness on the base circle as an angle,
  /// s = m (pi/2 + 2 x tan(alpha)) the thickness on the pitch circle. A pair may thin it
  /// (GearPairSpec::backlash).
  double base_half_angle = 0.0;
};

/// The tip relief [m] of `gear`'s flank at roll angle t [rad]: C_a ((t - t_Ca) / (t_a - t_Ca))^e
/// above t_Ca = t_a - L_Ca / r_b (t_a = tip_roll, e the exponent), 0 below it or without relief.
/// The rigid flanks' gap of a tooth pair grows by both teeth's relief (gear_mesh.h).
double TipRelief(const SpurGear& gear, double roll);

/// The involute function inv(alpha) = tan(alpha) - alpha, alpha in [0, pi/2).
double Involute(double alpha);
/// The angle alpha in [0, pi/2) with inv(alpha) = value >= 0 (Newton's method from
/// (3 value)^(1/3), to round-off).
double InverseInvolute(double value);

/// The wheel of `spec`, after its checks; InputError "<item>: <parameter> <value> ..." (one line)
/// for a module, pressure angle, coefficient or face width out of range, fewer than 3 teeth,
/// undercut (z < z_min = 2 (h_a* - x) / sin^2(alpha), ISO 21771 sec. 5.4: the message names the
/// shift that avoids it), a root circle at or below the centre, a tip circle not above the base
/// circle, pointed teeth (tip thickness <= 0), or a tip relief with C_a < 0, L_Ca <= 0, an
/// exponent other than 1 or 2, or a start at or below the base circle. `item` names the wheel in
/// the message.
SpurGear MakeSpurGear(const SpurGearSpec& spec, const char* item);

/// Two external wheels in mesh.
struct GearPairSpec {
  SpurGearSpec gear1, gear2;
  /// a [m]; <= 0 (the default): the zero-backlash centre distance a_0.
  double centre_distance = 0.0;
  /// Normal backlash j [m] >= 0 added by thinner teeth (each wheel's tooth thinner by j/2 along
  /// the line of action): a tooth thickness allowance, on top of the backlash from a > a_0.
  double backlash = 0.0;
  /// Whether a tooth's tip corner may touch the mating flank off the line of action
  /// (MeshingToothPairs, ToothContact): under load a pair then enters before the path of
  /// contact's start and leaves after its end. false: the involutes on the line only (the
  /// textbook's path of contact).
  bool tip_corners = true;
};

/// A pair's derived geometry at its centre distance. The transverse plane's pair frame: origin
/// at wheel 1's centre O1, x axis towards wheel 2's centre O2, both wheels turning about z.
/// Lengths [m], angles [rad].
struct GearPair {
  SpurGear gear1, gear2;         ///< base_half_angle thinned by the allowance
  double centre_distance = 0.0;  ///< a
  /// a_0 = (r_b1 + r_b2) / cos(alpha_w0), inv(alpha_w0) = inv(alpha) + 2 tan(alpha) (x1 + x2) /
  /// (z1 + z2): the zero-backlash centre distance.
  double zero_backlash_distance = 0.0;
  double working_pressure_angle = 0.0;  ///< alpha_w = acos((r_b1 + r_b2) / a)
  /// j_bn: the normal backlash along the line of action, PairBacklash(a).
  double backlash = 0.0;
  /// j_wt = j_bn / cos(alpha_w): the backlash on the working pitch circle.
  double circumferential_backlash = 0.0;
  /// T1T2 = a sin(alpha_w): the line of action between the base circles.
  double line_length = 0.0;
  /// s_A = T1T2 - r_b2 tan(alpha_a2): where wheel 2's tip meets the line, from T1.
  double path_start = 0.0;
  /// s_E = r_b1 tan(alpha_a1): where wheel 1's tip meets it.
  double path_end = 0.0;
  /// epsilon_alpha = (s_E - s_A) / p_b (ISO 21771 sec. 6.3).
  double contact_ratio = 0.0;
  bool tip_corners = true;  ///< GearPairSpec::tip_corners
};

/// The pair of `spec` after the wheels' checks (MakeSpurGear, items "gear 1", "gear 2") and the
/// pair's: InputError for wheels that cannot mesh (different modules or pressure angles), a
/// negative backlash or one that thins a wheel's tips to nothing, a centre distance below a_0
/// (the teeth would interpenetrate) or so large that the contact ratio falls below 1, a tip that
/// meets the other wheel's flank below its base circle (interference) or reaches its root
/// circle (no tip clearance).
GearPair MakeGearPair(const GearPairSpec& spec);

/// The normal backlash j_bn [m] of `pair`'s wheels at centre distance a > r_b1 + r_b2:
///   j_bn = 2 (r_b1 + r_b2) (inv(alpha_w) - inv(alpha_w0)) + j
/// (the change of the gap along the line of action with a, derived in docs/contact.md; j the
/// allowance). The pair's own backlash is this at its centre distance.
double PairBacklash(const GearPair& pair, double centre_distance);

}  // namespace flexmbs::contact
