#pragma once
// A flexible body's contact surface against a plane, as unilateral contacts (docs/contact.md,
// "Flexible bodies: surface against plane"): every vertex of the SID contact surface is a contact
// point, deformed by the body's modal coordinates (the surface's own phi rows, restricted to the
// scene's modes), and the plane is the x-y plane of a marker (ground or a body).

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include "mbs/unilateral_contact.h"
#include "sid/reduced_body.h"

namespace flexmbs::mbs {

/// The vertices V of surface S of flexible body A against the plane through the origin of marker
/// P (body B) with outward normal P's z axis. With R = R_WB, s_V = p_BoV_B + phi_V q (phi_V the
/// surface's 3 x n rows of vertex V [m/q]; first order in q, the node markers' stiffening terms
/// are not carried by surfaces):
///   p_WV_W = p_WBo_W + R s_V,   g_N,V = n . (p_WV_W - p_WP_W),   n = R_WP e_z,
///   v_V = v_Bo + w_W x (R s_V) + R phi_V qdot,
/// so W_N,V = n^T [I, -[R s_V]x J_w, R phi_V] on A's columns minus the plane's point velocity at
/// the vertex's foot p_WV_W - g_N,V n. The tangents t1, t2 are TangentBasis(n), shared by all
/// vertices.
class SurfacePlaneUnilateral final : public UnilateralContact {
 public:
  /// `origin` is A's body-frame marker (FlexibleBody::kOriginMarker), `surface` its contact
  /// surface with phi restricted to the body's kept modes (3 V x num_modes). InputError naming
  /// the contact: a surface without vertices, phi of the wrong size (and as UnilateralContact).
  SurfacePlaneUnilateral(std::string name, MarkerRef origin, sid::ContactSurface surface, Eigen::Index num_modes,
                         MarkerRef plane, UnilateralLaw law);

  std::string_view type() const override { return "surface_plane"; }
  int num_points() const override { return static_cast<int>(surface_.vertices.rows()); }
  /// The surface's name in the body's SID file.
  const std::string& surface_name() const { return surface_.name; }

 private:
  std::vector<UnilateralContactKinematics> EvaluatePoints(const MultibodySystem& system,
                                                          const ConstVectorRef& y) const override;

  sid::ContactSurface surface_;
  Eigen::Index num_modes_;
};

}  // namespace flexmbs::mbs
