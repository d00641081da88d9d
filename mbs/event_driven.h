#pragma once
// Event-driven integration of unilateral contacts (docs/contact.md, "Event-driven integration";
// Pfeiffer & Glocker 1996, "Multibody Dynamics with Unilateral Contacts"; Glocker 2001, "Set-Valued
// Force Laws"; Acary & Brogliato 2008, "Numerical Methods for Nonsmooth Dynamical Systems", ch.
// 7-8): ARKODE between events with the closed contacts on acceleration level (sticking or
// sliding under Coulomb friction), root finding on the open gaps, on the closed contacts' forces,
// on the sticking contacts' friction margins and on the sliding contacts' velocities, an impact
// problem with Newton's restitution (and Coulomb friction) at each impact. The settings, the per-event records and the counters; the step loop is
// mbs/event_driven_simulation.h, the contact algebra mbs/event_driven_contacts.h.

#include <functional>

namespace flexmbs::mbs {

/// The impact law of event-driven impacts (docs/contact.md, "Event-driven integration").
enum class ImpactLaw {
  /// Newton's: U_N+ + e min(U_N-, 0) >= 0 _|_ P_N >= 0, one problem (with friction: De Saxce's).
  kNewton,
  /// Poisson's: a compression phase to U_N,C >= 0 _|_ P_C >= 0 and an expansion phase with
  /// P_E = e P_C + Lambda, U_N+ >= 0 _|_ Lambda >= 0 (Pfeiffer & Glocker 1996; Glocker 2001);
  /// frictionless contacts only.
  kPoisson,
};

/// Settings of event-driven integration (the smooth phases take SimulationOptions::integrator).
struct EventDrivenOptions {
  /// A contact point whose normal velocity after an impact is below this [m/s] is closed
  /// (persistent contact from then on): the rule that ends an accumulation of impacts (Zeno).
  /// A ball bouncing with e < 1 under an acceleration a is closed at most 2 rest_velocity /
  /// (a (1 - e)) before the exact accumulation time.
  double rest_velocity = 1e-3;
  /// A point takes part in an impact (or is closed at the start) when its gap is at most this [m].
  double gap_tolerance = 1e-9;
  /// The closed gaps are projected to |g_N| <= this [m] after every step.
  double gap_projection_tolerance = 1e-12;
  /// A sliding point whose tangential velocity has turned through zero along its sliding
  /// direction sticks when |U_T| is at most this [m/s]; a closed point with friction sticks after
  /// an impact when |U_T+| is at most this.
  double stick_velocity = 1e-6;
  /// A run with more events than this stops with a SimulationError (an accumulation that
  /// rest_velocity does not end).
  long max_events = 1000000;
  double lcp_tolerance = 1e-10;  ///< the LCP solves' error (contact::LcpError)
  ImpactLaw impact_law = ImpactLaw::kNewton;
};

/// Throws InputError "simulation: ..." unless rest_velocity > 0, stick_velocity > 0, gap
/// tolerances > 0, max_events >= 1 and lcp_tolerance > 0 (all finite).
void CheckEventDrivenOptions(const EventDrivenOptions& options);

/// What happened at one contact point at an event.
enum class ContactEventKind {
  kImpact = 1,      ///< the point took part in an impact LCP (its gap closed, or it was closed)
  kSeparation = 2,  ///< a closed point opened: its normal force reached 0 with g_N'' > 0
  kStick = 3,       ///< a sliding point stuck: its tangential velocity reached 0 (stick_velocity)
  kSlip = 4,        ///< a sticking point began to slide: its friction force reached mu lambda_N
};

/// One contact point at one event: a row of the results' events/ group.
struct ContactEvent {
  double time = 0.0;  ///< [s]
  ContactEventKind kind = ContactEventKind::kImpact;
  int contact = 0;                      ///< the contact's index in the system
  int point = 0;                        ///< the point's index in the contact
  double normal_velocity_before = 0.0;  ///< U_N- [m/s]
  double normal_velocity_after = 0.0;   ///< U_N+ [m/s] (after closing: 0)
  double normal_impulse = 0.0;          ///< P_N [N s] (0 for a separation, stick or slip)
  double kinetic_energy_before = 0.0;   ///< of the whole system [J]
  double kinetic_energy_after = 0.0;    ///< [J]
  bool closed_after = false;            ///< the point is closed after the event
};

/// Called at every event, once per contact point that took part, in order.
using EventOutputCallback = std::function<void(const ContactEvent& event)>;

/// Counters of an event-driven run.
struct EventDrivenStatistics {
  long events = 0;            ///< event times handled (impacts and separations)
  long impacts = 0;           ///< impact LCPs solved
  long separations = 0;       ///< points opened by their force
  long closings = 0;          ///< points closed after an impact (rest_velocity)
  long sticks = 0;            ///< sliding points that stuck
  long slips = 0;             ///< sticking points that began to slide
  long ignored_roots = 0;     ///< roots that were no event (a gap rising through 0 after an impact)
  int max_impact_points = 0;  ///< the most points in one impact LCP
  /// The largest error a converged LCP or friction-contact problem ended with.
  double max_lcp_error = 0.0;
  /// Process CPU time of the contact solves [s]: the closed points' acceleration-level problems
  /// and the impact problems, each with its constrained response W (mbs/cpu_time.h).
  double contact_solve_cpu_seconds = 0.0;
};

}  // namespace flexmbs::mbs
