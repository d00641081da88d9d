#pragma once
// Compliant contact force elements (docs/mbs.md, "Seams for contact"): spheres against a plane
// and against each other, with any normal law of contact/laws and optional regularised friction,
// all evaluated by mbs/compliant_contact.h. Each element here owns its geometry only.

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

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

/// A compliant contact of many points under one law (the corners of a box, the vertices of a
/// surface): its loads, energy, Jacobian and drawn loads are its points' (CompliantContact), the
/// points its geometry's (Points).
class CompliantPointsContact : public ForceElement {
 public:
  const std::string& name() const final { return name_; }
  void AddForces(double t, const MultibodySystem& system, const ConstVectorRef& y,
                 Eigen::Ref<Eigen::VectorXd> h) const final;
  double PotentialEnergy(double t, const MultibodySystem& system, const ConstVectorRef& y) const final;
  /// CompliantContact::AddForceJacobian of every point in contact.
  void AddForceJacobian(double t, const MultibodySystem& system, const ConstVectorRef& y,
                        Eigen::Ref<Eigen::MatrixXd> dh_dx, Eigen::Ref<Eigen::MatrixXd> dh_du) const final;
  bool is_contact() const final { return true; }
  /// The load at every point in contact.
  std::vector<ContactLoad> ContactLoads(double t, const MultibodySystem& system, const ConstVectorRef& y) const final;
  /// The normal forces summed over the points [N] at y.
  double NormalForce(const MultibodySystem& system, const ConstVectorRef& y) const;
  /// The law every point takes.
  const CompliantContactLaw& law() const { return contact_.law(); }
  /// Every point's geometry at y (a fixed number of them; penetration <= 0 apart).
  virtual std::vector<ContactPoint> Points(const MultibodySystem& system, const ConstVectorRef& y) const = 0;

 protected:
  /// The law between markers a (body A) and b (body B).
  CompliantPointsContact(std::string name, CompliantContactLaw law, MarkerRef a, MarkerRef b);

 private:
  std::string name_;
  CompliantContact contact_;
};

/// A box of half extents h [m] about the origin of marker C (its axes the box's) against the plane
/// through the origin of marker P with outward normal n = P's z axis, a compliant contact at each
/// of its 8 corners: penetration delta = -n . (p_corner - p_P), F_N(delta, delta') n + F_T at the
/// corner on the box, the opposite on the plane's body. The penalty counterpart of
/// BoxPlaneUnilateral.
class BoxPlaneContact final : public CompliantPointsContact {
 public:
  /// half_extents > 0 and finite [m]; InputError naming the element otherwise.
  BoxPlaneContact(std::string name, MarkerRef box, const Eigen::Vector3d& half_extents, MarkerRef plane,
                  CompliantContactLaw law);

 private:
  std::vector<ContactPoint> Points(const MultibodySystem& system, const ConstVectorRef& y) const override;

  MarkerRef box_, plane_;
  std::array<Eigen::Vector3d, 8> corners_C_;  ///< in C's frame [m]
};

}  // namespace flexmbs::mbs
