#pragma once
// Redundant constraint rows (docs/mbs.md, "Redundant constraints"). A planar closed loop of
// revolute joints in 3-D repeats its out-of-plane equations: 3 rows per loop are linear
// combinations of the others at every pose of the loop, so G M^-1 G^T is singular everywhere.
// At the start of a run these rows are found from the rank of G at t0 and dropped for the whole
// run (MultibodySystem::set_dropped_constraints); during the run the dropped rows are watched:
// on the manifold of the kept rows they hold by themselves, unless the redundancy changes.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "mbs/multibody_system.h"

namespace flexmbs::mbs {

/// The rows found redundant at one state.
struct ConstraintRedundancy {
  std::vector<Eigen::Index> dropped_rows;  ///< stacked rows, ascending
  double pivot_limit = 0.0;                ///< the limit they were found with
  /// "none", or "<n> rows dropped: 'j' row i of m, ..." (MultibodySystem::DescribeConstraintRow).
  std::string Describe(const MultibodySystem& system) const;
};

/// The rows of G(t, y) that depend on the rows before them, in stacked order (joint order, then
/// each joint's equations), in the metric of the Schur complement: with S = G M^-1 G^T scaled to
/// unit diagonal, a Cholesky factorisation of S in that order whose pivot for row k is
/// sin^2 of the angle between row k and the span of the rows kept before it (rows in the metric
/// M^-1). Row k is dropped when that pivot is below `pivot_limit` (ConstraintSettings::
/// singular_pivot: a row the rank check of the run would call dependent, about sqrt(limit) rad
/// from the span of the others); the kept rows are independent with every pivot >= the limit.
/// The order keeps the earlier joints' rows, so the rows that close a loop are the ones dropped.
/// Ignores the system's current dropped_constraints().
ConstraintRedundancy FindRedundantConstraints(const MultibodySystem& system, double t, const ConstVectorRef& y,
                                              double pivot_limit);

/// Throws SimulationError at t ("the redundancy of the constraints changed") naming the worst
/// dropped row of the system if max |g| over the dropped rows exceeds `limit` [m or 1]; g are
/// all stacked constraint values at t.
void CheckDroppedConstraints(const MultibodySystem& system, double t, const Eigen::VectorXd& g, double limit);

}  // namespace flexmbs::mbs
