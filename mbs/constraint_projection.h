#pragma once
// Projection of a state onto the constraint manifold (docs/mbs.md): positions onto g = 0 and
// |e| = 1 by Gauss-Newton in the mass metric, velocities onto G u = -g_t, both on the kept rows
// (MultibodySystem::dropped_constraints are watched, not projected); and the check of initial
// conditions (find the redundant rows, report, then project or refuse).

#include <string>

#include "mbs/constraint_redundancy.h"
#include "mbs/multibody_system.h"

namespace flexmbs::mbs {

/// Settings of the position projection.
struct ProjectionOptions {
  /// Converged when max |g_k| <= this over the kept rows [m for translations, 1 (about rad) for
  /// rotations]; the dropped rows are watched by the caller (DroppedRowWatch).
  double position_tolerance = 1e-11;
  int max_iterations = 10;
};

/// max |g_k| and max |(G u + g_t)_k| at (t, y), and the joints where they occur (-1 without
/// constraints).
struct ConstraintResidual {
  double position = 0.0;
  double velocity = 0.0;
  int position_joint = -1;
  int velocity_joint = -1;
};
ConstraintResidual MeasureConstraints(const MultibodySystem& system, double t, const ConstVectorRef& y);

/// What a position projection did.
struct ProjectionResult {
  int iterations = 0;             ///< Gauss-Newton steps taken
  double initial_residual = 0.0;  ///< max |g| before [m or 1]
  double final_residual = 0.0;    ///< max |g| after
};

/// Normalises the Euler parameters, then moves the positions by Gauss-Newton steps
/// du = -M^-1 G^T (G M^-1 G^T)^-1 g on the kept rows (the smallest change in the kinetic
/// metric, MultibodySystem::DisplacePositions) until max |g| <= tolerance there. Throws
/// SimulationError at t naming the joints if G M^-1 G^T is rank deficient or if it does not
/// converge (naming the joint of the largest residual). The dropped rows are not looked at.
ProjectionResult ProjectPositions(const MultibodySystem& system, double t, Eigen::Ref<Eigen::VectorXd> y,
                                  const ProjectionOptions& options);

/// u -= M^-1 G^T (G M^-1 G^T)^-1 (G u + g_t) on the kept rows: the nearest velocities (kinetic
/// metric) with G u = -g_t. Throws SimulationError for a rank-deficient G M^-1 G^T.
void ProjectVelocities(const MultibodySystem& system, double t, Eigen::Ref<Eigen::VectorXd> y);

/// How far initial conditions may violate the constraints and still be projected.
struct ConsistencyOptions {
  double max_position_residual = 1e-3;  ///< max |g_k| [m or 1] (and | |e| - 1 |)
  double max_velocity_residual = 1e-3;  ///< max |(G u + g_t)_k| [m/s or 1/s]
  /// Rows whose pivot at t0 (FindRedundantConstraints) is below this are dropped for the run:
  /// redundant below ConstraintSettings::singular_pivot, nearly redundant above it (within
  /// about 1e-3 rad of the span of the others: enforced, they would lock a flexible body's modes
  /// through a trace of motion, with multipliers amplified by 1 / pivot). In
  /// [singular_pivot, 1). 1e-6 is also where a failing run is blamed on a nearly singular
  /// configuration (Simulate).
  double redundant_pivot = 1e-6;
  ProjectionOptions projection;
};

/// What the consistency check found and did.
struct ConsistencyReport {
  ConstraintRedundancy redundancy;     ///< the rows dropped for the run
  ConstraintResidual before;
  double euler_parameter_error = 0.0;  ///< largest | |e| - 1 | before
  ConstraintResidual after;
  bool projected = false;              ///< y was changed
  /// One line for a log.
  std::string Describe(const MultibodySystem& system) const;
};

/// Checks initial conditions y at t: within ProjectionOptions::position_tolerance (and round-off
/// for velocities) they are kept; within the limits they are projected (positions, then
/// velocities); beyond, InputError names the worst joint and the residual ("inconsistent
/// initial conditions"). Finds the redundant rows (FindRedundantConstraints with
/// options.redundant_pivot) at y, and again at the projected y, and sets them as the system's
/// dropped_constraints for the run. Throws InputError if redundant_pivot is outside
/// [singular_pivot, 1), SimulationError if the kept rows are rank deficient at the end (they
/// are not right after the search) or a dropped row does not hold (DroppedRowWatch at t).
ConsistencyReport MakeConsistent(MultibodySystem& system, double t, Eigen::Ref<Eigen::VectorXd> y,
                                 const ConsistencyOptions& options);

}  // namespace flexmbs::mbs
