#include "mbs/movable_teeth_gear_contact.h"

#include <array>
#include <utility>

#include "mbs/multibody_system.h"

namespace flexmbs::mbs {

MovableTeethGearContact::MovableTeethGearContact(std::string name, MarkerRef wheel1, MarkerRef wheel2,
                                                 contact::GearPair pair, contact::MovableTeeth teeth)
    : name_(std::move(name)),
      wheel1_(std::move(wheel1)),
      wheel2_(std::move(wheel2)),
      pair_(std::move(pair)),
      teeth_(std::move(teeth)) {
  contact::CheckMovableTeeth(teeth_);
}

Eigen::Index MovableTeethGearContact::num_states() const {
  return pair_.gear1.spec.teeth + pair_.gear2.spec.teeth;
}

MovableTeethGearContact::Mesh MovableTeethGearContact::Evaluate(double t, const MultibodySystem& system,
                                                                const ConstVectorRef& y) const {
  Mesh mesh;
  mesh.frame = MeasureGearPairFrame(t, system, y, wheel1_, wheel2_, pair_, name_);
  const auto d = system.ElementStates(y, *this);
  const double a = mesh.frame.centre_distance;
  for (const contact::ToothPair& tp : contact::MeshingToothPairs(pair_, a, mesh.frame.phi1, mesh.frame.phi2)) {
    MovedPair p;
    p.pair = tp;
    p.levers = contact::PairLevers(pair_, a, tp);
    p.state1 = tp.tooth1;
    p.state2 = pair_.gear1.spec.teeth + tp.tooth2;
    p.pair.gap += p.levers.lever1 * d(p.state1) + p.levers.lever2 * d(p.state2);
    if (p.pair.gap < 0.0) {  // Weber's logarithms only for the pairs in contact
      p.stiffness = contact::FlatteningStiffness(teeth_, pair_, tp);
      p.force = -p.stiffness * p.pair.gap;
    }
    p.point = GearContactPoint(mesh.frame, p.pair, -p.pair.gap);
    mesh.pairs.push_back(std::move(p));
  }
  return mesh;
}

Eigen::VectorXd MovableTeethGearContact::ToothStiffnesses(const Mesh& mesh) const {
  const int z1 = pair_.gear1.spec.teeth;
  const double pitch = contact::PitchRoll(pair_, mesh.frame.centre_distance);
  Eigen::VectorXd k(num_states());
  for (Eigen::Index i = 0; i < k.size(); ++i) k(i) = contact::ToothStiffness(teeth_, pair_, i < z1 ? 1 : 2, pitch);
  for (const MovedPair& p : mesh.pairs) {
    if (p.force <= 0.0) continue;
    k(p.state1) = contact::ToothStiffness(teeth_, pair_, 1, p.pair.roll1);
    k(p.state2) = contact::ToothStiffness(teeth_, pair_, 2, p.pair.roll2);
  }
  return k;
}

CompliantContact MovableTeethGearContact::PairContact(const MovedPair& p) const {
  return CompliantContact(CompliantContactLaw{contact::LinearLaw(p.stiffness, 0.0), {}}, wheel2_, wheel1_);
}

void MovableTeethGearContact::AddForces(double t, const MultibodySystem& system, const ConstVectorRef& y,
                                        Eigen::Ref<Eigen::VectorXd> h) const {
  for (const MovedPair& p : Evaluate(t, system, y).pairs) {
    if (p.force > 0.0) PairContact(p).AddForces(system, p.point, h);
  }
}

double MovableTeethGearContact::PotentialEnergy(double t, const MultibodySystem& system,
                                                const ConstVectorRef& y) const {
  const Mesh mesh = Evaluate(t, system, y);
  double energy = 0.0;
  for (const MovedPair& p : mesh.pairs) energy += 0.5 * p.force * p.point.penetration;
  const auto d = system.ElementStates(y, *this);
  energy += 0.5 * d.dot(ToothStiffnesses(mesh).cwiseProduct(d));
  return energy;
}

void MovableTeethGearContact::AddForceJacobian(double t, const MultibodySystem& system, const ConstVectorRef& y,
                                               Eigen::Ref<Eigen::MatrixXd> dh_dx,
                                               Eigen::Ref<Eigen::MatrixXd> dh_du) const {
  for (const MovedPair& p : Evaluate(t, system, y).pairs) {
    if (p.force > 0.0) PairContact(p).AddForceJacobian(system, p.point, dh_dx, dh_du);
  }
}

void MovableTeethGearContact::StateDerivatives(double t, const MultibodySystem& system, const ConstVectorRef& y,
                                               Eigen::Ref<Eigen::VectorXd> s_dot) const {
  const Mesh mesh = Evaluate(t, system, y);
  s_dot = -ToothStiffnesses(mesh).cwiseProduct(system.ElementStates(y, *this));
  for (const MovedPair& p : mesh.pairs) {
    s_dot(p.state1) += p.levers.lever1 * p.force;
    s_dot(p.state2) += p.levers.lever2 * p.force;
  }
  s_dot /= teeth_.damping;
}

void MovableTeethGearContact::AddStateJacobian(double t, const MultibodySystem& system, const ConstVectorRef& y,
                                               ElementStateJacobian& jacobian) const {
  const Mesh mesh = Evaluate(t, system, y);
  const double c = teeth_.damping;
  jacobian.ds_ds.diagonal() -= ToothStiffnesses(mesh) / c;
  for (const MovedPair& p : mesh.pairs) {
    if (p.force <= 0.0) continue;
    Eigen::VectorXd w = Eigen::VectorXd::Zero(system.num_velocities());
    AddGearPairLoad(system, wheel1_, wheel2_, p.point, 1.0, w);
    const std::array<std::pair<Eigen::Index, double>, 2> teeth{std::pair{p.state1, p.levers.lever1},
                                                               std::pair{p.state2, p.levers.lever2}};
    for (const auto& [i, lever_i] : teeth) {
      jacobian.dh_ds.col(i) -= p.stiffness * lever_i * w;
      jacobian.ds_dx.row(i) -= lever_i * p.stiffness / c * w.transpose();
      for (const auto& [j, lever_j] : teeth) jacobian.ds_ds(i, j) -= lever_i * p.stiffness * lever_j / c;
    }
  }
}

MovableTeethGearContact::Readout MovableTeethGearContact::Read(double t, const MultibodySystem& system,
                                                               const ConstVectorRef& y) const {
  const Mesh mesh = Evaluate(t, system, y);
  const auto d = system.ElementStates(y, *this);
  Readout readout;
  readout.centre_distance = mesh.frame.centre_distance;
  readout.phi1 = mesh.frame.phi1;
  readout.phi2 = mesh.frame.phi2;
  for (const MovedPair& p : mesh.pairs) {
    readout.pairs.push_back({p.pair, p.force});
    readout.deflections.push_back({p.levers.lever1 * d(p.state1), p.levers.lever2 * d(p.state2),
                                   p.force > 0.0 ? p.force / p.stiffness : 0.0});
    if (p.force > 0.0) AddPairTorques(mesh.frame, p.point, p.force, &readout);
  }
  return readout;
}

std::vector<ContactLoad> MovableTeethGearContact::ContactLoads(double t, const MultibodySystem& system,
                                                               const ConstVectorRef& y) const {
  std::vector<ContactLoad> loads;
  for (const MovedPair& p : Evaluate(t, system, y).pairs) {
    if (p.force > 0.0) PairContact(p).AppendLoad(p.point, &loads);
  }
  return loads;
}

}  // namespace flexmbs::mbs
