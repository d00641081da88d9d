#pragma once
// The step loop of Moreau-Jean time stepping (docs/contact.md, "Moreau-Jean time stepping"):
// the initial-state check, fixed steps of mbs/moreau_jean.h with the joints' drift projected
// after each, and the outputs. Simulate (mbs/simulation.h) calls it for options.moreau_jean.

#include <Eigen/Core>

#include "mbs/moreau_jean.h"
#include "mbs/multibody_system.h"
#include "mbs/simulation.h"

namespace flexmbs::mbs {

/// Integrates `system` from y0 at options.start_time to options.end_time by Moreau-Jean steps of
/// options.moreau_jean (which must be set): steps of h up to each output time, the last one
/// before it shortened to land on it when the output interval is not a multiple of h (within
/// 1e-9 h it is). After every step the positions are projected onto the kept joint rows and the
/// velocities onto G u = -g_t (ProjectPositions, ProjectVelocities; nothing without joints).
/// At every output time calls contact_output (if set) with the report of the output interval
/// (the steps since the last output: impulses summed, a contact active if it was in any step's
/// index set, gaps and the rest from the last step), then output(t, y, lambda) with lambda the
/// joints' average forces of the last step. Throws InputError for bad options or
/// initial conditions (as Simulate), SimulationError as MoreauJeanStepper::Step and the
/// projections do.
SimulationStatistics SimulateMoreauJean(MultibodySystem& system, const SimulationOptions& options, Eigen::VectorXd y0,
                                        const OutputCallback& output, const ContactOutputCallback& contact_output);

}  // namespace flexmbs::mbs
