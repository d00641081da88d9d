#pragma once
// The evaluation that every compliant contact force element shares (docs/mbs.md, "Seams for
// contact"): given one contact point between two markers' bodies, a normal law and optional
// regularised friction from contact/laws, the loads on both bodies and their Jacobian. The
// elements (mbs/contact_force.h) differ only in their geometry.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "contact/laws/friction.h"
#include "contact/laws/normal_law.h"
#include "core/error.h"
#include "mbs/body.h"
#include "mbs/contact_load.h"
#include "mbs/marker_ref.h"

namespace flexmbs::mbs {

class MultibodySystem;

/// A contact's constitutive model: the normal law and, optionally, regularised Coulomb friction
/// at the contact point.
struct CompliantContactLaw {
  contact::NormalLaw normal;                          ///< F_N(delta, delta') (contact/laws/normal_law.h)
  std::optional<contact::RegularisedCoulomb> friction;  ///< F_T(v_T, F_N); none: frictionless
};

/// Runs `build` (which makes a law or checks its parameters), prefixing an InputError's message
/// with "force element '<element>': ".
template <typename Build>
auto ForElement(const std::string& element, Build build) -> decltype(build()) {
  try {
    return build();
  } catch (const InputError& e) {
    throw InputError("force element '" + element + "': " + e.what());
  }
}

/// One contact point between body A (marker a) and body B (marker b) at a state, as an
/// element's geometry finds it.
struct ContactPoint {
  MarkerKinematics a, b;                                    ///< the two markers
  Eigen::Vector3d n_W = Eigen::Vector3d::UnitZ();           ///< unit normal from B to A: F_N n acts on A
  Eigen::Vector3d p_Wc_W = Eigen::Vector3d::Zero();         ///< the contact point c [m]
  double penetration = 0.0;                                 ///< delta [m] (> 0: in contact)
  /// dn/dd [1/m]: the normal's turning by a relative displacement d of A's material point at c
  /// against B's (sphere on sphere: (I - n n^T) / l; zero where n turns only with a body).
  Eigen::Matrix3d n_turning = Eigen::Matrix3d::Zero();
  /// Where an end is a point of a reduced body's contact surface (mbs/surface_state.h) and its
  /// marker the body frame: the point's velocity per modal velocity of that body, R sum_i w_i
  /// phi_i (3 x n) [m/q], and the modal share of its velocity [m/s]. Empty and zero where the end
  /// is a material point of its marker's frame.
  Eigen::Matrix3Xd modal_a, modal_b;
  Eigen::Vector3d modal_velocity_a_W = Eigen::Vector3d::Zero(), modal_velocity_b_W = Eigen::Vector3d::Zero();
};

/// The velocity of A's material point at the contact point relative to B's [m/s] in W, a surface
/// point's modal share included.
Eigen::Vector3d RelativeVelocity(const ContactPoint& point);

/// The loads of a law at a ContactPoint. With v_rel the velocity of A's material point at c
/// relative to B's (a surface point's modal share included), delta' = -n . v_rel and v_T = v_rel + delta' n (the slip), A carries
/// f = F_N(delta, delta') n + F_T(v_T, F_N) at c, and B carries -f at c.
class CompliantContact {
 public:
  /// The law between markers a (body A) and b (body B); either may be the ground.
  CompliantContact(CompliantContactLaw law, MarkerRef a, MarkerRef b);

  /// Adds both bodies' generalised forces at `point` to h (size num_velocities()).
  void AddForces(const MultibodySystem& system, const ContactPoint& point, Eigen::Ref<Eigen::VectorXd> h) const;
  /// Adds J_rel^T K J_rel to dh_du and dh_dx, J_rel the Jacobian of A's material point at c less
  /// B's (each marker's jacobian moved to c): K = df/dv_rel exactly (normal law and friction), and
  /// df/dd through delta, delta' and the normal's turning (ContactPoint::n_turning); left out in x:
  /// the lever arms' and the slip's change by a body's rotation (the load times that rotation).
  void AddForceJacobian(const MultibodySystem& system, const ContactPoint& point, Eigen::Ref<Eigen::MatrixXd> dh_dx,
                        Eigen::Ref<Eigen::MatrixXd> dh_du) const;
  /// Appends the load f on A at `point` to `loads` if the point is in contact (F_N > 0).
  void AppendLoad(const ContactPoint& point, std::vector<ContactLoad>* loads) const;
  /// The normal force F_N [N] at `point` (0 apart).
  double NormalForce(const ContactPoint& point) const { return Evaluate(point).normal.force; }
  /// The normal law's spring energy at `point` [J] (contact::ElasticEnergy).
  double PotentialEnergy(const ContactPoint& point) const;

  /// The law this contact evaluates.
  const CompliantContactLaw& law() const { return law_; }

 private:
  /// The relative velocity, the normal force and the friction at `point`.
  struct Loads {
    Eigen::Vector3d v_rel_W = Eigen::Vector3d::Zero();
    contact::NormalForce normal;
    contact::TangentialForce tangential;
  };
  Loads Evaluate(const ContactPoint& point) const;

  CompliantContactLaw law_;
  MarkerRef a_, b_;
};

}  // namespace flexmbs::mbs
