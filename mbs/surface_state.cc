#include "mbs/surface_state.h"

#include "mbs/multibody_system.h"

namespace flexmbs::mbs {

SurfaceState::SurfaceState(const MultibodySystem& system, const MarkerRef& origin, const sid::ContactSurface& surface,
                           Eigen::Index num_modes, const ConstVectorRef& y)
    : surface_(surface),
      frame_(system.MarkerState(origin, y)),
      q_dot_(system.BodyVelocities(y, origin.body).tail(num_modes)),
      modal_column_(system.velocity_block(origin.body).start + 6) {
  const Eigen::VectorXd q = system.BodyPositions(y, origin.body).tail(num_modes);
  const Eigen::Index V = surface.vertices.rows();
  const Eigen::Matrix3Xd s_B = surface.vertices.transpose() + (surface.phi * q).reshaped(3, V);
  mesh_.vertices_W = (frame_.R_WM * s_B).colwise() + frame_.p_WM_W;
  mesh_.face_sizes = surface.face_sizes;
  mesh_.face_vertices = surface.face_vertices;
}

Eigen::Matrix3Xd SurfaceState::ModalJacobian(const std::array<int, 4>& vertices,
                                            const Eigen::Vector4d& weights) const {
  Eigen::Matrix3Xd phi_c = Eigen::Matrix3Xd::Zero(3, surface_.phi.cols());
  for (std::size_t i = 0; i < 4; ++i) {
    if (weights(static_cast<Eigen::Index>(i)) != 0.0) {
      phi_c += weights(static_cast<Eigen::Index>(i)) * surface_.phi.middleRows(3 * vertices[i], 3);
    }
  }
  return frame_.R_WM * phi_c;
}

Eigen::Matrix3Xd SurfaceState::ModalJacobian(int vertex) const {
  return frame_.R_WM * surface_.phi.middleRows(3 * vertex, 3);
}

}  // namespace flexmbs::mbs
