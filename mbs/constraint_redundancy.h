#pragma once
// Redundant constraint rows (docs/mbs.md, "Redundant constraints"). A planar closed loop of
// revolute joints in 3-D repeats its out-of-plane equations: 3 rows per loop are linear
// combinations of the others at every pose of the loop, so G M^-1 G^T is singular everywhere.
// A flexible body whose modes carry a trace of the motion such a row constrains (a round rod's
// bending modes with a twist of 1e-4 of their rotation, from an unstructured mesh) leaves the
// row nearly redundant: enforcing it would lock the modes through that trace. At the start of a
// run both kinds are found from the rank of G at t0 and dropped for the whole run
// (MultibodySystem::set_dropped_constraints); during the run the dropped rows are watched
// (DroppedRowWatch): on the manifold of the kept rows they hold by themselves, up to the drift
// their independent part allows, unless the redundancy changes.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "mbs/multibody_system.h"

namespace flexmbs::mbs {

/// The rows found redundant at one state.
struct ConstraintRedundancy {
  std::vector<Eigen::Index> dropped_rows;  ///< stacked rows, ascending
  /// Per dropped row: its pivot, sin^2 of the angle between the row and the span of the rows
  /// kept before it in the metric M^-1 (FindRedundantConstraints); round-off for a row that is
  /// redundant by the mechanism's geometry.
  std::vector<double> pivots;
  /// Per dropped row k: sqrt(pivot_k (G M^-1 G^T)_kk), the norm of the row's part outside the
  /// kept rows' span in the metric M^-1. While the kept rows hold, |d g_k / dt| <= this times
  /// |u|_M = sqrt(u^T M u) [m or 1 per (sqrt(kg) m)], to first order in the motion.
  std::vector<double> drift_rates;
  double pivot_limit = 0.0;  ///< the limit they were found with
  /// "none", or "<n> rows dropped: " and DescribeRow of each.
  std::string Describe(const MultibodySystem& system) const;
  /// "'j' row i of m" (MultibodySystem::DescribeConstraintRow) of dropped row `index`, with
  /// " (nearly redundant: pivot p)" if its pivot is not below the system's singular_pivot.
  std::string DescribeRow(const MultibodySystem& system, std::size_t index) const;
};

/// The rows of G(t, y) that depend on the rows before them, in stacked order (joint order, then
/// each joint's equations), in the metric of the Schur complement: with S = G M^-1 G^T scaled to
/// unit diagonal, a Cholesky factorisation of S in that order whose pivot for row k is
/// sin^2 of the angle between row k and the span of the rows kept before it (rows in the metric
/// M^-1). Row k is dropped when that pivot is below `pivot_limit` (ConsistencyOptions::
/// redundant_pivot: about sqrt(limit) rad from the span of the others); the kept rows are
/// independent with every pivot >= the limit. The order keeps the earlier joints' rows, so the
/// rows that close a loop are the ones dropped. Ignores the system's current
/// dropped_constraints(). In a planar scene a row whose in-plane part keeps less than
/// `pivot_limit` of its mobility G_k M^-1 G_k^T (full M) is dropped first, that share its pivot
/// and no drift rate: the out-of-plane rows of spatial joints (docs/mbs.md, "Planar scenes").
ConstraintRedundancy FindRedundantConstraints(const MultibodySystem& system, double t, const ConstVectorRef& y,
                                              double pivot_limit);

/// The dropped rows may be violated by this many times the projection tolerance beyond their
/// drift (DroppedRowWatch): to first order they are combinations of the kept rows with
/// coefficients of the order of the loop's length ratios, so they follow the kept rows'
/// residual (measured: 1.0e-11 at a tolerance of 1e-11 on the slider-crank of
/// tests/validation/slider_crank_test.cc); a change of the redundancy makes them grow with the
/// motion, far beyond.
inline constexpr double kDroppedRowSlack = 100.0;

/// Watches the dropped rows of a run. After every projection, dropped row k must hold to
///   |g_k| <= base_limit + drift_rate_k s(t),   s(t) = integral of |u|_M dt since t0,
/// the drift its part outside the kept rows' span allows (ConstraintRedundancy::drift_rates;
/// s is summed step by step with the larger |u|_M of the step's two ends). A row that is
/// redundant by geometry has a drift rate at round-off and must follow the kept rows; one that
/// is only redundant at t0 (a mechanism started at a singular configuration) drifts
/// quadratically in the motion and soon exceeds its linear allowance.
class DroppedRowWatch {
 public:
  /// The watch of `redundancy`'s rows; `base_limit` [m or 1] > 0. The first Check starts s(t).
  DroppedRowWatch(ConstraintRedundancy redundancy, double base_limit);
  /// Adds the path from the last check to (t, y) (none at the first) and throws SimulationError at t ("the
  /// redundancy of the constraints changed") naming the worst row if a dropped row exceeds its
  /// limit. Nothing to do (and no cost) without dropped rows.
  void Check(const MultibodySystem& system, double t, const ConstVectorRef& y);
  /// The largest |g_k| over the dropped rows and checks so far [m or 1].
  double largest_violation() const { return largest_violation_; }
  /// The largest |g_k| / limit_k so far (<= 1 while the run goes on).
  double largest_share() const { return largest_share_; }

 private:
  ConstraintRedundancy redundancy_;
  double base_limit_;
  double path_ = 0.0;        // s(t) [sqrt(kg) m]
  double speed_ = 0.0;       // |u|_M at the last check [sqrt(kg) m/s]
  double last_time_ = 0.0;   // [s]
  bool started_ = false;
  double largest_violation_ = 0.0;
  double largest_share_ = 0.0;
};

}  // namespace flexmbs::mbs
