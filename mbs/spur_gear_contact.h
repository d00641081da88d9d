#pragma once
// A rigid involute spur gear pair between two markers as a compliant force element (docs/mbs.md,
// "Seams for contact"; docs/contact.md, "Spur gears"): contact/gears finds the tooth pairs and
// their gaps, mbs/compliant_contact.h loads both bodies at each pair's contact point.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "contact/gears/gear_mesh.h"
#include "contact/gears/gear_mesh_force.h"
#include "contact/gears/spur_gear.h"
#include "mbs/compliant_contact.h"
#include "mbs/force_element.h"
#include "mbs/gear_mesh_element.h"
#include "mbs/gear_pair_frame.h"
#include "mbs/marker_ref.h"

namespace flexmbs::mbs {

/// Wheel 1 on marker W1, wheel 2 on marker W2 (either may be the ground) in the pair frame of
/// mbs/gear_pair_frame.h. Every tooth pair of contact::MeshingToothPairs with a penetration
/// -g > 0 is a contact point in the middle of its two flank points, half way between the two
/// markers' planes, with normal n_12 (wheel 2 takes F n_12): CompliantContact with the tooth
/// pair's law (contact::MeshLaw: constant, or of massless elastic teeth at the pair's place on the
/// path) on the relative velocity of the two wheels' material points there, which is the gap's
/// rate. A joint law (contact::MeshLaw::joint: teeth coupled through the rims, or the flattening
/// at each pair's load) takes all pairs in contact together (MeshLaw::ForcesWithDerivatives on
/// their penetrations and rates) and loads each pair's point with its force. Axes that stay
/// parallel are assumed; the Jacobian leaves out the line of action's turning with moving axes
/// and the tables' change along the path. Throws SimulationError as MeasureGearPairFrame.
class SpurGearContact final : public GearMeshElement {
 public:
  /// `pair` from contact::MakeGearPair, `law` a contact::ToothPairLaw or an elastic MeshLaw (any:
  /// its InputErrors come from its constructor).
  SpurGearContact(std::string name, MarkerRef wheel1, MarkerRef wheel2, contact::GearPair pair,
                  contact::MeshLaw law);
  const std::string& name() const override { return name_; }
  void AddForces(double t, const MultibodySystem& system, const ConstVectorRef& y,
                 Eigen::Ref<Eigen::VectorXd> h) const override;
  double PotentialEnergy(double t, const MultibodySystem& system,
                         const ConstVectorRef& y) const override;
  /// CompliantContact::AddForceJacobian of every tooth pair in contact; for a joint law, with
  /// w_i pair i's generalised force per unit normal force (both wheels at its contact point),
  /// dh/dx -= sum_ij w_i K_ij w_j^T and dh/du -= sum_ij w_i D_ij w_j^T
  /// (contact::MeshPairForces: the cross terms of the pairs in mesh; d delta_i = -w_i^T dx,
  /// delta_i' = -w_i^T u).
  void AddForceJacobian(double t, const MultibodySystem& system, const ConstVectorRef& y,
                        Eigen::Ref<Eigen::MatrixXd> dh_dx,
                        Eigen::Ref<Eigen::MatrixXd> dh_du) const override;

  bool is_contact() const override { return true; }
  /// Each tooth pair's load on wheel 2 at its contact point (ParaView's contact points).
  std::vector<ContactLoad> ContactLoads(double t, const MultibodySystem& system,
                                        const ConstVectorRef& y) const override;

  /// The sum of the tooth pairs' normal forces [N] at time t [s] and state y: the mesh force along
  /// the lines of action (wheel 2 pushed along the driving side's n_12).
  double MeshForce(double t, const MultibodySystem& system, const ConstVectorRef& y) const;
  /// The tooth pairs that can mesh at state y (gaps of both signs), with the current a and angles.
  std::vector<contact::ToothPair> ToothPairs(double t, const MultibodySystem& system,
                                             const ConstVectorRef& y) const;
  /// The mesh at state y (GearMeshElement::Readout; the elastic teeth's deflections
  /// contact::MeshLaw::Deflections' of the pairs in contact: a coupled tooth's with the rim's share
  /// of the other pair's load).
  Readout Read(double t, const MultibodySystem& system, const ConstVectorRef& y) const override;
  const contact::GearPair& pair() const override { return pair_; }
  /// The tooth pairs' laws.
  const contact::MeshLaw& law() const { return law_; }

 private:
  /// A tooth pair in contact: its point and the contact evaluating its law.
  struct PairContact {
    contact::ToothPair pair;
    ContactPoint point;
    CompliantContact contact;
  };
  /// The pairs of `pairs` in contact (penetration > 0) in frame `f`.
  std::vector<PairContact> InContact(const GearPairFrame& f,
                                     const std::vector<contact::ToothPair>& pairs) const;
  /// The tooth pairs in contact (penetration > 0).
  std::vector<PairContact> Contacts(double t, const MultibodySystem& system,
                                    const ConstVectorRef& y) const;
  /// The compliant contact of tooth pair `tp` (wheel 2 as body A).
  CompliantContact PairLaw(const contact::ToothPair& tp) const;
  /// The joint law's forces and derivatives of `contacts` (MeshLaw::ForcesWithDerivatives at
  /// their penetrations and rates -n . v_rel).
  contact::MeshPairForces JointForces(const std::vector<PairContact>& contacts) const;
  /// Each contact's normal force [N]: its CompliantContact's, or the joint law's.
  std::vector<double> NormalForces(const std::vector<PairContact>& contacts) const;
  std::string name_;
  MarkerRef wheel1_, wheel2_;
  contact::GearPair pair_;
  contact::MeshLaw law_;
};

}  // namespace flexmbs::mbs
