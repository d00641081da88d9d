#pragma once
// Compliant contact on a reduced body's contact surface (docs/contact.md, "Flexible bodies"): a
// sphere against the surface's deformed faces, and every vertex against a plane, with any normal
// law of contact/laws (Hertz for a sphere on a flat, a penalty per vertex) and optional
// regularised friction, evaluated by mbs/compliant_contact.h with the surface point's modal
// velocity.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "mbs/compliant_contact.h"
#include "mbs/contact_force.h"
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

  bool is_contact() const override { return true; }
  /// The load at the contact point while in contact.
  std::vector<ContactLoad> ContactLoads(double t, const MultibodySystem& system, const ConstVectorRef& y) const override;

 private:
  std::string name_;
  MarkerRef sphere_, origin_;
  double radius_;
  sid::ContactSurface surface_;
  Eigen::Index num_modes_;
  CompliantContact contact_;
};

/// Every vertex V of surface S of flexible body A against the plane through the origin of marker
/// P (body B) with outward normal n = P's z axis, each a compliant contact point: penetration
/// delta_V = -n . (p_WV_W - p_WP_W), the law's force F_N(delta_V, delta_V') n + F_T at the vertex
/// on A (its frame and modes: mbs/surface_state.h), the opposite on B. The penalty counterpart of
/// SurfacePlaneUnilateral.
class SurfacePlaneContact final : public CompliantPointsContact {
 public:
  /// `origin` is A's body-frame marker, `surface` its contact surface with phi over A's kept
  /// modes (3 V x num_modes). InputError naming the element otherwise.
  SurfacePlaneContact(std::string name, MarkerRef origin, sid::ContactSurface surface, Eigen::Index num_modes,
                      MarkerRef plane, CompliantContactLaw law);

  /// A's body-frame marker (its body is the reduced body), the plane's marker, A's surface.
  const MarkerRef& origin() const { return origin_; }
  const MarkerRef& plane() const { return plane_; }
  const sid::ContactSurface& surface() const { return surface_; }

 private:
  /// Every vertex's contact point at y.
  std::vector<ContactPoint> Points(const MultibodySystem& system, const ConstVectorRef& y) const override;

  MarkerRef origin_, plane_;
  sid::ContactSurface surface_;
  Eigen::Index num_modes_;
};

}  // namespace flexmbs::mbs
