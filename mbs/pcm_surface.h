#pragma once
// One side of a Polygonal Contact Model pair (docs/contact.md, "Polygonal Contact Model"): a rigid
// triangle mesh on a marker or a reduced body's contact surface deformed by its modes, and that
// side placed at a state of the system (its vertices and their velocities in W, the Jacobian of
// a material point of one of its faces).

#include <Eigen/Core>
#include <optional>
#include <string>

#include "contact/geometry/sphere_surface.h"
#include "contact/pcm/foundation.h"
#include "mbs/body.h"
#include "mbs/marker_ref.h"
#include "mbs/surface_state.h"
#include "sid/reduced_body.h"

namespace flexmbs::mbs {

class MultibodySystem;

/// One side of a PCM pair: a triangle mesh (counter-clockwise seen from outside) with vertices in
/// the frame of `marker` on an elastic layer. A rigid side's mesh is carried rigidly by the marker;
/// a modal side (ModalPcmSurface) is a reduced body's contact surface, `marker` the body frame,
/// its vertices moved by the modes: p_BoV_B + phi_V q (mbs/surface_state.h).
struct PcmSurface {
  std::string name;
  MarkerRef marker;
  contact::PolygonMesh mesh_M;  ///< p_MV_M [m]; a modal side's undeformed triangles
  contact::ElasticLayer layer;
  bool closed = false;  ///< whether the mesh must be closed (a body's whole boundary)
  /// A modal side's surface: the body's contact surface with its faces those of mesh_M and phi
  /// over the body's kept modes (3 V x n) [m/q]; no vertices on a rigid side.
  sid::ContactSurface modal{};
  bool is_modal() const { return modal.vertices.rows() > 0; }
};

/// The modal side of contact surface `surface` of the reduced body whose frame marker is `origin`,
/// phi over the body's `num_modes` kept modes: its quads split into two triangles along the
/// diagonal from their first vertex (v0 v1 v2, v0 v2 v3; the vertices and phi kept), named as the
/// surface. InputError "surface '<name>': ..." for a surface without faces or with phi not
/// 3 V x num_modes.
PcmSurface ModalPcmSurface(const MarkerRef& origin, const sid::ContactSurface& surface, Eigen::Index num_modes,
                           const contact::ElasticLayer& layer, bool closed);

/// A PCM side at a state y: its mesh in W (a modal side deformed by its modal coordinates), each
/// vertex's velocity v_V = v_Bo + w x (p_V - p_Bo) + R phi_V qdot (the last term on a modal side
/// only) and the Jacobian of a material point of a face.
class PlacedPcmSurface {
 public:
  /// `surface` must outlive this.
  PlacedPcmSurface(const MultibodySystem& system, const PcmSurface& surface, const ConstVectorRef& y);

  /// The mesh in W [m].
  const contact::PolygonMesh& mesh() const { return modal_ ? modal_->mesh() : mesh_; }
  /// Each vertex's velocity in W (3 x V) [m/s].
  const Eigen::Matrix3Xd& velocities_W() const { return velocities_W_; }
  /// The marker's (a modal side's body frame's) kinematics at y.
  const MarkerKinematics& frame() const { return modal_ ? modal_->frame() : frame_; }
  /// The point of triangle `face` with barycentric weights w: R sum_k w_k phi_k (3 x n) [m/q], the
  /// velocity of that material point per modal velocity; 3 x 0 on a rigid side.
  Eigen::Matrix3Xd ModalJacobian(int face, const Eigen::Vector3d& weights) const;
  /// The velocity Jacobian (3 x the body's velocities) of the side's material point at p_W, the
  /// point of `face` with weights w: J_v - (p_W - p_M)~ J_w of the marker, plus ModalJacobian on the
  /// body's modal columns. Empty for the ground.
  Eigen::MatrixXd PointJacobian(const Eigen::Vector3d& p_W, int face, const Eigen::Vector3d& weights) const;
  /// The derivative of PointJacobian by the point's coordinate `axis` (0, 1, 2) of W as it moves
  /// over `face`, whose weights change by the column `axis` of `weight_gradients` (row k: weight
  /// k's gradient [1/m]): -e_axis~ J_w plus ModalJacobian of those changes [1/m per body velocity].
  /// PointJacobian is linear in the point, so this is constant over the face. Empty for the ground.
  Eigen::MatrixXd PointJacobianGradient(int face, const Eigen::Matrix3d& weight_gradients, int axis) const;
  /// Where the body's modal velocities start in the system's velocities (modal side only).
  Eigen::Index modal_column() const { return modal_->modal_column(); }

 private:
  const PcmSurface& surface_;
  MarkerKinematics frame_;
  contact::PolygonMesh mesh_;
  std::optional<SurfaceState> modal_;
  Eigen::Matrix3Xd velocities_W_;
};

}  // namespace flexmbs::mbs
