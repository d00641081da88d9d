#pragma once
// Unilateral (hard) contacts between two bodies for Moreau-Jean time stepping (docs/contact.md,
// "Moreau-Jean time stepping"): a gap g_N >= 0, Newton's impact law with restitution e and Coulomb
// friction mu, seen by the step through their kinematics only: the point-contact frame of
// contact/geometry (gap, normal, tangents, contact points) and the Jacobians of the relative
// velocity, never through a shape.

#include <Eigen/Core>
#include <string>
#include <string_view>

#include "contact/geometry/point_contact.h"
#include "mbs/body.h"
#include "mbs/marker_ref.h"

namespace flexmbs::mbs {

class MultibodySystem;

/// A unilateral contact's constitutive data: Newton's restitution e in [0, 1] (U_N+ = -e U_N-
/// at an impact; Moreau's form U_N,k+1 + e U_N,k >= 0 _|_ P_N >= 0 per step) and Coulomb's
/// friction coefficient mu >= 0 (Acary & Brogliato 2008, §1.1, §3.2, §10.1).
struct UnilateralLaw {
  double restitution = 0.0;
  double friction = 0.0;
};

/// One contact's kinematics at a state y, in W: gap g_N [m], the contact frame (n_W from B to A,
/// t1_W, t2_W; n_W x t1_W = t2_W, contact/geometry/point_contact.h), the contact points on A and
/// B [m], and the Jacobians of the relative velocity of A's material point at p_WA_W against B's
/// at p_WB_W through the whole system's velocities u (rigid and modal coordinates of both bodies):
/// U_N = W_N u [m/s] (dg_N/dt = U_N), [U_T1; U_T2] = W_T u.
struct UnilateralContactKinematics : contact::PointContactKinematics {
  Eigen::RowVectorXd W_N;                        ///< 1 x num_velocities()
  Eigen::Matrix<double, 2, Eigen::Dynamic> W_T;  ///< 2 x num_velocities()
};

/// A unilateral contact between a shape on marker a (body A) and a shape on marker b (body B);
/// either may be the ground, not both, and not both on one body. Immutable after construction.
class UnilateralContact {
 public:
  virtual ~UnilateralContact() = default;
  UnilateralContact(const UnilateralContact&) = delete;
  UnilateralContact& operator=(const UnilateralContact&) = delete;

  const std::string& name() const { return name_; }
  /// The scene's type name: "sphere_plane", "sphere_sphere".
  virtual std::string_view type() const = 0;
  const UnilateralLaw& law() const { return law_; }
  const MarkerRef& marker_a() const { return a_; }
  const MarkerRef& marker_b() const { return b_; }

  /// The kinematics at (t, y). The velocity of a point at offset r from a marker's origin is
  /// J_v u - [r]x J_w u (the marker's jacobian rows, MultibodySystem::MarkerState), so W_N and W_T
  /// carry A's point Jacobian at p_WA_W minus B's at p_WB_W, projected on the frame. Throws
  /// SimulationError at t naming the contact where the geometry has no normal.
  UnilateralContactKinematics Evaluate(double t, const MultibodySystem& system, const ConstVectorRef& y) const;

 protected:
  /// Checks the law (InputError naming the contact: e outside [0, 1], mu < 0 or not finite) and
  /// the markers (both the ground, or both on one body).
  UnilateralContact(std::string name, MarkerRef a, MarkerRef b, UnilateralLaw law);

  /// The geometry between the two markers: g_N, the frame and the contact points (W_N, W_T left
  /// empty). May throw contact::DegenerateContactError.
  virtual UnilateralContactKinematics Geometry(const MarkerKinematics& a, const MarkerKinematics& b) const = 0;

 private:
  std::string name_;
  MarkerRef a_, b_;
  UnilateralLaw law_;
};

/// A sphere of radius r [m] centred on marker S (body A) against the plane through the origin of
/// marker P (body B) with outward normal P's z axis, as the compliant SpherePlaneContact
/// (mbs/contact_force.h): g_N = n . (p_S - p_P) - r (contact::SpherePlane).
class SpherePlaneUnilateral final : public UnilateralContact {
 public:
  /// radius > 0 [m]; InputError naming the contact otherwise (and as UnilateralContact).
  SpherePlaneUnilateral(std::string name, MarkerRef sphere, MarkerRef plane, double radius, UnilateralLaw law);
  std::string_view type() const override { return "sphere_plane"; }

 private:
  UnilateralContactKinematics Geometry(const MarkerKinematics& a, const MarkerKinematics& b) const override;
  double radius_;
};

/// Two spheres of radii r1, r2 [m] centred on markers S1 (body A) and S2 (body B):
/// g_N = |p_S1 - p_S2| - r1 - r2, n from S2 to S1 (contact::SphereSphere). Coincident centres:
/// SimulationError.
class SphereSphereUnilateral final : public UnilateralContact {
 public:
  /// radius1, radius2 > 0 [m]; InputError naming the contact otherwise (and as UnilateralContact).
  SphereSphereUnilateral(std::string name, MarkerRef sphere1, MarkerRef sphere2, double radius1, double radius2,
                         UnilateralLaw law);
  std::string_view type() const override { return "sphere_sphere"; }

 private:
  UnilateralContactKinematics Geometry(const MarkerKinematics& a, const MarkerKinematics& b) const override;
  double radius1_, radius2_;
};

}  // namespace flexmbs::mbs
