#include "mbs/contact_force.h"

#include <fmt/format.h>

#include <cmath>
#include <utility>

#include "contact/geometry/point_contact.h"
#include "core/error.h"
#include "mbs/multibody_system.h"
#include "mbs/simulation_error.h"

namespace flexmbs::mbs {
namespace {

double CheckedRadius(const std::string& element, std::string_view what, double radius) {
  if (!(radius > 0.0) || !std::isfinite(radius)) {
    throw InputError(fmt::format("force element '{}': {} {} must be finite and > 0", element, what, radius));
  }
  return radius;
}

}  // namespace

SpherePlaneContact::SpherePlaneContact(std::string name, MarkerRef sphere, MarkerRef plane, double radius,
                                       double stiffness, double damping, double exponent)
    : SpherePlaneContact(name, std::move(sphere), std::move(plane), CheckedRadius(name, "radius [m]", radius),
                         ForElement(name, [&] {
                           return CompliantContactLaw{contact::LinearLaw(stiffness, damping, exponent), {}};
                         })) {}

SpherePlaneContact::SpherePlaneContact(std::string name, MarkerRef sphere, MarkerRef plane, double radius,
                                       CompliantContactLaw law)
    : name_(std::move(name)), sphere_(std::move(sphere)), plane_(std::move(plane)),
      radius_(CheckedRadius(name_, "radius [m]", radius)), contact_(std::move(law), sphere_, plane_) {}

ContactPoint SpherePlaneContact::Geometry(const MultibodySystem& system, const ConstVectorRef& y) const {
  ContactPoint point;
  point.a = system.MarkerState(sphere_, y);
  point.b = system.MarkerState(plane_, y);
  const contact::PointContactKinematics kinematics =
      contact::SpherePlane({point.a.p_WM_W, radius_}, {point.b.p_WM_W, point.b.R_WM.col(2)});
  point.n_W = kinematics.n_W;
  point.penetration = -kinematics.g_N;
  point.p_Wc_W = kinematics.p_WA_W;  // the sphere's lowest point
  return point;
}

void SpherePlaneContact::AddForces(double /*t*/, const MultibodySystem& system, const ConstVectorRef& y,
                                   Eigen::Ref<Eigen::VectorXd> h) const {
  contact_.AddForces(system, Geometry(system, y), h);
}

double SpherePlaneContact::PotentialEnergy(double /*t*/, const MultibodySystem& system, const ConstVectorRef& y) const {
  return contact_.PotentialEnergy(Geometry(system, y));
}

void SpherePlaneContact::AddForceJacobian(double /*t*/, const MultibodySystem& system, const ConstVectorRef& y,
                                          Eigen::Ref<Eigen::MatrixXd> dh_dx, Eigen::Ref<Eigen::MatrixXd> dh_du) const {
  contact_.AddForceJacobian(system, Geometry(system, y), dh_dx, dh_du);
}

SphereSphereContact::SphereSphereContact(std::string name, MarkerRef sphere1, MarkerRef sphere2, double radius1,
                                         double radius2, CompliantContactLaw law)
    : name_(std::move(name)), sphere1_(std::move(sphere1)), sphere2_(std::move(sphere2)),
      radius1_(CheckedRadius(name_, "radius1 [m]", radius1)), radius2_(CheckedRadius(name_, "radius2 [m]", radius2)),
      contact_(std::move(law), sphere1_, sphere2_) {}

ContactPoint SphereSphereContact::Geometry(double t, const MultibodySystem& system, const ConstVectorRef& y) const {
  ContactPoint point;
  point.a = system.MarkerState(sphere1_, y);
  point.b = system.MarkerState(sphere2_, y);
  contact::PointContactKinematics kinematics;
  try {
    kinematics = contact::SphereSphere({point.a.p_WM_W, radius1_}, {point.b.p_WM_W, radius2_});
  } catch (const contact::DegenerateContactError&) {
    throw SimulationError(t, fmt::format("t = {:.9g} s: sphere-sphere contact '{}': the centres meet (no normal)", t, name_));
  }
  point.n_W = kinematics.n_W;
  point.penetration = -kinematics.g_N;
  point.p_Wc_W = 0.5 * (kinematics.p_WA_W + kinematics.p_WB_W);  // the middle of the overlap
  const double length = (point.a.p_WM_W - point.b.p_WM_W).norm();
  point.n_turning = (Eigen::Matrix3d::Identity() - point.n_W * point.n_W.transpose()) / length;
  return point;
}

void SphereSphereContact::AddForces(double t, const MultibodySystem& system, const ConstVectorRef& y,
                                    Eigen::Ref<Eigen::VectorXd> h) const {
  contact_.AddForces(system, Geometry(t, system, y), h);
}

double SphereSphereContact::PotentialEnergy(double t, const MultibodySystem& system, const ConstVectorRef& y) const {
  return contact_.PotentialEnergy(Geometry(t, system, y));
}

void SphereSphereContact::AddForceJacobian(double t, const MultibodySystem& system, const ConstVectorRef& y,
                                           Eigen::Ref<Eigen::MatrixXd> dh_dx, Eigen::Ref<Eigen::MatrixXd> dh_du) const {
  contact_.AddForceJacobian(system, Geometry(t, system, y), dh_dx, dh_du);
}

std::vector<ContactLoad> SpherePlaneContact::ContactLoads(double /*t*/, const MultibodySystem& system,
                                                          const ConstVectorRef& y) const {
  std::vector<ContactLoad> loads;
  contact_.AppendLoad(Geometry(system, y), &loads);
  return loads;
}

std::vector<ContactLoad> SphereSphereContact::ContactLoads(double t, const MultibodySystem& system,
                                                           const ConstVectorRef& y) const {
  std::vector<ContactLoad> loads;
  contact_.AppendLoad(Geometry(t, system, y), &loads);
  return loads;
}

CompliantPointsContact::CompliantPointsContact(std::string name, CompliantContactLaw law, MarkerRef a, MarkerRef b)
    : name_(std::move(name)), contact_(std::move(law), std::move(a), std::move(b)) {}

void CompliantPointsContact::AddForces(double, const MultibodySystem& system, const ConstVectorRef& y,
                                       Eigen::Ref<Eigen::VectorXd> h) const {
  for (const ContactPoint& point : Points(system, y)) contact_.AddForces(system, point, h);
}

double CompliantPointsContact::PotentialEnergy(double, const MultibodySystem& system, const ConstVectorRef& y) const {
  double energy = 0.0;
  for (const ContactPoint& point : Points(system, y)) energy += contact_.PotentialEnergy(point);
  return energy;
}

void CompliantPointsContact::AddForceJacobian(double, const MultibodySystem& system, const ConstVectorRef& y,
                                              Eigen::Ref<Eigen::MatrixXd> dh_dx,
                                              Eigen::Ref<Eigen::MatrixXd> dh_du) const {
  for (const ContactPoint& point : Points(system, y)) contact_.AddForceJacobian(system, point, dh_dx, dh_du);
}

std::vector<ContactLoad> CompliantPointsContact::ContactLoads(double, const MultibodySystem& system,
                                                              const ConstVectorRef& y) const {
  std::vector<ContactLoad> loads;
  for (const ContactPoint& point : Points(system, y)) contact_.AppendLoad(point, &loads);
  return loads;
}

double CompliantPointsContact::NormalForce(const MultibodySystem& system, const ConstVectorRef& y) const {
  double force = 0.0;
  for (const ContactPoint& point : Points(system, y)) force += contact_.NormalForce(point);
  return force;
}

BoxPlaneContact::BoxPlaneContact(std::string name, MarkerRef box, const Eigen::Vector3d& half_extents, MarkerRef plane,
                                 CompliantContactLaw law)
    : CompliantPointsContact(std::move(name), std::move(law), box, plane), box_(std::move(box)),
      plane_(std::move(plane)) {
  if (!(half_extents.minCoeff() > 0.0) || !half_extents.allFinite()) {
    throw InputError(fmt::format("force element '{}': the box's half extents [m] ({:g}, {:g}, {:g}) must be finite "
                                 "and > 0",
                                 this->name(), half_extents.x(), half_extents.y(), half_extents.z()));
  }
  corners_C_ = contact::BoxCorners(half_extents);
}

std::vector<ContactPoint> BoxPlaneContact::Points(const MultibodySystem& system, const ConstVectorRef& y) const {
  const MarkerKinematics box = system.MarkerState(box_, y), plane = system.MarkerState(plane_, y);
  std::vector<ContactPoint> points(corners_C_.size());
  for (std::size_t c = 0; c < corners_C_.size(); ++c) {
    ContactPoint& point = points[c];
    point.a = box;
    point.b = plane;
    point.n_W = plane.R_WM.col(2);
    point.p_Wc_W = box.p_WM_W + box.R_WM * corners_C_[c];
    point.penetration = -point.n_W.dot(point.p_Wc_W - plane.p_WM_W);
  }
  return points;
}

}  // namespace flexmbs::mbs
