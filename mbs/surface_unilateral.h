#pragma once
// Unilateral contacts on a reduced body's contact surface (docs/contact.md, "Flexible bodies"):
// every vertex against a plane, a sphere against the surface's faces, and every vertex against
// another flexible body's surface. The surface deforms
// with the body's modal coordinates (mbs/surface_state.h); only its own rows of the basis are kept.

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include "mbs/unilateral_contact.h"
#include "sid/reduced_body.h"

namespace flexmbs::mbs {

/// The vertices V of surface S of flexible body A against the plane through the origin of marker
/// P (body B) with outward normal n = P's z axis: g_N,V = n . (p_WV_W - p_WP_W), and W_N,V the
/// velocity of the vertex (SurfaceState) less the plane's at the vertex's foot p_WV_W - g_N,V n,
/// on n. The tangents t1, t2 are TangentBasis(n), shared by all vertices.
class SurfacePlaneUnilateral final : public UnilateralContact {
 public:
  /// `origin` is A's body-frame marker (FlexibleBody::kOriginMarker), `surface` its contact
  /// surface with phi restricted to the body's kept modes (3 V x num_modes). InputError naming
  /// the contact: a surface without vertices, phi of the wrong size (and as UnilateralContact).
  SurfacePlaneUnilateral(std::string name, MarkerRef origin, sid::ContactSurface surface, Eigen::Index num_modes,
                         MarkerRef plane, UnilateralLaw law);

  std::string_view type() const override { return "surface_plane"; }
  int num_points() const override { return static_cast<int>(surface_.vertices.rows()); }

 private:
  std::vector<UnilateralContactKinematics> EvaluatePoints(const MultibodySystem& system,
                                                          const ConstVectorRef& y) const override;

  sid::ContactSurface surface_;
  Eigen::Index num_modes_;
};

/// A sphere of radius r [m] centred on marker S (body A) against surface S of flexible body B:
/// one point, the surface point nearest the centre (contact::SphereMesh on the deformed faces),
/// which moves with its face's vertices by their weights (SurfaceState).
class SphereSurfaceUnilateral final : public UnilateralContact {
 public:
  /// radius > 0 [m]; `origin` is B's body-frame marker, `surface` as SurfacePlaneUnilateral's.
  /// InputError naming the contact otherwise (and as UnilateralContact).
  SphereSurfaceUnilateral(std::string name, MarkerRef sphere, double radius, MarkerRef origin,
                          sid::ContactSurface surface, Eigen::Index num_modes, UnilateralLaw law);

  std::string_view type() const override { return "sphere_surface"; }
  int num_points() const override { return 1; }

 private:
  std::vector<UnilateralContactKinematics> EvaluatePoints(const MultibodySystem& system,
                                                          const ConstVectorRef& y) const override;

  double radius_;
  sid::ContactSurface surface_;
  Eigen::Index num_modes_;
};

/// Node to surface between two flexible bodies: every vertex V of surface S_A of body A against
/// the faces of surface S_B of body B (contact::PointMesh on S_B deformed, the nearest face found
/// through a Bvh built on S_B at each evaluation: contact/pcm/nearest_face.h), g_N,V along the normal
/// of B's face at the nearest point c, W_N,V the velocity of the vertex less that of B's material
/// point at c (both through their body's frame and modes, SurfaceState). Name the surfaces that
/// meet (an end face against an end face): a vertex off S_B is apart.
class SurfaceSurfaceUnilateral final : public UnilateralContact {
 public:
  /// `origin_a`, `origin_b` are the bodies' frame markers, the surfaces' phi over each body's
  /// kept modes (as SurfacePlaneUnilateral's). InputError naming the contact otherwise.
  SurfaceSurfaceUnilateral(std::string name, MarkerRef origin_a, sid::ContactSurface surface_a,
                           Eigen::Index num_modes_a, MarkerRef origin_b, sid::ContactSurface surface_b,
                           Eigen::Index num_modes_b, UnilateralLaw law);

  std::string_view type() const override { return "surface_surface"; }
  int num_points() const override { return static_cast<int>(surface_a_.vertices.rows()); }

 private:
  std::vector<UnilateralContactKinematics> EvaluatePoints(const MultibodySystem& system,
                                                          const ConstVectorRef& y) const override;

  sid::ContactSurface surface_a_, surface_b_;
  Eigen::Index num_modes_a_, num_modes_b_;
};

/// Throws InputError naming contact `contact` unless `surface` has vertices, faces, and phi of
/// 3 V x num_modes.
void CheckSurface(const std::string& contact, const sid::ContactSurface& surface, Eigen::Index num_modes);

}  // namespace flexmbs::mbs
