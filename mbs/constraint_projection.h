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
  /// rotations]; the dropped rows must then hold to 100 times it (CheckDroppedConstraints).
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
/// converge (naming the joint of the largest residual), and CheckDroppedConstraints' error if a
/// dropped row is then violated by more than 100 times the tolerance (the redundancy changed;
/// the dropped rows follow the kept rows' residual with a gain of order 1).
ProjectionResult ProjectPositions(const MultibodySystem& system, double t, Eigen::Ref<Eigen::VectorXd> y,
                                  const ProjectionOptions& options);

/// u -= M^-1 G^T (G M^-1 G^T)^-1 (G u + g_t) on the kept rows: the nearest velocities (kinetic
/// metric) with G u = -g_t. Throws SimulationError for a rank-deficient G M^-1 G^T.
void ProjectVelocities(const MultibodySystem& system, double t, Eigen::Ref<Eigen::VectorXd> y);

/// How far initial conditions may violate the constraints and still be projected.
struct ConsistencyOptions {
  double max_position_residual = 1e-3;  ///< max |g_k| [m or 1] (and | |e| - 1 |)
  double max_velocity_residual = 1e-3;  ///< max |(G u + g_t)_k| [m/s or 1/s]
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
/// initial conditions"). Finds the redundant rows (FindRedundantConstraints with the system's
/// singular_pivot) at y, and again at the projected y, and sets them as the system's
/// dropped_constraints for the run. Throws SimulationError if the kept rows are rank deficient
/// at the end (they are not right after the search) or a dropped row does not hold.
ConsistencyReport MakeConsistent(MultibodySystem& system, double t, Eigen::Ref<Eigen::VectorXd> y,
                                 const ConsistencyOptions& options);

}  // namespace flexmbs::mbs
