#pragma once
// Joints between marker I of body i (or the ground) and marker J of body j (docs/mbs.md,
// "Joints and constraints"), optionally with a driver that prescribes the free coordinate of a
// revolute or prismatic joint by a time function.

#include <Eigen/Core>
#include <string>
#include <string_view>

#include "mbs/body.h"
#include "mbs/marker_ref.h"
#include "mbs/time_function.h"

namespace flexmbs::mbs {

/// The joint types of docs/mbs.md; the free axes are I's z (and, for the universal joint, I's x
/// and J's y).
enum class JointType {
  kFixed,        ///< 6 equations: p_J = p_I, R_WJ = R_WI
  kRevolute,     ///< 5: p_J = p_I, z_J parallel to z_I
  kPrismatic,    ///< 5: p_J - p_I along z_I, R_WJ = R_WI
  kCylindrical,  ///< 4: p_J - p_I along z_I, z_J parallel to z_I
  kSpherical,    ///< 3: p_J = p_I
  kUniversal,    ///< 4: p_J = p_I, x_I perpendicular to y_J
};

/// "fixed", "revolute", "prismatic", "cylindrical", "spherical", "universal".
std::string_view JointTypeName(JointType type);
/// The type named `name`; throws InputError listing the known names.
JointType ParseJointType(std::string_view name);

/// A joint's equations at one time: g(x, t) = 0 with the velocity Jacobian G (dg/dt = G u + g_t)
/// and gamma, minus the terms of d2g/dt2 that do not depend on u' (d2g/dt2 = G u' - gamma), so
/// G u' = gamma on every motion that keeps g = 0.
struct JointEquations {
  Eigen::VectorXd g;      ///< m [m or 1]
  Eigen::VectorXd g_t;    ///< partial time derivative [m/s or 1/s]
  Eigen::MatrixXd G_i;    ///< m x n_u of body i (no columns for the ground)
  Eigen::MatrixXd G_j;    ///< m x n_u of body j
  Eigen::VectorXd gamma;  ///< m
  /// m x 6: with multipliers lambda (M u' = h + G^T lambda), the joint's load on body j at the
  /// origin of marker J is [f_W; tau_W] = D_J^T lambda [N; N m].
  Eigen::MatrixXd D_J;
};

/// A joint: immutable, evaluated from the kinematics of its two markers.
class Joint {
 public:
  /// `driver` (may be null) prescribes, for a revolute joint, the angle [rad] of J's x axis from
  /// I's x axis about I's z axis (the equation sin(angle - driver(t)) = 0); for a prismatic
  /// joint, the offset [m] of J's origin from I's along I's z axis. Throws InputError (naming
  /// the joint) for a driver on another type or for two markers on the same body.
  Joint(std::string name, JointType type, MarkerRef marker_i, MarkerRef marker_j, TimeFunctionPtr driver = nullptr);

  const std::string& name() const { return name_; }
  JointType type() const { return type_; }
  const MarkerRef& marker_i() const { return marker_i_; }
  const MarkerRef& marker_j() const { return marker_j_; }
  bool driven() const { return driver_ != nullptr; }
  /// m: the type's equations plus one for a driver.
  Eigen::Index num_equations() const;

  /// The equations at time t [s] for the kinematics I of marker_i and J of marker_j (for the
  /// ground: the fixed frame with a 6 x 0 jacobian).
  JointEquations Evaluate(double t, const MarkerKinematics& I, const MarkerKinematics& J) const;

 private:
  std::string name_;
  JointType type_;
  MarkerRef marker_i_, marker_j_;
  TimeFunctionPtr driver_;
};

}  // namespace flexmbs::mbs
