#pragma once
// Compliant contact force elements (docs/mbs.md, "Seams for contact"): spheres against a plane
// and against each other, with any normal law of contact/laws and optional regularised friction,
// all evaluated by mbs/compliant_contact.h. Each element here owns its geometry only.

#include <Eigen/Core>
#include <string>

#include "mbs/compliant_contact.h"
#include "mbs/force_element.h"
#include "mbs/marker_ref.h"

namespace flexmbs::mbs {

/// A sphere of radius r [m] centred on marker S against the plane through the origin of marker
/// P with outward normal n = P's z axis (either marker may be the ground). Penetration
/// delta = r - n . (p_S - p_P) [m]; contact point c = p_S - r n (contact::SpherePlane). The sphere takes
/// F_N(delta, delta') n + F_T at c, the plane's body the opposite (CompliantContact); the
/// friction's moment about the sphere's centre is (c - p_S) x F_T. Potential energy: the
/// normal law's spring energy.
class SpherePlaneContact final : public ForceElement {
 public:
  /// The original penalty law: lambda = max(0, k delta^e + c delta') (contact::LinearLaw):
  /// radius > 0 [m], stiffness k >= 0 [N/m^e], damping c >= 0 [N s/m], exponent e >= 1;
  /// InputError naming the element otherwise.
  SpherePlaneContact(std::string name, MarkerRef sphere, MarkerRef plane, double radius, double stiffness,
                     double damping, double exponent);
  /// Any law (normal and optional friction); radius > 0 [m], InputError naming the element otherwise.
  SpherePlaneContact(std::string name, MarkerRef sphere, MarkerRef plane, double radius, CompliantContactLaw law);
  const std::string& name() const override { return name_; }
  void AddForces(double t, const MultibodySystem& system, const ConstVectorRef& y,
                 Eigen::Ref<Eigen::VectorXd> h) const override;
  double PotentialEnergy(double t, const MultibodySystem& system, const ConstVectorRef& y) const override;
  /// CompliantContact::AddForceJacobian on both bodies.
  void AddForceJacobian(double t, const MultibodySystem& system, const ConstVectorRef& y,
                        Eigen::Ref<Eigen::MatrixXd> dh_dx, Eigen::Ref<Eigen::MatrixXd> dh_du) const override;

  bool is_contact() const override { return true; }
  /// The load at the contact point while in contact.
  std::vector<ContactLoad> ContactLoads(double t, const MultibodySystem& system, const ConstVectorRef& y) const override;
 private:
  ContactPoint Geometry(const MultibodySystem& system, const ConstVectorRef& y) const;

  std::string name_;
  MarkerRef sphere_, plane_;
  double radius_;
  CompliantContact contact_;
};

/// Two spheres of radii r1, r2 [m] centred on markers S1 and S2 (either may be the ground). With
/// l = |p_S1 - p_S2| and n = (p_S1 - p_S2) / l, the penetration is delta = r1 + r2 - l and the
/// contact point the middle of the overlap, c = p_S2 + (r2 - delta / 2) n (contact::SphereSphere). Sphere 1 takes
/// F_N n + F_T at c, sphere 2 the opposite (CompliantContact). Throws SimulationError if the
/// centres meet (no normal).
class SphereSphereContact final : public ForceElement {
 public:
  /// radius1, radius2 > 0 [m]; InputError naming the element otherwise.
  SphereSphereContact(std::string name, MarkerRef sphere1, MarkerRef sphere2, double radius1, double radius2,
                      CompliantContactLaw law);
  const std::string& name() const override { return name_; }
  void AddForces(double t, const MultibodySystem& system, const ConstVectorRef& y,
                 Eigen::Ref<Eigen::VectorXd> h) const override;
  double PotentialEnergy(double t, const MultibodySystem& system, const ConstVectorRef& y) const override;
  /// CompliantContact::AddForceJacobian on both bodies, with the normal's turning (I - n n^T) / l.
  void AddForceJacobian(double t, const MultibodySystem& system, const ConstVectorRef& y,
                        Eigen::Ref<Eigen::MatrixXd> dh_dx, Eigen::Ref<Eigen::MatrixXd> dh_du) const override;

  bool is_contact() const override { return true; }
  /// The load at the contact point while in contact.
  std::vector<ContactLoad> ContactLoads(double t, const MultibodySystem& system, const ConstVectorRef& y) const override;
 private:
  ContactPoint Geometry(double t, const MultibodySystem& system, const ConstVectorRef& y) const;

  std::string name_;
  MarkerRef sphere1_, sphere2_;
  double radius1_, radius2_;
  CompliantContact contact_;
};

}  // namespace flexmbs::mbs
