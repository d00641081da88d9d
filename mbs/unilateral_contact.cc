#include "mbs/unilateral_contact.h"

#include <fmt/format.h>

#include <cmath>
#include <utility>

#include "contact/geometry/point_contact.h"
#include "core/error.h"
#include "core/skew.h"
#include "mbs/multibody_system.h"
#include "mbs/simulation_error.h"

namespace flexmbs::mbs {
namespace {

void CheckRadius(const std::string& contact, std::string_view what, double radius) {
  if (!(radius > 0.0) || !std::isfinite(radius)) {
    throw InputError(fmt::format("contact '{}': {} {:g} must be finite and > 0", contact, what, radius));
  }
}

UnilateralContactKinematics FromPointContact(const contact::PointContactKinematics& c) {
  UnilateralContactKinematics k;
  static_cast<contact::PointContactKinematics&>(k) = c;
  return k;
}

}  // namespace

UnilateralContact::UnilateralContact(std::string name, MarkerRef a, MarkerRef b, UnilateralLaw law)
    : name_(std::move(name)), a_(std::move(a)), b_(std::move(b)), law_(law) {
  if (!(law_.restitution >= 0.0 && law_.restitution <= 1.0)) {
    throw InputError(fmt::format("contact '{}': restitution {:g} must be in [0, 1]", name_, law_.restitution));
  }
  if (!(law_.friction >= 0.0) || !std::isfinite(law_.friction)) {
    throw InputError(fmt::format("contact '{}': friction {:g} must be finite and >= 0", name_, law_.friction));
  }
  if (a_.body == b_.body) {
    throw InputError(fmt::format("contact '{}': both shapes are on {}", name_,
                                 a_.is_ground() ? "the ground" : "one body"));
  }
}

std::vector<UnilateralContactKinematics> UnilateralContact::Evaluate(double t, const MultibodySystem& system,
                                                                   const ConstVectorRef& y) const {
  try {
    return EvaluatePoints(system, y);
  } catch (const contact::DegenerateContactError& e) {
    throw SimulationError(t, fmt::format("t = {:.9g} s: contact '{}': {}", t, name_, e.what()));
  }
}

void UnilateralContact::AddPointJacobian(const MultibodySystem& system, const MarkerRef& ref,
                                         const MarkerKinematics& marker, const Eigen::Vector3d& p_W, double sign,
                                         UnilateralContactKinematics* k) {
  if (ref.is_ground()) return;
  const Eigen::MatrixXd J_p =
      marker.jacobian.topRows<3>() - Skew(p_W - marker.p_WM_W) * marker.jacobian.bottomRows<3>();
  const Eigen::Index column = system.velocity_block(ref.body).start, n = J_p.cols();
  k->W_N.segment(column, n) += sign * k->n_W.transpose() * J_p;
  k->W_T.middleCols(column, n).row(0) += sign * k->t1_W.transpose() * J_p;
  k->W_T.middleCols(column, n).row(1) += sign * k->t2_W.transpose() * J_p;
}

void UnilateralContact::AddModalJacobian(Eigen::Index column, const Eigen::Matrix3Xd& modal_W, double sign,
                                         UnilateralContactKinematics* k) {
  const Eigen::Index n = modal_W.cols();
  k->W_N.segment(column, n) += sign * k->n_W.transpose() * modal_W;
  k->W_T.middleCols(column, n).row(0) += sign * k->t1_W.transpose() * modal_W;
  k->W_T.middleCols(column, n).row(1) += sign * k->t2_W.transpose() * modal_W;
}

template <std::size_t N>
std::vector<UnilateralContactKinematics> UnilateralContact::PointsOnPlane(
    const MultibodySystem& system, const ConstVectorRef& y, const std::array<Eigen::Vector3d, N>& points_A) const {
  const MarkerKinematics a = system.MarkerState(marker_a(), y), plane = system.MarkerState(marker_b(), y);
  std::vector<UnilateralContactKinematics> points;
  points.reserve(N);
  for (const Eigen::Vector3d& point_A : points_A) {
    UnilateralContactKinematics k;
    static_cast<contact::PointContactKinematics&>(k) =
        contact::PointPlane(a.p_WM_W + a.R_WM * point_A, {plane.p_WM_W, plane.R_WM.col(2)});
    k.W_N = Eigen::RowVectorXd::Zero(system.num_velocities());
    k.W_T = Eigen::MatrixXd::Zero(2, system.num_velocities());
    AddPointJacobian(system, marker_a(), a, k.p_WA_W, 1.0, &k);
    AddPointJacobian(system, marker_b(), plane, k.p_WB_W, -1.0, &k);
    points.push_back(std::move(k));
  }
  return points;
}

std::vector<UnilateralContactKinematics> ShapePairUnilateral::EvaluatePoints(const MultibodySystem& system,
                                                                             const ConstVectorRef& y) const {
  const MarkerKinematics a = system.MarkerState(marker_a(), y), b = system.MarkerState(marker_b(), y);
  UnilateralContactKinematics k = Geometry(a, b);
  k.W_N = Eigen::RowVectorXd::Zero(system.num_velocities());
  k.W_T = Eigen::MatrixXd::Zero(2, system.num_velocities());
  AddPointJacobian(system, marker_a(), a, k.p_WA_W, 1.0, &k);
  AddPointJacobian(system, marker_b(), b, k.p_WB_W, -1.0, &k);
  return {k};
}

SpherePlaneUnilateral::SpherePlaneUnilateral(std::string name, MarkerRef sphere, MarkerRef plane, double radius,
                                             UnilateralLaw law)
    : ShapePairUnilateral(std::move(name), std::move(sphere), std::move(plane), law), radius_(radius) {
  CheckRadius(this->name(), "radius [m]", radius_);
}

UnilateralContactKinematics SpherePlaneUnilateral::Geometry(const MarkerKinematics& a, const MarkerKinematics& b) const {
  return FromPointContact(contact::SpherePlane({a.p_WM_W, radius_}, {b.p_WM_W, b.R_WM.col(2)}));
}

SphereSphereUnilateral::SphereSphereUnilateral(std::string name, MarkerRef sphere1, MarkerRef sphere2, double radius1,
                                               double radius2, UnilateralLaw law)
    : ShapePairUnilateral(std::move(name), std::move(sphere1), std::move(sphere2), law),
      radius1_(radius1), radius2_(radius2) {
  CheckRadius(this->name(), "radius1 [m]", radius1_);
  CheckRadius(this->name(), "radius2 [m]", radius2_);
}

UnilateralContactKinematics SphereSphereUnilateral::Geometry(const MarkerKinematics& a,
                                                             const MarkerKinematics& b) const {
  return FromPointContact(contact::SphereSphere({a.p_WM_W, radius1_}, {b.p_WM_W, radius2_}));
}

BoxPlaneUnilateral::BoxPlaneUnilateral(std::string name, MarkerRef box, const Eigen::Vector3d& half_extents,
                                       MarkerRef plane, UnilateralLaw law)
    : UnilateralContact(std::move(name), std::move(box), std::move(plane), law) {
  if (!(half_extents.minCoeff() > 0.0) || !half_extents.allFinite()) {
    throw InputError(fmt::format("contact '{}': the box's half extents [m] ({:g}, {:g}, {:g}) must be finite and > 0",
                                 this->name(), half_extents.x(), half_extents.y(), half_extents.z()));
  }
  corners_C_ = contact::BoxCorners(half_extents);
}

std::vector<UnilateralContactKinematics> BoxPlaneUnilateral::EvaluatePoints(const MultibodySystem& system,
                                                                            const ConstVectorRef& y) const {
  return PointsOnPlane(system, y, corners_C_);
}

CylinderPlaneUnilateral::CylinderPlaneUnilateral(std::string name, MarkerRef cylinder, double radius, double length,
                                                 MarkerRef plane, UnilateralLaw law)
    : UnilateralContact(std::move(name), std::move(cylinder), std::move(plane), law),
      radius_(radius),
      half_length_(0.5 * length) {
  if (!(radius > 0.0) || !std::isfinite(radius) || !(length > 0.0) || !std::isfinite(length)) {
    throw InputError(fmt::format("contact '{}': the cylinder's radius {:g} m and length {:g} m must be finite and > 0",
                                 this->name(), radius, length));
  }
}

std::vector<UnilateralContactKinematics> CylinderPlaneUnilateral::EvaluatePoints(const MultibodySystem& system,
                                                                                 const ConstVectorRef& y) const {
  const MarkerKinematics cylinder = system.MarkerState(marker_a(), y), plane = system.MarkerState(marker_b(), y);
  const Eigen::Vector3d n_C = cylinder.R_WM.transpose() * plane.R_WM.col(2);
  return PointsOnPlane(system, y, contact::CylinderSupportPoints(radius_, half_length_, n_C));
}

}  // namespace flexmbs::mbs
