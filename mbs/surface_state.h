#pragma once
// A reduced body's contact surface at one state of the system (docs/contact.md, "Flexible
// bodies"): its vertices in W, deformed by the modal coordinates, and the velocity of a material
// point of the surface through the body's modal velocities. The surface contacts (unilateral and
// compliant) share it.

#include <Eigen/Core>
#include <array>

#include "contact/geometry/sphere_surface.h"
#include "mbs/body.h"
#include "mbs/marker_ref.h"
#include "sid/reduced_body.h"

namespace flexmbs::mbs {

class MultibodySystem;

/// Surface S of reduced body A at y. With R = R_WB and q A's modal coordinates, vertex V is at
/// p_WV_W = p_WBo_W + R (p_BoV_B + phi_V q) (first order in q: a surface carries phi, not the node
/// markers' stiffening terms), and a material point c = sum_i w_i V_i of the surface moves with
///   v_c = v_Bo + w_W x (p_c - p_WBo_W) + R (sum_i w_i phi_Vi) qdot:
/// the frame marker's point velocity at c plus the modal part.
class SurfaceState {
 public:
  /// `origin` is A's body-frame marker, `surface` A's contact surface with phi over A's kept modes
  /// (3 V x num_modes, checked by the caller).
  SurfaceState(const MultibodySystem& system, const MarkerRef& origin, const sid::ContactSurface& surface,
               Eigen::Index num_modes, const ConstVectorRef& y);

  /// The deformed mesh in W.
  const contact::PolygonMesh& mesh() const { return mesh_; }
  /// The body frame's marker kinematics at y.
  const MarkerKinematics& frame() const { return frame_; }
  /// R sum_i w_i phi_Vi (3 x num_modes) [m/q]: the velocity of the material point sum_i w_i V_i per
  /// modal velocity, in W.
  Eigen::Matrix3Xd ModalJacobian(const std::array<int, 4>& vertices, const Eigen::Vector4d& weights) const;
  /// The same for vertex V alone.
  Eigen::Matrix3Xd ModalJacobian(int vertex) const;
  /// The body's modal velocities qdot [q/s].
  const Eigen::VectorXd& modal_velocities() const { return q_dot_; }
  /// Where A's modal velocities start in the system's velocities.
  Eigen::Index modal_column() const { return modal_column_; }

 private:
  const sid::ContactSurface& surface_;
  MarkerKinematics frame_;
  contact::PolygonMesh mesh_;
  Eigen::VectorXd q_dot_;
  Eigen::Index modal_column_;
};

}  // namespace flexmbs::mbs
