#include "mbs/constraint_rows.h"

#include <Eigen/Geometry>

#include "core/error.h"
#include "core/skew.h"

namespace flexmbs::mbs {
namespace {

// Column blocks of D: v_I, w_I, v_J, w_J.
constexpr int kVI = 0, kWI = 3, kVJ = 6, kWJ = 9;

Eigen::Index NextRows(ConstraintRows& rows, Eigen::Index count) {
  FLEXMBS_CHECK(rows.filled + count <= rows.value.size(), "constraint rows: more rows appended than reserved");
  const Eigen::Index first = rows.filled;
  rows.filled += count;
  return first;
}

}  // namespace

void AppendCoincidence(const MarkerKinematics& I, const MarkerKinematics& J, ConstraintRows& rows) {
  const Eigen::Index r = NextRows(rows, 3);
  rows.value.segment<3>(r) = J.p_WM_W - I.p_WM_W;
  rows.D.block<3, 3>(r, kVI) = -Eigen::Matrix3d::Identity();
  rows.D.block<3, 3>(r, kVJ) = Eigen::Matrix3d::Identity();
}

void AppendAxisOffset(int axis_i, const MarkerKinematics& I, const MarkerKinematics& J, ConstraintRows& rows) {
  const Eigen::Index r = NextRows(rows, 1);
  const Eigen::Vector3d a = I.R_WM.col(axis_i);
  const Eigen::Vector3d d = J.p_WM_W - I.p_WM_W;
  const Eigen::Vector3d d_dot = J.v_WM_W - I.v_WM_W;
  const Eigen::Vector3d a_dot = I.w_WM_W.cross(a);
  rows.value(r) = a.dot(d);
  rows.D.block<1, 3>(r, kVI) = -a.transpose();
  rows.D.block<1, 3>(r, kWI) = a.cross(d).transpose();
  rows.D.block<1, 3>(r, kVJ) = a.transpose();
  // d/dt of the row, times V: a_dot . d_dot + (a_dot x d + a x d_dot) . w_I.
  rows.velocity_product(r) = a_dot.dot(d_dot) + (a_dot.cross(d) + a.cross(d_dot)).dot(I.w_WM_W);
}

void AppendAxesDot(int axis_i, int axis_j, const MarkerKinematics& I, const MarkerKinematics& J, ConstraintRows& rows) {
  const Eigen::Index r = NextRows(rows, 1);
  const Eigen::Vector3d a = I.R_WM.col(axis_i);
  const Eigen::Vector3d b = J.R_WM.col(axis_j);
  const Eigen::Vector3d a_cross_b = a.cross(b);
  rows.value(r) = a.dot(b);
  rows.D.block<1, 3>(r, kWI) = a_cross_b.transpose();
  rows.D.block<1, 3>(r, kWJ) = -a_cross_b.transpose();
  const Eigen::Vector3d a_cross_b_dot = I.w_WM_W.cross(a).cross(b) + a.cross(J.w_WM_W.cross(b));
  rows.velocity_product(r) = a_cross_b_dot.dot(I.w_WM_W - J.w_WM_W);
}

void AppendRelativeRotation(const MarkerKinematics& I, const MarkerKinematics& J, ConstraintRows& rows) {
  const Eigen::Index r = NextRows(rows, 3);
  const Eigen::Matrix3d R_IJ = I.R_WM.transpose() * J.R_WM;
  const Eigen::Matrix3d H = 0.5 * (R_IJ.trace() * Eigen::Matrix3d::Identity() - R_IJ);
  const Eigen::Matrix3d B = H * I.R_WM.transpose();
  rows.value.segment<3>(r) = Axial(R_IJ);
  rows.D.block<3, 3>(r, kWI) = -B;
  rows.D.block<3, 3>(r, kWJ) = B;
  // d/dt (H R_WI^T) (w_J - w_I) = Hdot w - H R_WI^T (w_I x Omega), with Omega = w_J - w_I,
  // w = R_WI^T Omega, Rdot_IJ = w~ R_IJ.
  const Eigen::Vector3d Omega = J.w_WM_W - I.w_WM_W;
  const Eigen::Vector3d w = I.R_WM.transpose() * Omega;
  const Eigen::Matrix3d R_IJ_dot = Skew(w) * R_IJ;
  const Eigen::Matrix3d H_dot = 0.5 * (R_IJ_dot.trace() * Eigen::Matrix3d::Identity() - R_IJ_dot);
  rows.velocity_product.segment<3>(r) = H_dot * w - B * I.w_WM_W.cross(Omega);
}

}  // namespace flexmbs::mbs
