#pragma once
// A spur gear pair on tangentially movable elastic teeth (docs/contact.md, "Movable teeth"; the
// thesis' chapter 7) as a force element with states: every tooth of both wheels a massless tooth
// turned about its wheel's axis by its deflection d / r_b, c_t d' + k_t d = Q, its deflection a
// state integrated with the system (docs/mbs.md, "Force elements with states"). The tooth pairs
// touch on the moved teeth through the flanks' linearised flattening k_H; the wheels take the
// pairs' loads at their contact points (a massless tooth passes its load on whole).

#include <Eigen/Core>
#include <string>
#include <vector>

#include "contact/gears/gear_mesh.h"
#include "contact/gears/movable_teeth.h"
#include "contact/gears/spur_gear.h"
#include "mbs/compliant_contact.h"
#include "mbs/force_element.h"
#include "mbs/gear_mesh_element.h"
#include "mbs/gear_pair_frame.h"
#include "mbs/marker_ref.h"

namespace flexmbs::mbs {

/// The pair between markers W1 and W2 as in mbs/gear_pair_frame.h. States s = [d1_0 .. d1_{z1-1},
/// d2_0 .. d2_{z2-1}] [m]: tooth k of wheel i turned by d_ik / r_bi about +z relative to its wheel
/// (0 at the start). Each tooth pair of contact::MeshingToothPairs has the moved gap
/// g' = g + lever1 d1 + lever2 d2 (contact::PairLevers) and, where it penetrates (delta = -g' > 0),
/// the force F = k_H delta (contact::FlatteningStiffness, no damping: the teeth's dashpots hold
/// it) on wheel 2 along n_12 at the contact point and the opposite on wheel 1; tooth i takes
/// Q_i = sum lever_i F, and d_i' = (Q_i - k_t d_i) / c_t with k_t = contact::ToothStiffness at
/// the roll of the pair it is in, at the pitch point (contact::PitchRoll) out of mesh. Axes that
/// stay parallel are assumed, as in SpurGearContact.
class MovableTeethGearContact final : public GearMeshElement {
 public:
  /// `pair` from contact::MakeGearPair; InputError (one line) from contact::CheckMovableTeeth.
  MovableTeethGearContact(std::string name, MarkerRef wheel1, MarkerRef wheel2, contact::GearPair pair,
                          contact::MovableTeeth teeth);
  const std::string& name() const override { return name_; }
  Eigen::Index num_states() const override;
  void AddForces(double t, const MultibodySystem& system, const ConstVectorRef& y,
                 Eigen::Ref<Eigen::VectorXd> h) const override;
  /// The flanks' k_H delta^2 / 2 per pair and the teeth's k_t d^2 / 2 [J].
  double PotentialEnergy(double t, const MultibodySystem& system, const ConstVectorRef& y) const override;
  /// Each pair's CompliantContact Jacobian with the law k_H delta (the wheels' motion).
  void AddForceJacobian(double t, const MultibodySystem& system, const ConstVectorRef& y,
                        Eigen::Ref<Eigen::MatrixXd> dh_dx, Eigen::Ref<Eigen::MatrixXd> dh_du) const override;
  void StateDerivatives(double t, const MultibodySystem& system, const ConstVectorRef& y,
                        Eigen::Ref<Eigen::VectorXd> s_dot) const override;
  /// With w the generalised force of a unit normal load at a pair's contact point (delta' =
  /// -w^T u): dh/dd_j = -k_H lever_j w, dd_i'/dx = -lever_i k_H w^T / c_t, dd_i'/dd_j =
  /// -(lever_i k_H lever_j + k_t delta_ij) / c_t; the levers' and k_t's change with the angles left out.
  void AddStateJacobian(double t, const MultibodySystem& system, const ConstVectorRef& y,
                        ElementStateJacobian& jacobian) const override;
  bool is_contact() const override { return true; }
  std::vector<ContactLoad> ContactLoads(double t, const MultibodySystem& system,
                                        const ConstVectorRef& y) const override;

  /// A tooth pair that can mesh at a state, on the moved teeth.
  struct MovedPair {
    contact::ToothPair pair;       ///< gap: the moved one
    contact::ToothLevers levers;
    Eigen::Index state1 = 0, state2 = 0;  ///< its teeth's states in s
    double stiffness = 0.0;        ///< k_H [N/m] of a pair in contact (0 apart)
    double force = 0.0;            ///< F [N], 0 apart
    ContactPoint point;
  };
  /// The frame and every tooth pair that can mesh at state y.
  struct Mesh {
    GearPairFrame frame;
    std::vector<MovedPair> pairs;
  };
  Mesh Evaluate(double t, const MultibodySystem& system, const ConstVectorRef& y) const;
  /// Each tooth's stiffness k_t [N/m] in `mesh` (size num_states()).
  Eigen::VectorXd ToothStiffnesses(const Mesh& mesh) const;
  /// The mesh at state y (GearMeshElement::Readout): the moved pairs, their forces, and the
  /// teeth's deflections as the gap's shares lever_i d_i, the flattening F / k_H.
  Readout Read(double t, const MultibodySystem& system, const ConstVectorRef& y) const override;
  const contact::GearPair& pair() const override { return pair_; }
  const contact::MovableTeeth& teeth() const { return teeth_; }

 private:
  /// The pair's law k_H delta between wheel 2 (body A) and wheel 1.
  CompliantContact PairContact(const MovedPair& p) const;

  std::string name_;
  MarkerRef wheel1_, wheel2_;
  contact::GearPair pair_;
  contact::MovableTeeth teeth_;
};

}  // namespace flexmbs::mbs
