#pragma once
// Compliant contact as a force element (docs/mbs.md, "Seams for contact"): the first contact
// law, a penalty sphere on a plane.

#include <Eigen/Core>
#include <string>

#include "mbs/force_element.h"
#include "mbs/marker_ref.h"

namespace flexmbs::mbs {

/// A sphere of radius r [m] centred on marker S against the plane through the origin of marker
/// P with outward normal n = P's z axis (either marker may be the ground). With the penetration
/// delta = r - n . (p_S - p_P) [m] and its rate delta', the normal force on the sphere is
///   lambda = max(0, k delta^e + c delta')   for delta > 0, else 0,
/// along n at the contact point (e = 1: linear spring-dashpot, e = 3/2: Hertz with
/// k = 4/3 E* sqrt(r)); clipped at 0 so the dashpot never pulls. The plane's body takes
/// -lambda n at the contact point p_S - r n. No friction. Potential energy k delta^(e+1)/(e+1).
class SpherePlaneContact final : public ForceElement {
 public:
  /// radius > 0 [m], stiffness k >= 0 [N/m^e], damping c >= 0 [N s/m], exponent e >= 1;
  /// InputError naming the element otherwise.
  SpherePlaneContact(std::string name, MarkerRef sphere, MarkerRef plane, double radius, double stiffness,
                     double damping, double exponent);
  const std::string& name() const override { return name_; }
  void AddForces(double t, const MultibodySystem& system, const ConstVectorRef& y,
                 Eigen::Ref<Eigen::VectorXd> h) const override;
  double PotentialEnergy(double t, const MultibodySystem& system, const ConstVectorRef& y) const override;
  /// d lambda / d delta = e k delta^(e-1) and c along n n^T on the sphere's body (its block of
  /// dh/dx and dh/du, in contact); the plane body's blocks are left to the Newton iteration.
  void AddForceJacobian(double t, const MultibodySystem& system, const ConstVectorRef& y,
                        Eigen::Ref<Eigen::MatrixXd> dh_dx, Eigen::Ref<Eigen::MatrixXd> dh_du) const override;

 private:
  /// The contact's markers, geometry and normal force at y (force 0 when apart).
  struct State {
    MarkerKinematics sphere, plane;      ///< the markers S and P
    Eigen::Vector3d n_W;                 ///< the plane's normal
    double penetration = 0.0;            ///< delta [m]
    double penetration_rate = 0.0;       ///< delta' [m/s]
    double force = 0.0;                  ///< lambda [N]
  };
  State Evaluate(const MultibodySystem& system, const ConstVectorRef& y) const;

  std::string name_;
  MarkerRef sphere_, plane_;
  double radius_, stiffness_, damping_, exponent_;
};

}  // namespace flexmbs::mbs
