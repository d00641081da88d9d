#include "mbs/spur_gear_contact.h"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "core/error.h"
#include "mbs/multibody_system.h"
#include "mbs/simulation_error.h"

namespace flexmbs::mbs {
namespace {

/// The cosine of the largest angle between the wheels' axes the planar mesh accepts (8.1 deg).
constexpr double kParallelAxes = 0.99;

}  // namespace

struct SpurGearContact::Frame {
  MarkerKinematics wheel1, wheel2;
  double centre_distance = 0.0;
  Eigen::Vector3d x_W, y_W;       ///< the pair frame's x (W1 -> W2) and y axes in W
  Eigen::Vector3d p_WO_W;         ///< its origin: W1's origin moved half the axial offset
  double phi1 = 0.0, phi2 = 0.0;  ///< the wheels' angles from x about W1's z [rad]
};

SpurGearContact::SpurGearContact(std::string name, MarkerRef wheel1, MarkerRef wheel2,
                                 contact::GearPair pair, contact::MeshLaw law)
    : name_(std::move(name)),
      wheel1_(std::move(wheel1)),
      wheel2_(std::move(wheel2)),
      pair_(std::move(pair)),
      law_(std::move(law)) {}

CompliantContact SpurGearContact::PairLaw(const contact::ToothPair& tp) const {
  return CompliantContact(CompliantContactLaw{law_.PairLaw(tp), {}}, wheel2_, wheel1_);
}

SpurGearContact::Frame SpurGearContact::PairFrame(double t, const MultibodySystem& system,
                                                  const ConstVectorRef& y) const {
  Frame f;
  f.wheel1 = system.MarkerState(wheel1_, y);
  f.wheel2 = system.MarkerState(wheel2_, y);
  const Eigen::Vector3d z = f.wheel1.R_WM.col(2);
  const double axes_cosine = z.dot(f.wheel2.R_WM.col(2));
  if (!(axes_cosine > kParallelAxes)) {
    throw SimulationError(
        t, fmt::format("t = {:.9g} s: spur gear contact '{}': the wheels' axes (the markers' z) "
                       "are {:.3g} deg apart; they must be parallel and point the same way",
                       t, name_,
                       std::acos(std::clamp(axes_cosine, -1.0, 1.0)) * 180.0 / std::numbers::pi));
  }
  const Eigen::Vector3d d = f.wheel2.p_WM_W - f.wheel1.p_WM_W;
  const Eigen::Vector3d in_plane = d - z.dot(d) * z;
  f.centre_distance = in_plane.norm();
  if (!(f.centre_distance > pair_.gear1.base_radius + pair_.gear2.base_radius)) {
    throw SimulationError(
        t,
        fmt::format("t = {:.9g} s: spur gear contact '{}': the axes are {:.6g} m apart, within the "
                    "sum of the base radii",
                    t, name_, f.centre_distance));
  }
  f.x_W = in_plane / f.centre_distance;
  f.y_W = z.cross(f.x_W);
  f.p_WO_W = f.wheel1.p_WM_W + 0.5 * z.dot(d) * z;
  const auto angle = [&](const MarkerKinematics& m) {
    const Eigen::Vector3d x = m.R_WM.col(0);
    return std::atan2(x.dot(f.y_W), x.dot(f.x_W));
  };
  f.phi1 = angle(f.wheel1);
  f.phi2 = angle(f.wheel2);
  return f;
}

std::vector<contact::ToothPair> SpurGearContact::ToothPairs(double t, const MultibodySystem& system,
                                                            const ConstVectorRef& y) const {
  const Frame f = PairFrame(t, system, y);
  return contact::MeshingToothPairs(pair_, f.centre_distance, f.phi1, f.phi2);
}

ContactPoint SpurGearContact::Point(const Frame& f, const contact::ToothPair& tp) {
  ContactPoint point;
  point.a = f.wheel2;
  point.b = f.wheel1;
  point.n_W = tp.n_12.x() * f.x_W + tp.n_12.y() * f.y_W;
  point.p_Wc_W = f.p_WO_W + tp.p_O1C.x() * f.x_W + tp.p_O1C.y() * f.y_W;
  point.penetration = -tp.gap;
  return point;
}

std::vector<SpurGearContact::PairContact> SpurGearContact::InContact(
    const Frame& f, const std::vector<contact::ToothPair>& pairs) const {
  std::vector<PairContact> contacts;
  for (const contact::ToothPair& tp : pairs) {
    if (tp.gap < 0.0) contacts.push_back({tp, Point(f, tp), PairLaw(tp)});
  }
  return contacts;
}

std::vector<SpurGearContact::PairContact> SpurGearContact::Contacts(double t,
                                                                    const MultibodySystem& system,
                                                                    const ConstVectorRef& y) const {
  const Frame f = PairFrame(t, system, y);
  return InContact(f, contact::MeshingToothPairs(pair_, f.centre_distance, f.phi1, f.phi2));
}

SpurGearContact::Readout SpurGearContact::Read(double t, const MultibodySystem& system,
                                               const ConstVectorRef& y) const {
  const Frame f = PairFrame(t, system, y);
  Readout readout;
  readout.centre_distance = f.centre_distance;
  readout.phi1 = f.phi1;
  readout.phi2 = f.phi2;
  const std::vector<contact::ToothPair> all =
      contact::MeshingToothPairs(pair_, f.centre_distance, f.phi1, f.phi2);
  const std::vector<PairContact> contacts = InContact(f, all);
  const std::vector<double> forces = NormalForces(contacts);
  std::size_t next = 0;  // the next contact, in the order of the pairs
  for (const contact::ToothPair& tp : all) {
    double force = 0.0;
    if (tp.gap < 0.0) {
      const ContactPoint& point = contacts[next].point;
      force = forces[next++];
      const Eigen::Vector3d f_W = force * point.n_W;  // on wheel 2; wheel 1 takes -f_W
      readout.torque1 += (point.p_Wc_W - f.wheel1.p_WM_W).cross(-f_W).dot(f.wheel1.R_WM.col(2));
      readout.torque2 += (point.p_Wc_W - f.wheel2.p_WM_W).cross(f_W).dot(f.wheel2.R_WM.col(2));
    }
    readout.pairs.push_back({tp, force});
    readout.deflections.push_back(law_.Deflection(tp, force));
  }
  return readout;
}

contact::MeshPairForces SpurGearContact::JointForces(
    const std::vector<PairContact>& contacts) const {
  std::vector<contact::ToothPair> pairs;
  std::vector<double> rates;
  for (const PairContact& c : contacts) {
    pairs.push_back(c.pair);
    rates.push_back(-c.point.n_W.dot(RelativeVelocity(c.point)));
  }
  return law_.ForcesWithDerivatives(pairs, rates);
}

std::vector<double> SpurGearContact::NormalForces(const std::vector<PairContact>& contacts) const {
  if (law_.joint()) return JointForces(contacts).force;
  std::vector<double> forces;
  for (const PairContact& c : contacts) forces.push_back(c.contact.NormalForce(c.point));
  return forces;
}

void SpurGearContact::AddPairLoad(const MultibodySystem& system, const ContactPoint& point,
                                  double force, Eigen::Ref<Eigen::VectorXd> h) const {
  const Eigen::Vector3d f_W = force * point.n_W;
  system.AddMarkerLoad(wheel2_, point.a, f_W, (point.p_Wc_W - point.a.p_WM_W).cross(f_W), h);
  system.AddMarkerLoad(wheel1_, point.b, -f_W, (point.p_Wc_W - point.b.p_WM_W).cross(-f_W), h);
}

void SpurGearContact::AddForces(double t, const MultibodySystem& system, const ConstVectorRef& y,
                                Eigen::Ref<Eigen::VectorXd> h) const {
  const std::vector<PairContact> contacts = Contacts(t, system, y);
  if (!law_.joint()) {
    for (const PairContact& c : contacts) c.contact.AddForces(system, c.point, h);
    return;
  }
  const std::vector<double> forces = JointForces(contacts).force;
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    if (forces[i] > 0.0) AddPairLoad(system, contacts[i].point, forces[i], h);
  }
}

double SpurGearContact::PotentialEnergy(double t, const MultibodySystem& system,
                                        const ConstVectorRef& y) const {
  const std::vector<PairContact> contacts = Contacts(t, system, y);
  if (law_.joint()) return JointForces(contacts).energy;
  double energy = 0.0;
  for (const PairContact& c : contacts) energy += c.contact.PotentialEnergy(c.point);
  return energy;
}

void SpurGearContact::AddForceJacobian(double t, const MultibodySystem& system,
                                       const ConstVectorRef& y, Eigen::Ref<Eigen::MatrixXd> dh_dx,
                                       Eigen::Ref<Eigen::MatrixXd> dh_du) const {
  const std::vector<PairContact> contacts = Contacts(t, system, y);
  if (!law_.joint()) {
    for (const PairContact& c : contacts) c.contact.AddForceJacobian(system, c.point, dh_dx, dh_du);
    return;
  }
  const contact::MeshPairForces mesh = JointForces(contacts);
  const auto n = static_cast<Eigen::Index>(contacts.size());
  Eigen::MatrixXd w = Eigen::MatrixXd::Zero(system.num_velocities(), n);
  for (Eigen::Index i = 0; i < n; ++i)
    AddPairLoad(system, contacts[static_cast<std::size_t>(i)].point, 1.0, w.col(i));
  dh_dx.noalias() -= w * mesh.d_delta * w.transpose();
  dh_du.noalias() -= w * mesh.d_rate * w.transpose();
}

std::vector<ContactLoad> SpurGearContact::ContactLoads(double t, const MultibodySystem& system,
                                                       const ConstVectorRef& y) const {
  const std::vector<PairContact> contacts = Contacts(t, system, y);
  const std::vector<double> forces = NormalForces(contacts);
  std::vector<ContactLoad> loads;
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const ContactPoint& p = contacts[i].point;
    if (forces[i] > 0.0) loads.push_back({0, p.p_Wc_W, p.n_W, forces[i] * p.n_W});
  }
  return loads;
}

double SpurGearContact::MeshForce(double t, const MultibodySystem& system,
                                  const ConstVectorRef& y) const {
  double force = 0.0;
  for (const double f : NormalForces(Contacts(t, system, y))) force += f;
  return force;
}

}  // namespace flexmbs::mbs
