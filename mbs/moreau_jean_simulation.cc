#include "mbs/moreau_jean_simulation.h"

#include <algorithm>
#include <chrono>

#include "core/error.h"
#include "mbs/constraint_projection.h"
#include "mbs/constraint_redundancy.h"

namespace flexmbs::mbs {

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
    output(t, y, report.lambda);
    if (contact_output) contact_output(t, report);
    ++statistics.outputs;
  };
  emit(options.start_time, y0, stepper.Initial(options.start_time, y0));
  double t = options.start_time;
  Eigen::VectorXd& y = y0;
  for (const double t_out : OutputTimes(options)) {
    const MoreauJeanStepReport* report = nullptr;
    while (t_out - t > 1e-9 * h) {
      const bool last = t_out - t <= h * (1.0 + 1e-9);
      report = &stepper.Step(t, last ? t_out - t : h, y);
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
    if (report != nullptr) emit(t, y, *report);
  }
  statistics.moreau_jean = stepper.statistics();
  statistics.integrator.steps = statistics.moreau_jean.steps;
  statistics.dropped_row_violation = watch.largest_violation();
  statistics.dropped_row_limit_share = watch.largest_share();
  statistics.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return statistics;
}

}  // namespace flexmbs::mbs
