#include "mbs/spur_gear_contact.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/error.h"
#include "mbs/multibody_system.h"

namespace flexmbs::mbs {
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

std::vector<contact::ToothPair> SpurGearContact::ToothPairs(double t, const MultibodySystem& system,
                                                            const ConstVectorRef& y) const {
  const GearPairFrame f = MeasureGearPairFrame(t, system, y, wheel1_, wheel2_, pair_, name_);
  return contact::MeshingToothPairs(pair_, f.centre_distance, f.phi1, f.phi2);
}

std::vector<SpurGearContact::PairContact> SpurGearContact::InContact(
    const GearPairFrame& f, const std::vector<contact::ToothPair>& pairs) const {
  std::vector<PairContact> contacts;
  for (const contact::ToothPair& tp : pairs) {
    if (tp.gap < 0.0) contacts.push_back({tp, GearContactPoint(f, tp, -tp.gap), PairLaw(tp)});
  }
  return contacts;
}

std::vector<SpurGearContact::PairContact> SpurGearContact::Contacts(double t,
                                                                    const MultibodySystem& system,
                                                                    const ConstVectorRef& y) const {
  const GearPairFrame f = MeasureGearPairFrame(t, system, y, wheel1_, wheel2_, pair_, name_);
  return InContact(f, contact::MeshingToothPairs(pair_, f.centre_distance, f.phi1, f.phi2));
}

SpurGearContact::Readout SpurGearContact::Read(double t, const MultibodySystem& system,
                                               const ConstVectorRef& y) const {
  const GearPairFrame f = MeasureGearPairFrame(t, system, y, wheel1_, wheel2_, pair_, name_);
  Readout readout;
  readout.centre_distance = f.centre_distance;
  readout.phi1 = f.phi1;
  readout.phi2 = f.phi2;
  const std::vector<contact::ToothPair> all =
      contact::MeshingToothPairs(pair_, f.centre_distance, f.phi1, f.phi2);
  const std::vector<PairContact> contacts = InContact(f, all);
  const std::vector<double> forces = NormalForces(contacts);
  std::vector<contact::ToothPair> touching;
  for (const PairContact& c : contacts) touching.push_back(c.pair);
  const std::vector<contact::ToothPairDeflection> bent = law_.Deflections(touching, forces);
  std::size_t next = 0;  // the next contact, in the order of the pairs
  for (const contact::ToothPair& tp : all) {
    double force = 0.0;
    contact::ToothPairDeflection deflection;
    if (tp.gap < 0.0) {
      AddPairTorques(f, contacts[next].point, forces[next], &readout);
      force = forces[next];
      deflection = bent[next++];
    }
    readout.pairs.push_back({tp, force});
    readout.deflections.push_back(deflection);
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

void SpurGearContact::AddForces(double t, const MultibodySystem& system, const ConstVectorRef& y,
                                Eigen::Ref<Eigen::VectorXd> h) const {
  const std::vector<PairContact> contacts = Contacts(t, system, y);
  if (!law_.joint()) {
    for (const PairContact& c : contacts) c.contact.AddForces(system, c.point, h);
    return;
  }
  const std::vector<double> forces = JointForces(contacts).force;
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    if (forces[i] > 0.0) AddGearPairLoad(system, wheel1_, wheel2_, contacts[i].point, forces[i], h);
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
    AddGearPairLoad(system, wheel1_, wheel2_, contacts[static_cast<std::size_t>(i)].point, 1.0, w.col(i));
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
