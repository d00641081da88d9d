#include "mbs/contact_force.h"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <cmath>
#include <utility>

#include "core/error.h"
#include "mbs/multibody_system.h"

namespace flexmbs::mbs {
namespace {

void Require(bool ok, const std::string& element, std::string_view what, double value, std::string_view bound) {
  if (!ok || !std::isfinite(value)) {
    throw InputError(fmt::format("force element '{}': {} {} must be finite and {}", element, what, value, bound));
  }
}

}  // namespace

SpherePlaneContact::SpherePlaneContact(std::string name, MarkerRef sphere, MarkerRef plane, double radius,
                                       double stiffness, double damping, double exponent)
    : name_(std::move(name)), sphere_(std::move(sphere)), plane_(std::move(plane)), radius_(radius),
      stiffness_(stiffness), damping_(damping), exponent_(exponent) {
  Require(radius > 0.0, name_, "radius [m]", radius, "> 0");
  Require(stiffness >= 0.0, name_, "stiffness", stiffness, ">= 0");
  Require(damping >= 0.0, name_, "damping [N s/m]", damping, ">= 0");
  Require(exponent >= 1.0, name_, "exponent", exponent, ">= 1");
}

SpherePlaneContact::State SpherePlaneContact::Evaluate(const MultibodySystem& system, const ConstVectorRef& y) const {
  State state;
  state.sphere = system.MarkerState(sphere_, y);
  state.plane = system.MarkerState(plane_, y);
  const MarkerKinematics& S = state.sphere;
  const MarkerKinematics& P = state.plane;
  state.n_W = P.R_WM.col(2);
  const Eigen::Vector3d p_PS_W = S.p_WM_W - P.p_WM_W;
  state.penetration = radius_ - state.n_W.dot(p_PS_W);
  if (!(state.penetration > 0.0)) return state;
  // The plane's material point under the contact point c = p_S - r n, and n's own turning.
  const Eigen::Vector3d p_Pc_W = p_PS_W - radius_ * state.n_W;
  const Eigen::Vector3d v_plane_W = P.v_WM_W + P.w_WM_W.cross(p_Pc_W);
  state.penetration_rate = -state.n_W.dot(S.v_WM_W - v_plane_W) - P.w_WM_W.cross(state.n_W).dot(p_PS_W);
  state.force =
      std::max(0.0, stiffness_ * std::pow(state.penetration, exponent_) + damping_ * state.penetration_rate);
  return state;
}

void SpherePlaneContact::AddForces(double /*t*/, const MultibodySystem& system, const ConstVectorRef& y,
                                   Eigen::Ref<Eigen::VectorXd> h) const {
  const State state = Evaluate(system, y);
  if (state.force == 0.0) return;
  const Eigen::Vector3d f_W = state.force * state.n_W;
  const Eigen::Vector3d p_Pc_W = state.sphere.p_WM_W - radius_ * state.n_W - state.plane.p_WM_W;
  system.AddMarkerLoad(sphere_, state.sphere, f_W, Eigen::Vector3d::Zero(), h);
  system.AddMarkerLoad(plane_, state.plane, -f_W, p_Pc_W.cross(-f_W), h);
}

double SpherePlaneContact::PotentialEnergy(double /*t*/, const MultibodySystem& system, const ConstVectorRef& y) const {
  const State state = Evaluate(system, y);
  if (!(state.penetration > 0.0)) return 0.0;
  return stiffness_ * std::pow(state.penetration, exponent_ + 1.0) / (exponent_ + 1.0);
}

void SpherePlaneContact::AddForceJacobian(double /*t*/, const MultibodySystem& system, const ConstVectorRef& y,
                                          Eigen::Ref<Eigen::MatrixXd> dh_dx, Eigen::Ref<Eigen::MatrixXd> dh_du) const {
  if (sphere_.is_ground()) return;
  const State state = Evaluate(system, y);
  if (state.force == 0.0) return;
  const MarkerKinematics& S = state.sphere;
  // h_S = J_v^T lambda n with d delta = -n^T J_v du (and likewise in x): d h_S = -J_v^T n
  // (dlambda/ddelta) n^T J_v.
  const Eigen::MatrixXd n_J = state.n_W.transpose() * S.jacobian.topRows<3>();
  const Eigen::MatrixXd coupling = n_J.transpose() * n_J;
  const Eigen::Index at = system.velocity_offset(sphere_.body), size = coupling.rows();
  const double dlambda_ddelta = exponent_ * stiffness_ * std::pow(state.penetration, exponent_ - 1.0);
  dh_dx.block(at, at, size, size) -= dlambda_ddelta * coupling;
  dh_du.block(at, at, size, size) -= damping_ * coupling;
}

}  // namespace flexmbs::mbs
