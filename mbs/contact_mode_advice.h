#pragma once
// Which modes a reduced body needs for a compliant contact on its surface (docs/contact.md,
// "Which modes a contact needs"): from the contact's Hertz law, the two bodies' masses and the
// impact speed the scene's initial state and gravity give, Hertz's contact time t_c, and from it
// the cut-off frequency measured to keep the peak contact force within 1 % of the full model:
// 1.5 / t_c for the modes the contact loads when the body keeps a static correction mode, 3 / t_c
// without one (tests/mbs/sphere_rod_impact_test.cc).

#include <string>
#include <vector>

#include "mbs/multibody_system.h"

namespace flexmbs::mbs {

/// The rule's factors: f_max t_c with and without a static correction mode.
inline constexpr double kCutoffTimesContactTimeWithCorrection = 1.5;
inline constexpr double kCutoffTimesContactTimeWithout = 3.0;

/// The advice for one sphere_surface_contact element.
struct ContactModeAdvice {
  std::string element;           ///< the force element
  std::string body;              ///< the reduced body whose surface it touches
  double impact_speed = 0.0;     ///< v [m/s]: the initial approach speed and the fall through the gap
  double contact_time = 0.0;     ///< t_c [s]: Hertz's, 2.94 (5 m* v^2 / (4 k))^(2/5) / v
  bool correction_mode = false;  ///< the body keeps a static correction mode
  double cutoff_hz = 0.0;        ///< f_max [Hz]: the rule's
  int loaded_modes = 0;          ///< the body's kept modes the contact loads (n . R phi_c != 0)
  int loaded_modes_above = 0;    ///< of those, above f_max (could go)
  double highest_loaded_hz = 0.0;  ///< the highest frequency among them [Hz]
  /// One line: the contact time, the cut-off and why, and what the body keeps against it.
  std::string Describe() const;
};

/// The advice for every sphere_surface_contact of `system` whose normal law is Hertz's (exponent
/// 3/2) and whose sphere approaches the surface from y0 (moving towards it, or falling towards it
/// under gravity); none for the others.
std::vector<ContactModeAdvice> AdviseContactModes(const MultibodySystem& system, const ConstVectorRef& y0);

}  // namespace flexmbs::mbs
