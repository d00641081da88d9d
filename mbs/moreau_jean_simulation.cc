#include "mbs/moreau_jean_simulation.h"

#include <algorithm>
#include <chrono>
#include <optional>

#include "core/error.h"
#include "mbs/constraint_projection.h"
#include "mbs/constraint_redundancy.h"

namespace flexmbs::mbs {
namespace {

/// Adds `step` (the next step) to the report of an output interval: its impulses add up, a
/// contact counts as active (sliding) if it was in any step's index set (slid in any step), with
/// the most points any step had in it, and the gaps, velocities, point loads, joint forces and
/// solver figures are the last step's.
void AccumulateStep(const MoreauJeanStepReport& step, MoreauJeanStepReport* interval) {
  for (std::size_t k = 0; k < step.contacts.size(); ++k) {
    ContactStepResult& sum = interval->contacts[k];
    const ContactStepResult& next = step.contacts[k];
    sum.active = sum.active || next.active;
    sum.sliding = sum.sliding || next.sliding;
    sum.loads = next.loads;
    sum.active_points = std::max(sum.active_points, next.active_points);
    sum.g_N = next.g_N;
    sum.U_N = next.U_N;
    sum.P_N += next.P_N;
    sum.P_T += next.P_T;
  }
  interval->time = step.time;
  interval->active_contacts = step.active_contacts;
  interval->solver_iterations = step.solver_iterations;
  interval->solver_error = step.solver_error;
  interval->lambda = step.lambda;
}

}  // namespace

SimulationStatistics SimulateMoreauJean(MultibodySystem& system, const SimulationOptions& options, Eigen::VectorXd y0,
                                        const OutputCallback& output, const ContactOutputCallback& contact_output) {
  const auto wall_start = std::chrono::steady_clock::now();
  FLEXMBS_CHECK(options.moreau_jean.has_value(), "SimulateMoreauJean: no Moreau-Jean options");
  MoreauJeanStepper stepper(system, *options.moreau_jean);
  const double h = options.moreau_jean->step;
  SimulationStatistics statistics;
  system.set_constraint_settings({0.0, options.singular_pivot});
  statistics.initial_conditions = MakeConsistent(system, options.start_time, y0, options.initial_conditions);
  DroppedRowWatch watch(statistics.initial_conditions.redundancy,
                        kDroppedRowSlack * options.projection.position_tolerance);
  watch.Check(system, options.start_time, y0);

  const auto emit = [&](double t, const Eigen::VectorXd& y, const MoreauJeanStepReport& report) {
    if (contact_output) contact_output(t, report);
    output(t, y, report.lambda);
    ++statistics.outputs;
  };
  emit(options.start_time, y0, stepper.Initial(options.start_time, y0));
  double t = options.start_time;
  Eigen::VectorXd& y = y0;
  for (const double t_out : OutputTimes(options)) {
    std::optional<MoreauJeanStepReport> interval;  // the steps since the last output
    while (t_out - t > 1e-9 * h) {
      const bool last = t_out - t <= h * (1.0 + 1e-9);
      const MoreauJeanStepReport& step = stepper.Step(t, last ? t_out - t : h, y);
      if (interval) {
        AccumulateStep(step, &*interval);
      } else {
        interval = step;
      }
      t = last ? t_out : t + h;
      if (system.num_constraints() > 0) {
        const ProjectionResult projection = ProjectPositions(system, t, y, options.projection);
        ProjectVelocities(system, t, y);
        watch.Check(system, t, y);
        statistics.max_projection_iterations = std::max(statistics.max_projection_iterations, projection.iterations);
        statistics.max_drift = std::max(statistics.max_drift, projection.initial_residual);
        ++statistics.projections;
      }
    }
    if (interval) emit(t, y, *interval);
  }
  statistics.moreau_jean = stepper.statistics();
  statistics.integrator.steps = statistics.moreau_jean.steps;
  statistics.dropped_row_violation = watch.largest_violation();
  statistics.dropped_row_limit_share = watch.largest_share();
  statistics.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return statistics;
}

}  // namespace flexmbs::mbs
