#pragma once
// The step loop of event-driven integration (docs/contact.md, "Event-driven integration"): ARKODE
// (mbs/ode_integrator.h) between events on the state [y; I] (I: the closed points' normal
// impulses integrated since the start), root functions on the open points' gaps and on the closed
// points' forces, impacts and separations handled at the roots (mbs/event_driven_contacts.h),
// the integrator reset after each. Simulate (mbs/simulation.h) calls it for options.event_driven.

#include <Eigen/Core>

#include "mbs/event_driven.h"
#include "mbs/multibody_system.h"
#include "mbs/simulation.h"

namespace flexmbs::mbs {

/// Integrates `system` from y0 at options.start_time to options.end_time event-driven with the
/// settings options.event_driven (which must be set) and the ODE settings options.integrator
/// (explicit or implicit, between events). Root functions, one per contact point: an open point's
/// gap g_N (an impact when it falls through 0 with U_N < 0), a closed point's (W_NN)_ii lambda_N -
/// g_N'' (a separation when it falls through 0: the LCP let the force go to 0 and the gap
/// accelerate open). At an impact the impact LCP takes every point with g_N <= gap_tolerance; a
/// point whose U_N+ <= rest_velocity is closed. After an event, closed points with lambda_N = 0 and
/// g_N'' > 0 open, the closed gaps and their velocities are projected to 0 and the integrator is
/// reset. At every output time calls contact_output (per contact: the smallest gap, the normal
/// impulse over the output interval (impacts plus the integral of lambda_N), active if a point is
/// closed or took part in an impact in the interval), then output(t, y, lambda); event_output at
/// every event. Throws InputError for bad options or initial conditions (a point penetrated by more
/// than gap_tolerance), SimulationError when the integration, an LCP or a projection fails or when
/// there are more than max_events events.
SimulationStatistics SimulateEventDriven(MultibodySystem& system, const SimulationOptions& options,
                                         Eigen::VectorXd y0, const OutputCallback& output,
                                         const ContactOutputCallback& contact_output,
                                         const EventOutputCallback& event_output);

}  // namespace flexmbs::mbs
