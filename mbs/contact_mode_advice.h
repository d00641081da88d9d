#pragma once
// Which modes a reduced body needs for a contact on its surface (docs/contact.md, "Which modes a
// contact needs"). A compliant contact has a contact time t_c from its law: a power-law spring
// F = k delta^n (the law's damping left out) between the effective masses of the two bodies at the
// points that touch first, meeting at the approach speed the scene's initial state and gravity
// give; the cut-off frequency measured to keep the peak contact force within 1 % of the full
// model is 1.5 / t_c for the modes the contact loads when the body keeps a static correction
// mode, 3 / t_c without one (tests/mbs/sphere_rod_impact_test.cc). A unilateral (rigid) contact
// has no law: its contact time is the body's own, the period of its lowest loaded elastic mode
// (a free bar's 2L/c); the bar keeps its plateau force within 1 % with its four lowest axial
// modes (-0.65 %; two give +2.9 %, tests/mbs/bar_impact_test.cc), so the cut-off is 4.5 / t_c,
// halfway to the fifth (the FE model's dispersion lifts the fourth just above 4 / t_c).

#include <string>
#include <vector>

#include "mbs/multibody_system.h"

namespace flexmbs::mbs {

/// The rule's factors: f_max t_c with and without a static correction mode (compliant contacts),
/// and for a unilateral contact.
inline constexpr double kCutoffTimesContactTimeWithCorrection = 1.5;
inline constexpr double kCutoffTimesContactTimeWithout = 3.0;
inline constexpr double kCutoffTimesContactTimeUnilateral = 4.5;

/// The contact time [s] of an undamped power-law spring F = k delta^n (k > 0 [N/m^n], n >= 1)
/// between two masses of effective mass m [kg] meeting at v > 0 [m/s]: from the energy balance,
/// t_c = 2 (delta_m / v) sqrt(pi) Gamma(1 + 1/(n + 1)) / Gamma(1/2 + 1/(n + 1)) with the largest
/// compression delta_m = ((n + 1) m v^2 / (2 k))^(1/(n + 1)): pi sqrt(m / k) for n = 1, Hertz's
/// 2.9432 (5 m v^2 / (4 k))^(2/5) / v for n = 3/2 (Johnson, "Contact Mechanics", 1985, §11.4,
/// who rounds the factor to 2.94).
double PowerLawContactTime(double mass, double speed, double stiffness, double exponent);

/// The advice for one flexible body of one contact pair.
struct ContactModeAdvice {
  std::string element;            ///< the force element or unilateral contact
  std::string type;               ///< its scene type (sphere_surface_contact, surface_plane, ...)
  std::string body;               ///< the reduced body whose modes it advises on
  bool unilateral = false;        ///< t_c from the body's lowest loaded mode, not from a law
  int first_points = 0;           ///< the points that touch first (springs in parallel)
  double impact_speed = 0.0;      ///< v [m/s]: the initial approach speed and the fall through the gap
  double effective_mass = 0.0;    ///< m* [kg]: both bodies held rigid, along the normal at the first points
  /// The power law F = k delta^n whose contact time is t_c (none for a unilateral contact): the
  /// law's with the first points' springs in parallel, or a PCM pair's fitted to its layers' force
  /// past first touch (mbs/contact_mode_advice_pcm.h).
  double law_stiffness = 0.0;     ///< k [N/m^n]
  double law_exponent = 1.0;      ///< n
  double contact_time = 0.0;      ///< t_c [s]
  bool correction_mode = false;   ///< the body keeps a static correction mode
  double cutoff_hz = 0.0;         ///< f_max [Hz]: the rule's
  int loaded_modes = 0;           ///< the body's kept modes the contact loads (sum of n . R phi != 0)
  int loaded_modes_above = 0;     ///< of those, above f_max (could go)
  double highest_loaded_hz = 0.0;  ///< the highest frequency among them [Hz]
  /// The body's kept modes the contact loads, lowest frequency first (indices into its modes).
  std::vector<int> loaded;
  /// One line: the contact time and where it comes from, the cut-off and why, and what the body
  /// keeps against it.
  std::string Describe() const;
};

/// The advice for every contact pair of `system` that touches a reduced body's surface and
/// approaches from y0 (moving towards it, or falling towards it under gravity; none for pairs
/// apart and at rest, or with both ends held): the force elements sphere_surface_contact and
/// surface_plane_contact with a law k delta^n (k > 0), pcm_contact with a reduced body's surface
/// on either side (its layers' law fitted past first touch), and the unilateral contacts with a
/// flexible body at either end (surface_plane, sphere_surface, surface_surface), one advice per
/// flexible body. A body welded to the ground by a fixed joint counts as the ground in m*.
std::vector<ContactModeAdvice> AdviseContactModes(const MultibodySystem& system, const ConstVectorRef& y0);

}  // namespace flexmbs::mbs
