#pragma once
// Projection of a state onto the constraint manifold (docs/mbs.md): positions onto g = 0 and
// |e| = 1 by Gauss-Newton in the mass metric, velocities onto G u = -g_t; and the check of
// initial conditions (report, then project or refuse).

#include <string>

#include "mbs/multibody_system.h"

namespace flexmbs::mbs {

/// Settings of the position projection.
struct ProjectionOptions {
  /// Converged when max |g_k| <= this [m for translations, 1 (about rad) for rotations].
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
/// du = -M^-1 G^T (G M^-1 G^T)^-1 g (the smallest change in the kinetic metric,
/// MultibodySystem::DisplacePositions) until max |g| <= tolerance. Throws SimulationError at t
/// naming the joints if G M^-1 G^T is rank deficient or if it does not converge (naming the
/// joint of the largest residual).
ProjectionResult ProjectPositions(const MultibodySystem& system, double t, Eigen::Ref<Eigen::VectorXd> y,
                                  const ProjectionOptions& options);

/// u -= M^-1 G^T (G M^-1 G^T)^-1 (G u + g_t): the nearest velocities (kinetic metric) with
/// G u = -g_t. Throws SimulationError like ProjectPositions.
void ProjectVelocities(const MultibodySystem& system, double t, Eigen::Ref<Eigen::VectorXd> y);

/// How far initial conditions may violate the constraints and still be projected.
struct ConsistencyOptions {
  double max_position_residual = 1e-3;  ///< max |g_k| [m or 1] (and | |e| - 1 |)
  double max_velocity_residual = 1e-3;  ///< max |(G u + g_t)_k| [m/s or 1/s]
  ProjectionOptions projection;
};

/// What the consistency check found and did.
struct ConsistencyReport {
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
/// initial conditions"). Throws SimulationError for a rank-deficient constraint Jacobian.
ConsistencyReport MakeConsistent(const MultibodySystem& system, double t, Eigen::Ref<Eigen::VectorXd> y,
                                 const ConsistencyOptions& options);

}  // namespace flexmbs::mbs
