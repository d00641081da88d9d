#pragma once
// Compliant contact on a reduced body's contact surface (docs/contact.md, "Flexible bodies"): a
// sphere against the surface's deformed faces, with any normal law of contact/laws (Hertz for a
// sphere on a flat) and optional regularised friction, evaluated by mbs/compliant_contact.h with
// the surface point's modal velocity.

#include <Eigen/Core>
#include <string>

#include "mbs/compliant_contact.h"
#include "mbs/force_element.h"
#include "mbs/marker_ref.h"
#include "sid/reduced_body.h"

namespace flexmbs::mbs {

/// A sphere of radius r [m] centred on marker S (body A) against surface S of flexible body B:
/// the surface point c nearest the centre (contact::SphereMesh on the deformed faces,
/// mbs/surface_state.h), penetration delta = -g_N, normal n from the surface to the sphere. The
/// sphere takes F_N(delta, delta') n + F_T at c, the surface point the opposite, which loads
/// B's frame at c and its modes through R sum_i w_i phi_i (CompliantContact). The normal's
/// turning with the surface is left out of the Jacobian (it turns with the body only).
class SphereSurfaceContact final : public ForceElement {
 public:
  /// radius > 0 [m]; `origin` is B's body-frame marker, `surface` its contact surface with phi
  /// over B's kept modes (3 V x num_modes). InputError naming the element otherwise.
  SphereSurfaceContact(std::string name, MarkerRef sphere, double radius, MarkerRef origin, sid::ContactSurface surface,
                       Eigen::Index num_modes, CompliantContactLaw law);

  const std::string& name() const override { return name_; }
  void AddForces(double t, const MultibodySystem& system, const ConstVectorRef& y,
                 Eigen::Ref<Eigen::VectorXd> h) const override;
  double PotentialEnergy(double t, const MultibodySystem& system, const ConstVectorRef& y) const override;
  /// CompliantContact::AddForceJacobian with the surface point's modal columns.
  void AddForceJacobian(double t, const MultibodySystem& system, const ConstVectorRef& y,
                        Eigen::Ref<Eigen::MatrixXd> dh_dx, Eigen::Ref<Eigen::MatrixXd> dh_du) const override;
  /// The normal force F_N [N] at (t, y): 0 apart.
  double NormalForce(double t, const MultibodySystem& system, const ConstVectorRef& y) const;
  /// The contact point at (t, y); SimulationError at t where the centre lies on an edge.
  ContactPoint Geometry(double t, const MultibodySystem& system, const ConstVectorRef& y) const;

  const MarkerRef& sphere() const { return sphere_; }
  /// The surface's body frame marker (its body is the reduced body).
  const MarkerRef& origin() const { return origin_; }
  const sid::ContactSurface& surface() const { return surface_; }
  const CompliantContactLaw& law() const { return contact_.law(); }

 private:

  std::string name_;
  MarkerRef sphere_, origin_;
  double radius_;
  sid::ContactSurface surface_;
  Eigen::Index num_modes_;
  CompliantContact contact_;
};

}  // namespace flexmbs::mbs
