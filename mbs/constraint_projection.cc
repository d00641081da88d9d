#include "mbs/constraint_projection.h"

#include <fmt/format.h>

#include <algorithm>
#include <vector>

#include "core/error.h"
#include "mbs/constraint_solver.h"
#include "mbs/simulation_error.h"

namespace flexmbs::mbs {
namespace {

// Largest | |e| - 1 | of the Euler parameters kept without normalising: round-off.
constexpr double kEulerNormRoundOff = 1e-14;
std::string JointName(const MultibodySystem& system, int joint) {
  return joint < 0 ? std::string("-") : fmt::format("'{}'", system.joint(joint).name());
}

double EulerParameterError(const MultibodySystem& system, const ConstVectorRef& y) {
  Eigen::VectorXd copy = y;
  return system.NormalizeEulerParameters(copy);
}

}  // namespace

ConstraintResidual MeasureConstraints(const MultibodySystem& system, double t, const ConstVectorRef& y) {
  ConstraintResidual residual;
  if (system.num_constraints() == 0) return residual;
  const SystemConstraints c = system.Constraints(t, y);
  Eigen::Index row;
  residual.position = c.g.cwiseAbs().maxCoeff(&row);
  residual.position_joint = system.JointOfConstraint(row);
  residual.velocity = (c.G * system.Velocities(y) + c.g_t).cwiseAbs().maxCoeff(&row);
  residual.velocity_joint = system.JointOfConstraint(row);
  return residual;
}

ProjectionResult ProjectPositions(const MultibodySystem& system, double t, Eigen::Ref<Eigen::VectorXd> y,
                                  const ProjectionOptions& options) {
  system.NormalizeEulerParameters(y);
  ProjectionResult result;
  if (system.num_constraints() == 0) return result;
  const std::vector<Eigen::Index> kept = system.KeptConstraints();
  double residual = 0.0;
  Eigen::Index row = 0;
  for (int iteration = 0;; ++iteration) {
    const SystemConstraints c = system.Constraints(t, y);
    residual = kept.empty() ? 0.0 : c.g(kept).cwiseAbs().maxCoeff(&row);
    if (!kept.empty()) row = kept[static_cast<std::size_t>(row)];
    if (iteration == 0) result.initial_residual = residual;
    if (residual <= options.position_tolerance) {
      result.iterations = iteration;
      result.final_residual = residual;
      return result;
    }
    if (iteration == options.max_iterations) break;
    const ConstraintSolver solver(system, t, y, c.G);
    solver.RequireFullRank(t, system.constraint_settings().singular_pivot);
    system.DisplacePositions(-solver.mass_inverse_G_transpose() * solver.SolveSchur(c.g), y);
  }
  throw SimulationError(t, fmt::format("t = {:.9g} s: the position projection did not converge in {} iterations: "
                                       "|g| = {:.3g} in joint {}, {:.3g} after the step (a step beyond the "
                                       "method's stability limit, or a closed loop that cannot close)",
                                       t, options.max_iterations, residual,
                                       JointName(system, system.JointOfConstraint(row)), result.initial_residual));
}

void ProjectVelocities(const MultibodySystem& system, double t, Eigen::Ref<Eigen::VectorXd> y) {
  if (system.num_constraints() == 0) return;
  const SystemConstraints c = system.Constraints(t, y);
  const ConstraintSolver solver(system, t, y, c.G);
  solver.RequireFullRank(t, system.constraint_settings().singular_pivot);
  auto u = y.segment(system.num_positions(), system.num_velocities());
  u -= solver.mass_inverse_G_transpose() * solver.SolveSchur(solver.constraint_jacobian() * u + c.g_t);
}

std::string ConsistencyReport::Describe(const MultibodySystem& system) const {
  return fmt::format("initial conditions: |g| = {:.3g} (joint {}), |G u + g_t| = {:.3g}, | |e| - 1 | = {:.3g}{}",
                     before.position, JointName(system, before.position_joint), before.velocity, euler_parameter_error,
                     projected ? fmt::format("; projected to |g| = {:.3g}, |G u + g_t| = {:.3g}", after.position,
                                             after.velocity)
                               : std::string("; consistent"));
}

ConsistencyReport MakeConsistent(MultibodySystem& system, double t, Eigen::Ref<Eigen::VectorXd> y,
                                 const ConsistencyOptions& options) {
  ConsistencyReport report;
  const double singular_pivot = system.constraint_settings().singular_pivot;
  if (!(options.redundant_pivot >= singular_pivot && options.redundant_pivot < 1.0)) {
    throw InputError(fmt::format("simulation: redundant pivot {} must be in [singular pivot {}, 1)",
                                 options.redundant_pivot, singular_pivot));
  }
  report.redundancy = FindRedundantConstraints(system, t, y, options.redundant_pivot);
  system.set_dropped_constraints(report.redundancy.dropped_rows);
  report.before = MeasureConstraints(system, t, y);
  report.euler_parameter_error = EulerParameterError(system, y);
  const double position_error = std::max(report.before.position, report.euler_parameter_error);
  if (!(position_error <= options.max_position_residual)) {
    throw InputError(fmt::format("inconsistent initial conditions at t = {} s: positions violate joint {} by {:.3g} "
                                 "(| |e| - 1 | = {:.3g}; projected only up to {:.3g})",
                                 t, JointName(system, report.before.position_joint), report.before.position,
                                 report.euler_parameter_error, options.max_position_residual));
  }
  if (!(report.before.velocity <= options.max_velocity_residual)) {
    throw InputError(fmt::format("inconsistent initial conditions at t = {} s: velocities violate joint {} by {:.3g} "
                                 "(projected only up to {:.3g})",
                                 t, JointName(system, report.before.velocity_joint), report.before.velocity,
                                 options.max_velocity_residual));
  }
  const double tolerance = options.projection.position_tolerance;
  if (report.before.position > tolerance || report.euler_parameter_error > kEulerNormRoundOff) {
    ProjectPositions(system, t, y, options.projection);
    report.projected = true;
  }
  if (report.projected) {
    // Rows that were near-dependent only through the initial violation are found at the
    // projected state (a loop assembled slightly out of its plane).
    const ConstraintRedundancy projected = FindRedundantConstraints(system, t, y, options.redundant_pivot);
    if (projected.dropped_rows != report.redundancy.dropped_rows) {
      report.redundancy = projected;
      system.set_dropped_constraints(report.redundancy.dropped_rows);
      ProjectPositions(system, t, y, options.projection);
    }
  }
  if (report.projected || report.before.velocity > tolerance) {
    ProjectVelocities(system, t, y);
    report.projected = true;
  }
  report.after = MeasureConstraints(system, t, y);
  DroppedRowWatch(report.redundancy, kDroppedRowSlack * options.projection.position_tolerance).Check(system, t, y);
  if (system.num_constraints() > 0) {
    // A rank-deficient Jacobian is refused even for consistent initial conditions.
    const ConstraintSolver solver(system, t, y, system.Constraints(t, y).G);
    solver.RequireFullRank(t, singular_pivot);
  }
  return report;
}

}  // namespace flexmbs::mbs
