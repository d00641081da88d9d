#pragma once
// Unilateral (hard) contacts between two bodies for Moreau-Jean time stepping (docs/contact.md,
// "Moreau-Jean time stepping"): a gap g_N >= 0, Newton's impact law with restitution e and Coulomb
// friction mu, seen by the step through their kinematics only: the point-contact frame of
// contact/geometry (gap, normal, tangents, contact points) and the Jacobians of the relative
// velocity, never through a shape.

#include <Eigen/Core>
#include <array>
#include <string>
#include <string_view>
#include <vector>

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

/// A unilateral contact between body A (marker a) and body B (marker b): one point between two
/// shapes on markers, or many (the vertices of a flexible body's contact surface); either body
/// may be the ground, not both, and not both the same body. Immutable after construction.
class UnilateralContact {
 public:
  virtual ~UnilateralContact() = default;
  UnilateralContact(const UnilateralContact&) = delete;
  UnilateralContact& operator=(const UnilateralContact&) = delete;

  const std::string& name() const { return name_; }
  /// The scene's type name: "sphere_plane", "sphere_sphere", "surface_plane", "sphere_surface".
  virtual std::string_view type() const = 0;
  /// The number of contact points, fixed for the run: 1 for two shapes, the vertices of a surface.
  virtual int num_points() const = 0;
  const UnilateralLaw& law() const { return law_; }
  const MarkerRef& marker_a() const { return a_; }
  const MarkerRef& marker_b() const { return b_; }

  /// The kinematics of every point at (t, y), num_points() of them in a fixed order; W_N and W_T
  /// of a point carry the velocity Jacobian of A's material point at p_WA_W minus B's at p_WB_W,
  /// projected on its frame. Throws SimulationError at t naming the contact where the geometry
  /// has no normal.
  std::vector<UnilateralContactKinematics> Evaluate(double t, const MultibodySystem& system,
                                                    const ConstVectorRef& y) const;

 protected:
  /// Checks the law (InputError naming the contact: e outside [0, 1], mu < 0 or not finite) and
  /// the markers (both the ground, or both on one body).
  UnilateralContact(std::string name, MarkerRef a, MarkerRef b, UnilateralLaw law);

  /// The points' kinematics at y (Evaluate's). May throw contact::DegenerateContactError.
  virtual std::vector<UnilateralContactKinematics> EvaluatePoints(const MultibodySystem& system,
                                                                  const ConstVectorRef& y) const = 0;

  /// Adds sign [n; t1; t2]^T (J_v - [p_W - p_M]x J_w) to the columns of the body of marker `ref`
  /// in k->W_N, k->W_T (sized num_velocities()): the velocity Jacobian of the material point at
  /// p_W [m] moving with the marker's frame (`marker` = MarkerState(ref, y)). Nothing for the ground.
  static void AddPointJacobian(const MultibodySystem& system, const MarkerRef& ref, const MarkerKinematics& marker,
                               const Eigen::Vector3d& p_W, double sign, UnilateralContactKinematics* k);
  /// Adds sign [n; t1; t2]^T modal_W to the columns from `column` on: a reduced body's surface
  /// point moving with its modal velocities by modal_W (3 x n) [m/q] (mbs/surface_state.h).
  static void AddModalJacobian(Eigen::Index column, const Eigen::Matrix3Xd& modal_W, double sign,
                               UnilateralContactKinematics* k);
  /// Points p_A given in the frame of marker a (A's), each against the plane through the origin
  /// of marker b with outward normal b's z axis (contact::PointPlane), with their Jacobians.
  template <std::size_t N>
  std::vector<UnilateralContactKinematics> PointsOnPlane(const MultibodySystem& system, const ConstVectorRef& y,
                                                         const std::array<Eigen::Vector3d, N>& points_A) const;

 private:
  std::string name_;
  MarkerRef a_, b_;
  UnilateralLaw law_;
};

/// A unilateral contact of one point between a shape on marker a and a shape on marker b.
class ShapePairUnilateral : public UnilateralContact {
 public:
  int num_points() const final { return 1; }

 protected:
  using UnilateralContact::UnilateralContact;

  /// The geometry between the two markers: g_N, the frame and the contact points (W_N, W_T left
  /// empty). May throw contact::DegenerateContactError.
  virtual UnilateralContactKinematics Geometry(const MarkerKinematics& a, const MarkerKinematics& b) const = 0;

 private:
  std::vector<UnilateralContactKinematics> EvaluatePoints(const MultibodySystem& system,
                                                          const ConstVectorRef& y) const final;
};

/// A sphere of radius r [m] centred on marker S (body A) against the plane through the origin of
/// marker P (body B) with outward normal P's z axis, as the compliant SpherePlaneContact
/// (mbs/contact_force.h): g_N = n . (p_S - p_P) - r (contact::SpherePlane).
class SpherePlaneUnilateral final : public ShapePairUnilateral {
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
class SphereSphereUnilateral final : public ShapePairUnilateral {
 public:
  /// radius1, radius2 > 0 [m]; InputError naming the contact otherwise (and as UnilateralContact).
  SphereSphereUnilateral(std::string name, MarkerRef sphere1, MarkerRef sphere2, double radius1, double radius2,
                         UnilateralLaw law);
  std::string_view type() const override { return "sphere_sphere"; }

 private:
  UnilateralContactKinematics Geometry(const MarkerKinematics& a, const MarkerKinematics& b) const override;
  double radius1_, radius2_;
};

/// A box of half extents h [m] about the origin of marker C (body A; the box's axes C's) against
/// the plane through the origin of marker P (body B) with outward normal P's z axis: its 8 corners,
/// each a point with g_N = n . (p_corner - p_P) (contact::PointPlane) and W_N the corner's velocity
/// (moving with C) less the plane's at its foot. Edges and faces touch through their corners.
class BoxPlaneUnilateral final : public UnilateralContact {
 public:
  /// half_extents > 0 and finite [m]; InputError naming the contact otherwise (and as
  /// UnilateralContact).
  BoxPlaneUnilateral(std::string name, MarkerRef box, const Eigen::Vector3d& half_extents, MarkerRef plane,
                     UnilateralLaw law);
  std::string_view type() const override { return "box_plane"; }
  int num_points() const override { return 8; }

 private:
  std::vector<UnilateralContactKinematics> EvaluatePoints(const MultibodySystem& system,
                                                          const ConstVectorRef& y) const override;
  std::array<Eigen::Vector3d, 8> corners_C_;  ///< in C's frame [m]
};

/// A cylinder of radius r and length l [m] centred on marker C (body A; its axis C's z axis) against
/// the plane through the origin of marker P (body B) with outward normal P's z axis: its 6 support
/// points (contact::CylinderSupportPoints: on each end circle the lowest point and the two 120
/// degrees from it), each with g_N = n . (p - p_P) (contact::PointPlane) and W_N the material
/// point's velocity less the plane's at its foot. It rolls on the lowest points of its two rims and
/// stands on three points of an end face.
class CylinderPlaneUnilateral final : public UnilateralContact {
 public:
  /// radius, length > 0 and finite [m]; InputError naming the contact otherwise (and as
  /// UnilateralContact).
  CylinderPlaneUnilateral(std::string name, MarkerRef cylinder, double radius, double length, MarkerRef plane,
                          UnilateralLaw law);
  std::string_view type() const override { return "cylinder_plane"; }
  int num_points() const override { return 6; }

 private:
  std::vector<UnilateralContactKinematics> EvaluatePoints(const MultibodySystem& system,
                                                          const ConstVectorRef& y) const override;
  double radius_, half_length_;
};

}  // namespace flexmbs::mbs
