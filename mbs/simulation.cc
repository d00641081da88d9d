#include "mbs/simulation.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <utility>

#include "core/error.h"
#include "mbs/constraint_solver.h"
#include "mbs/event_driven_simulation.h"
#include "mbs/kkt_newton_solver.h"
#include "mbs/moreau_jean_simulation.h"
#include "mbs/simulation_error.h"
#include "mbs/system_jacobian.h"

namespace flexmbs::mbs {
namespace {

// When the integrator gives up where the scaled Schur complement has a pivot below this, the
// failure is blamed on a nearly singular configuration (velocities and multipliers grow like
// 1 / sqrt(pivot) there).
constexpr double kNearSingularPivot = 1e-6;

void CheckOptions(const SimulationOptions& options) {
  if (!(options.end_time > options.start_time)) {
    throw InputError(fmt::format("simulation: end time {} s must be > start time {} s", options.end_time,
                                 options.start_time));
  }
  if (!(options.output_interval > 0.0)) {
    throw InputError(fmt::format("simulation: output interval {} s must be > 0", options.output_interval));
  }
  if (!(options.singular_pivot > 0.0 && options.singular_pivot < 1.0)) {
    throw InputError(fmt::format("simulation: singular pivot {} must be in (0, 1)", options.singular_pivot));
  }
}

/// The implicit method's sparse Newton solve (kkt_newton_solver.h) for Simulate: a SimulationError
/// of the model's own evaluation is already explained (as from the other callbacks).
class SimulationNewtonSolver final : public OdeNewtonSolver {
 public:
  SimulationNewtonSolver(const MultibodySystem& system, bool& model_failed)
      : solver_(system), model_failed_(model_failed) {}
  void Evaluate(double t, Eigen::Ref<const Eigen::VectorXd> y) override {
    try {
      solver_.Evaluate(t, y);
    } catch (const SimulationError&) {
      model_failed_ = true;
      throw;
    }
  }
  void Factorize(double gamma) override { solver_.Factorize(gamma); }
  void Solve(Eigen::Ref<Eigen::VectorXd> r) override { solver_.Solve(r); }

 private:
  KktNewtonSolver solver_;
  bool& model_failed_;
};

/// The failure of the step loop explained: near a singular configuration of the joints (at the
/// last projected step) the message says so and names the joints.
[[noreturn]] void ExplainFailure(const MultibodySystem& system, const SimulationError& error, bool model_failed,
                                 double last_step_time, const Eigen::VectorXd& last_step_state) {
  if (model_failed || system.num_constraints() == 0) throw error;
  const ConstraintSolver solver(system, last_step_time, last_step_state,
                                system.Constraints(last_step_time, last_step_state).G);
  if (!(solver.smallest_relative_pivot() < kNearSingularPivot)) throw error;
  throw SimulationError(error.time(), fmt::format("{}; near a singular configuration: {}", error.what(),
                                                  solver.DescribeRankDeficiency(last_step_time, kNearSingularPivot)));
}

/// The ODE problem of a run without unilateral contacts: the equations of motion, their model
/// Jacobian or sparse Newton solver, and the projection after each step (counted in statistics,
/// checked by watch; the last projected step kept to explain a failure).
OdeProblem SmoothProblem(MultibodySystem& system, const SimulationOptions& options, DroppedRowWatch& watch,
                         SimulationStatistics& statistics, bool& model_failed, double& last_step_time,
                         Eigen::VectorXd& last_step_state) {
  OdeProblem problem;
  problem.size = system.state_size();
  problem.rhs = [&](double t, Eigen::Ref<const Eigen::VectorXd> y, Eigen::Ref<Eigen::VectorXd> y_dot) {
    try {
      system.Derivative(t, y, y_dot);
    } catch (const SimulationError&) {
      model_failed = true;
      throw;
    }
  };
  problem.jacobian = [&](double t, Eigen::Ref<const Eigen::VectorXd> y, Eigen::Ref<Eigen::MatrixXd> dfdy) {
    try {
      SystemJacobian(system, t, y, dfdy);
    } catch (const SimulationError&) {
      model_failed = true;
      throw;
    }
  };
  // The sparse Newton solve knows the bodies' and joints' structure, not the force elements' states
  // (docs/mbs.md, "Force elements with states"): with states the dense LU solves.
  if (options.integrator.method == OdeMethod::kImplicit && system.num_element_states() == 0) {
    problem.newton_solver = std::make_shared<SimulationNewtonSolver>(system, model_failed);
  }
  problem.project = [&](double t, Eigen::Ref<Eigen::VectorXd> y) {
    try {
      const ProjectionResult result = ProjectPositions(system, t, y, options.projection);
      ProjectVelocities(system, t, y);
      watch.Check(system, t, y);
      statistics.max_projection_iterations = std::max(statistics.max_projection_iterations, result.iterations);
      statistics.max_drift = std::max(statistics.max_drift, result.initial_residual);
      ++statistics.projections;
      last_step_time = t;
      last_step_state = y;
    } catch (const SimulationError&) {
      model_failed = true;
      throw;
    }
  };
  return problem;
}

/// The ODE methods' run (explicit, implicit) of a system without unilateral contacts.
SimulationStatistics SimulateOde(MultibodySystem& system, const SimulationOptions& options, Eigen::VectorXd y0,
                                 const OutputCallback& output) {
  const auto wall_start = std::chrono::steady_clock::now();
  SimulationStatistics statistics;
  statistics.baumgarte_frequency = BaumgarteFrequency(options);
  system.set_constraint_settings({statistics.baumgarte_frequency, options.singular_pivot});
  statistics.initial_conditions = MakeConsistent(system, options.start_time, y0, options.initial_conditions);
  DroppedRowWatch watch(statistics.initial_conditions.redundancy,
                        kDroppedRowSlack * options.projection.position_tolerance);
  watch.Check(system, options.start_time, y0);

  bool model_failed = false;  // the failure came from the model's own check, already explained
  double last_step_time = options.start_time;  // the last projected step, to explain a failure
  Eigen::VectorXd last_step_state = y0;
  OdeProblem problem =
      SmoothProblem(system, options, watch, statistics, model_failed, last_step_time, last_step_state);
  Eigen::VectorXd u_dot(system.num_velocities()), lambda(system.num_constraints());
  const auto emit = [&](double t, const Eigen::VectorXd& y) {
    system.Accelerations(t, y, u_dot, lambda);
    output(t, y, lambda);
    ++statistics.outputs;
  };
  emit(options.start_time, y0);
  OdeIntegrator integrator(std::move(problem), options.integrator, options.start_time, y0);
  for (const double t_out : OutputTimes(options)) {
    try {
      integrator.Advance(t_out);
    } catch (const SimulationError& error) {
      ExplainFailure(system, error, model_failed, last_step_time, last_step_state);
    }
    emit(integrator.time(), integrator.state());
  }
  statistics.integrator = integrator.statistics();
  statistics.dropped_row_violation = watch.largest_violation();
  statistics.dropped_row_limit_share = watch.largest_share();
  statistics.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return statistics;
}

}  // namespace

std::vector<double> OutputTimes(const SimulationOptions& options) {
  std::vector<double> times;
  const double span = options.end_time - options.start_time;
  const long count = static_cast<long>(std::ceil(span / options.output_interval - 1e-9));
  for (long k = 1; k < count; ++k) times.push_back(options.start_time + static_cast<double>(k) * options.output_interval);
  times.push_back(options.end_time);
  return times;
}

double BaumgarteFrequency(const SimulationOptions& options) {
  if (options.baumgarte_frequency >= 0.0) return options.baumgarte_frequency;
  const OdeOptions& ode = options.integrator;
  const double h = ode.fixed_step > 0.0 ? ode.fixed_step : ode.max_step > 0.0 ? ode.max_step : options.output_interval;
  return 1.0 / h;
}

SimulationStatistics Simulate(MultibodySystem& system, const SimulationOptions& options, Eigen::VectorXd y0,
                              const OutputCallback& output, const ContactOutputCallback& contact_output,
                              const EventOutputCallback& event_output) {
  CheckOptions(options);
  if (y0.size() != system.state_size()) {
    throw InputError(fmt::format("simulation: the initial state has {} entries, the system {}", y0.size(),
                                 system.state_size()));
  }
  FLEXMBS_CHECK(!(options.moreau_jean && options.event_driven), "Simulate: both Moreau-Jean and event-driven options");
  if (const int k = system.FirstElementWithStates(); k >= 0) {
    if (options.moreau_jean || options.event_driven) {
      throw InputError(fmt::format("simulation: force element '{}' has states of its own, which only methods "
                                   "explicit and implicit integrate",
                                   system.force_element(k).name()));
    }
    if (options.integrator.method == OdeMethod::kImplicit && options.integrator.newton == OdeNewton::kSparse) {
      throw InputError(fmt::format("simulation: newton sparse does not take force element '{}' with states of "
                                   "its own; newton dense or auto",
                                   system.force_element(k).name()));
    }
  }
  if (options.moreau_jean) return SimulateMoreauJean(system, options, std::move(y0), output, contact_output);
  if (options.event_driven) {
    return SimulateEventDriven(system, options, std::move(y0), output, contact_output, event_output);
  }
  if (system.num_unilateral_contacts() > 0) {
    throw InputError(fmt::format("simulation: contact '{}' is unilateral, which only methods moreau_jean and "
                                 "event_driven integrate (compliant contact for explicit and implicit: force elements "
                                 "sphere_plane_contact, sphere_sphere_contact)",
                                 system.unilateral_contact(0).name()));
  }
  return SimulateOde(system, options, std::move(y0), output);
}

}  // namespace flexmbs::mbs
