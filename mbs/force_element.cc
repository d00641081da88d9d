#include "mbs/force_element.h"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <cmath>
#include <string_view>
#include <utility>

#include "core/error.h"
#include "core/skew.h"
#include "mbs/multibody_system.h"
#include "mbs/simulation_error.h"

namespace flexmbs::mbs {
namespace {

Eigen::Vector3d Components(const std::array<TimeFunctionPtr, 3>& functions, double t) {
  Eigen::Vector3d value = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) {
    if (functions[static_cast<std::size_t>(k)]) value(k) = functions[static_cast<std::size_t>(k)]->Evaluate(t).value;
  }
  return value;
}

void CheckNonNegative(const std::string& element, std::string_view what, double value) {
  if (!(value >= 0.0) || !std::isfinite(value)) {
    throw InputError(fmt::format("force element '{}': {} {} must be finite and >= 0", element, what, value));
  }
}

// Offset d and rotation vector theta of J relative to I (in I), and their rates.
struct RelativeMotion {
  Eigen::Vector3d d, d_dot, theta, w;
};

RelativeMotion Relative(const MarkerKinematics& I, const MarkerKinematics& J) {
  const Eigen::Matrix3d R_IW = I.R_WM.transpose();
  const Eigen::Vector3d d_W = J.p_WM_W - I.p_WM_W;
  const Eigen::AngleAxisd rotation(R_IW * J.R_WM);
  return {R_IW * d_W, R_IW * (J.v_WM_W - I.v_WM_W - I.w_WM_W.cross(d_W)), rotation.angle() * rotation.axis(),
          R_IW * (J.w_WM_W - I.w_WM_W)};
}

/// One end of a two-point element: its marker and the marker's jacobian (6 x n_u of its body)
/// premultiplied by the end's share of the relative motion (and so of the load).
struct CouplingEnd {
  const MarkerRef* marker;
  Eigen::MatrixXd motion;  ///< 6 x n_u
};

/// Adds -(E_j - Gamma E_i)^T K (E_j - Gamma E_i) to `out` (num_velocities() square), the
/// derivative of the generalised forces of a load L_j on marker j and -Gamma^T L_j on marker i
/// (both at their origins) when dL_j = -K (E_j - Gamma E_i) du (E the markers' jacobians, which
/// map the load too). Bodies' blocks only; nothing for the ground.
void AddCoupling(const MultibodySystem& system, const MarkerRef& i, const MarkerKinematics& I, const MarkerRef& j,
                 const MarkerKinematics& J, const Eigen::Matrix<double, 6, 6>& Gamma,
                 const Eigen::Matrix<double, 6, 6>& K, Eigen::Ref<Eigen::MatrixXd> out) {
  const std::array<CouplingEnd, 2> ends{CouplingEnd{&i, -Gamma * I.jacobian}, CouplingEnd{&j, J.jacobian}};
  for (const CouplingEnd& row : ends) {
    if (row.marker->is_ground()) continue;
    for (const CouplingEnd& column : ends) {
      if (column.marker->is_ground()) continue;
      out.block(system.velocity_block(row.marker->body).start, system.velocity_block(column.marker->body).start,
                row.motion.cols(), column.motion.cols()) -= row.motion.transpose() * K * column.motion;
    }
  }
}

/// The unit vector along d = p_B - p_A of spring-damper `name`; SimulationError at t if its end
/// points meet.
Eigen::Vector3d SpringDirection(double t, const std::string& name, const Eigen::Vector3d& d) {
  const double length = d.norm();
  if (!(length > 0.0)) {
    throw SimulationError(t, fmt::format("t = {:.9g} s: spring-damper '{}': its end points meet (no direction)", t, name));
  }
  return d / length;
}

}  // namespace

void ForceElement::AddForceJacobian(double /*t*/, const MultibodySystem& /*system*/, const ConstVectorRef& /*y*/,
                                    Eigen::Ref<Eigen::MatrixXd> /*dh_dx*/,
                                    Eigen::Ref<Eigen::MatrixXd> /*dh_du*/) const {}

std::vector<ContactLoad> ForceElement::ContactLoads(double /*t*/, const MultibodySystem& /*system*/,
                                                    const ConstVectorRef& /*y*/) const {
  return {};
}

double ForceElement::PotentialEnergy(double /*t*/, const MultibodySystem& /*system*/,
                                     const ConstVectorRef& /*y*/) const {
  return 0.0;
}

void ForceElement::InitialStates(Eigen::Ref<Eigen::VectorXd> /*s0*/) const {}

void ForceElement::StateDerivatives(double /*t*/, const MultibodySystem& /*system*/, const ConstVectorRef& /*y*/,
                                    Eigen::Ref<Eigen::VectorXd> /*s_dot*/) const {
  FLEXMBS_CHECK(false, fmt::format("force element '{}' has no states to differentiate", name()));
}

void ForceElement::AddStateJacobian(double /*t*/, const MultibodySystem& /*system*/, const ConstVectorRef& /*y*/,
                                    ElementStateJacobian& /*jacobian*/) const {}

PointLoad::PointLoad(std::string name, MarkerRef at, std::array<TimeFunctionPtr, 3> force,
                     std::array<TimeFunctionPtr, 3> torque, LoadFrame frame)
    : name_(std::move(name)), at_(std::move(at)), force_(std::move(force)), torque_(std::move(torque)), frame_(frame) {}

void PointLoad::AddForces(double t, const MultibodySystem& system, const ConstVectorRef& y,
                          Eigen::Ref<Eigen::VectorXd> h) const {
  const MarkerKinematics at = system.MarkerState(at_, y);
  const Eigen::Matrix3d R = (frame_ == LoadFrame::kMarker) ? at.R_WM : Eigen::Matrix3d::Identity();
  system.AddMarkerLoad(at_, at, R * Components(force_, t), R * Components(torque_, t), h);
}

SpringDamper::SpringDamper(std::string name, MarkerRef a, MarkerRef b, double free_length, double stiffness,
                           double damping)
    : name_(std::move(name)), a_(std::move(a)), b_(std::move(b)), free_length_(free_length), stiffness_(stiffness),
      damping_(damping) {
  CheckNonNegative(name_, "free length [m]", free_length);
  CheckNonNegative(name_, "stiffness [N/m]", stiffness);
  CheckNonNegative(name_, "damping [N s/m]", damping);
}

void SpringDamper::AddForces(double t, const MultibodySystem& system, const ConstVectorRef& y,
                             Eigen::Ref<Eigen::VectorXd> h) const {
  const MarkerKinematics A = system.MarkerState(a_, y), B = system.MarkerState(b_, y);
  const Eigen::Vector3d d = B.p_WM_W - A.p_WM_W;
  const double length = d.norm();
  const Eigen::Vector3d e = SpringDirection(t, name_, d);
  const double tension = stiffness_ * (length - free_length_) + damping_ * e.dot(B.v_WM_W - A.v_WM_W);
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  system.AddMarkerLoad(a_, A, tension * e, zero, h);
  system.AddMarkerLoad(b_, B, -tension * e, zero, h);
}

double SpringDamper::PotentialEnergy(double /*t*/, const MultibodySystem& system, const ConstVectorRef& y) const {
  const double stretch = (system.MarkerState(b_, y).p_WM_W - system.MarkerState(a_, y).p_WM_W).norm() - free_length_;
  return 0.5 * stiffness_ * stretch * stretch;
}

void SpringDamper::AddForceJacobian(double t, const MultibodySystem& system, const ConstVectorRef& y,
                                    Eigen::Ref<Eigen::MatrixXd> dh_dx, Eigen::Ref<Eigen::MatrixXd> dh_du) const {
  const MarkerKinematics A = system.MarkerState(a_, y), B = system.MarkerState(b_, y);
  const Eigen::Vector3d d = B.p_WM_W - A.p_WM_W, dv = B.v_WM_W - A.v_WM_W;
  const double length = d.norm();
  const Eigen::Vector3d e = SpringDirection(t, name_, d);
  const double tension = stiffness_ * (length - free_length_) + damping_ * e.dot(dv);
  const Eigen::Matrix3d across = Eigen::Matrix3d::Identity() - e * e.transpose();
  Eigen::Matrix<double, 6, 6> K = Eigen::Matrix<double, 6, 6>::Zero(), C = K;
  K.topLeftCorner<3, 3>() = stiffness_ * e * e.transpose() + (tension / length) * across +
                            (damping_ / length) * e * (across * dv).transpose();
  C.topLeftCorner<3, 3>() = damping_ * e * e.transpose();
  const Eigen::Matrix<double, 6, 6> identity = Eigen::Matrix<double, 6, 6>::Identity();
  AddCoupling(system, a_, A, b_, B, identity, K, dh_dx);
  AddCoupling(system, a_, A, b_, B, identity, C, dh_du);
}

Bushing::Bushing(std::string name, MarkerRef marker_i, MarkerRef marker_j, const Eigen::Matrix<double, 6, 1>& stiffness,
                 const Eigen::Matrix<double, 6, 1>& damping)
    : name_(std::move(name)), marker_i_(std::move(marker_i)), marker_j_(std::move(marker_j)), stiffness_(stiffness),
      damping_(damping) {
  for (int k = 0; k < 6; ++k) {
    CheckNonNegative(name_, fmt::format("stiffness[{}]", k), stiffness(k));
    CheckNonNegative(name_, fmt::format("damping[{}]", k), damping(k));
  }
}

void Bushing::AddForces(double /*t*/, const MultibodySystem& system, const ConstVectorRef& y,
                        Eigen::Ref<Eigen::VectorXd> h) const {
  const MarkerKinematics I = system.MarkerState(marker_i_, y), J = system.MarkerState(marker_j_, y);
  const RelativeMotion relative = Relative(I, J);
  const Eigen::Vector3d f_I = -(stiffness_.head<3>().cwiseProduct(relative.d) + damping_.head<3>().cwiseProduct(relative.d_dot));
  const Eigen::Vector3d tau_I =
      -(stiffness_.tail<3>().cwiseProduct(relative.theta) + damping_.tail<3>().cwiseProduct(relative.w));
  const Eigen::Vector3d f_W = I.R_WM * f_I, tau_W = I.R_WM * tau_I;
  system.AddMarkerLoad(marker_j_, J, f_W, tau_W, h);
  // The reaction acts at J's origin: moved to I's origin it gains the moment of -f_W.
  system.AddMarkerLoad(marker_i_, I, -f_W, -tau_W - (J.p_WM_W - I.p_WM_W).cross(f_W), h);
}

void Bushing::AddForceJacobian(double /*t*/, const MultibodySystem& system, const ConstVectorRef& y,
                               Eigen::Ref<Eigen::MatrixXd> dh_dx, Eigen::Ref<Eigen::MatrixXd> dh_du) const {
  const MarkerKinematics I = system.MarkerState(marker_i_, y), J = system.MarkerState(marker_j_, y);
  // d_W = p_J - p_I moves by dp_J - dp_I + r~ dphi_I (r = p_J - p_I, dphi_I I's rotation in W):
  // the relative motion is E_J - Gamma E_I, and the reaction on I at its origin -Gamma^T L_J.
  Eigen::Matrix<double, 6, 6> Gamma = Eigen::Matrix<double, 6, 6>::Identity();
  Gamma.topRightCorner<3, 3>() = -Skew(J.p_WM_W - I.p_WM_W);
  const auto in_world = [&](const Eigen::Matrix<double, 6, 1>& diagonal) {
    Eigen::Matrix<double, 6, 6> out = Eigen::Matrix<double, 6, 6>::Zero();
    out.topLeftCorner<3, 3>() = I.R_WM * diagonal.head<3>().asDiagonal() * I.R_WM.transpose();
    out.bottomRightCorner<3, 3>() = I.R_WM * diagonal.tail<3>().asDiagonal() * I.R_WM.transpose();
    return out;
  };
  AddCoupling(system, marker_i_, I, marker_j_, J, Gamma, in_world(stiffness_), dh_dx);
  AddCoupling(system, marker_i_, I, marker_j_, J, Gamma, in_world(damping_), dh_du);
}

double Bushing::PotentialEnergy(double /*t*/, const MultibodySystem& system, const ConstVectorRef& y) const {
  const RelativeMotion relative = Relative(system.MarkerState(marker_i_, y), system.MarkerState(marker_j_, y));
  return 0.5 * (relative.d.dot(stiffness_.head<3>().cwiseProduct(relative.d)) +
                relative.theta.dot(stiffness_.tail<3>().cwiseProduct(relative.theta)));
}

}  // namespace flexmbs::mbs
