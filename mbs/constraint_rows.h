#pragma once
// The scalar constraints that joints are made of, between two marker frames I and J (docs/mbs.md,
// "Joints and constraints"). Each row is a function c of the two frames' poses with
//   dc/dt = D V,   d2c/dt2 = D A + Ddot V,
// V = [v_WI_W; w_WI_W; v_WJ_W; w_WJ_W] the frames' spatial velocities and A their
// accelerations (all in W). Rotation rows are dot products of frame axes (well conditioned near
// the assembled pose) or the axial vector of R_IJ = R_WI^T R_WJ.

#include <Eigen/Core>

#include "mbs/body.h"

namespace flexmbs::mbs {

/// Rows of scalar constraints, filled in order by the Append* functions.
struct ConstraintRows {
  /// Space for m rows.
  explicit ConstraintRows(Eigen::Index m)
      : value(Eigen::VectorXd::Zero(m)), D(Eigen::MatrixXd::Zero(m, 12)), velocity_product(Eigen::VectorXd::Zero(m)) {}

  Eigen::VectorXd value;             ///< c [m or 1]
  Eigen::MatrixXd D;                 ///< m x 12, dc/dt = D V
  Eigen::VectorXd velocity_product;  ///< Ddot V [m/s^2 or 1/s^2]
  Eigen::Index filled = 0;           ///< rows written so far
};

/// 3 rows: p_WJ - p_WI (W components) [m].
void AppendCoincidence(const MarkerKinematics& I, const MarkerKinematics& J, ConstraintRows& rows);

/// 1 row: a . (p_WJ - p_WI) with a = axis `axis_i` (0 x, 1 y, 2 z) of I [m].
void AppendAxisOffset(int axis_i, const MarkerKinematics& I, const MarkerKinematics& J, ConstraintRows& rows);

/// 1 row: a . b with a = axis `axis_i` of I and b = axis `axis_j` of J: zero when they are
/// perpendicular.
void AppendAxesDot(int axis_i, int axis_j, const MarkerKinematics& I, const MarkerKinematics& J, ConstraintRows& rows);

/// 3 rows: the axial vector of R_IJ = R_WI^T R_WJ, sin(theta) n for a relative rotation by theta
/// about n (I components); its rate is H R_WI^T (w_J - w_I) with H = (tr(R_IJ) 1 - R_IJ) / 2.
void AppendRelativeRotation(const MarkerKinematics& I, const MarkerKinematics& J, ConstraintRows& rows);

}  // namespace flexmbs::mbs
