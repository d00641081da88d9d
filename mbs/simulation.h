#pragma once
// The multibody step loop (docs/mbs.md, "Integrators"): checks the initial conditions, hands
// the equations of motion and the projection to an OdeIntegrator, and reports the state and
// the multipliers at fixed output times.

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <vector>

#include "mbs/constraint_projection.h"
#include "mbs/event_driven.h"
#include "mbs/moreau_jean.h"
#include "mbs/multibody_system.h"
#include "mbs/ode_integrator.h"

namespace flexmbs::mbs {

/// Settings of one simulation.
struct SimulationOptions {
  OdeOptions integrator;
  double start_time = 0.0;       ///< [s]
  double end_time = 1.0;         ///< [s], > start_time
  double output_interval = 0.01; ///< [s] > 0: outputs at start_time + k output_interval and at end_time
  /// omega_B [rad/s] of the Baumgarte terms; < 0: 1 / h with h the fixed step, else the maximum
  /// step, else the output interval (the projection after every step keeps the drift at its
  /// tolerance; omega_B h = 1 stays well inside the explicit method's stability region).
  double baumgarte_frequency = -1.0;
  /// ConstraintSettings::singular_pivot.
  double singular_pivot = 1e-10;
  ProjectionOptions projection;
  ConsistencyOptions initial_conditions;
  /// Set: Moreau-Jean time stepping (mbs/moreau_jean.h, the system's unilateral contacts) instead
  /// of the ODE integrator, whose settings are then unused.
  std::optional<MoreauJeanOptions> moreau_jean;
  /// Set: event-driven integration of the unilateral contacts (mbs/event_driven_simulation.h):
  /// `integrator` between the events, impacts and contact switches at them.
  std::optional<EventDrivenOptions> event_driven;
};

/// What a run did.
struct SimulationStatistics {
  /// The initial-state check, with the constraint rows dropped as redundant for the run.
  ConsistencyReport initial_conditions;
  OdeStatistics integrator;
  long outputs = 0;
  long projections = 0;               ///< position + velocity projections (one per step and output)
  int max_projection_iterations = 0;  ///< Gauss-Newton iterations of the worst projection
  double max_drift = 0.0;             ///< largest max |g| a projection started from [m or 1]
  /// DroppedRowWatch: the largest |g| of a dropped row after a projection [m or 1], and the
  /// largest share of its limit (0 without dropped rows).
  double dropped_row_violation = 0.0;
  double dropped_row_limit_share = 0.0;
  double baumgarte_frequency = 0.0;   ///< the omega_B used [rad/s]
  MoreauJeanStatistics moreau_jean;   ///< Moreau-Jean runs only (integrator.steps counts its steps too)
  EventDrivenStatistics event_driven; ///< event-driven runs only
  double wall_seconds = 0.0;
};

/// Called at every output time with the state y and the multipliers lambda (per joint in joint
/// order; MultibodySystem::ConstraintLoad turns them into loads).
using OutputCallback = std::function<void(double t, const Eigen::VectorXd& y, const Eigen::VectorXd& lambda)>;

/// The output times of a run: start_time + k output_interval, then end_time (a last interval
/// shorter than 1e-9 output intervals is merged into the one before).
std::vector<double> OutputTimes(const SimulationOptions& options);

/// The omega_B [rad/s] of a run: options.baumgarte_frequency if >= 0, else 1 / h with h the fixed
/// step, else the maximum step, else the output interval.
double BaumgarteFrequency(const SimulationOptions& options);

/// Integrates `system` from y0 at options.start_time to options.end_time; the implicit method
/// solves its Newton systems as options.integrator.newton says, sparse by KktNewtonSolver
/// (mbs/kkt_newton_solver.h), dense with the model Jacobian (SystemJacobian). Sets the system's
/// constraint settings from the options and its dropped (redundant) constraint rows from the
/// initial state (MakeConsistent). Throws InputError for bad options or inconsistent initial
/// conditions, SimulationError (with the time) when the integration fails; a failure near a
/// singular configuration is reported with the joints of the loop, a dropped row that stops
/// holding as a change of the redundancy (DroppedRowWatch, after every projection). With
/// options.moreau_jean the run is SimulateMoreauJean's (mbs/moreau_jean_simulation.h), with
/// options.event_driven SimulateEventDriven's (mbs/event_driven_simulation.h, which also calls
/// event_output), both calling contact_output; with neither a system with unilateral contacts is
/// an InputError.
SimulationStatistics Simulate(MultibodySystem& system, const SimulationOptions& options, Eigen::VectorXd y0,
                              const OutputCallback& output, const ContactOutputCallback& contact_output = {},
                              const EventOutputCallback& event_output = {});

}  // namespace flexmbs::mbs
