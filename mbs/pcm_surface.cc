#include "mbs/pcm_surface.h"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <array>
#include <cstddef>

#include "core/error.h"
#include "core/skew.h"
#include "mbs/multibody_system.h"

namespace flexmbs::mbs {

PcmSurface ModalPcmSurface(const MarkerRef& origin, const sid::ContactSurface& surface, Eigen::Index num_modes,
                           const contact::ElasticLayer& layer, bool closed) {
  const Eigen::Index V = surface.vertices.rows();
  if (V == 0 || surface.face_sizes.empty()) throw InputError(fmt::format("surface '{}' has no faces", surface.name));
  if (surface.phi.rows() != 3 * V || surface.phi.cols() != num_modes) {
    throw InputError(fmt::format("surface '{}' has phi {} x {} for {} vertices and {} modes", surface.name,
                                 surface.phi.rows(), surface.phi.cols(), V, num_modes));
  }
  PcmSurface side{surface.name, origin, {}, layer, closed, surface};
  side.modal.face_sizes.clear();
  side.modal.face_vertices.clear();
  std::size_t first = 0;
  for (const int size : surface.face_sizes) {
    const int* v = &surface.face_vertices[first];
    const std::array<int, 3> triangles[2] = {{v[0], v[1], v[2]}, {v[0], v[2], size == 4 ? v[3] : v[2]}};
    for (int t = 0; t < (size == 4 ? 2 : 1); ++t) {
      side.modal.face_sizes.push_back(3);
      side.modal.face_vertices.insert(side.modal.face_vertices.end(), triangles[t].begin(), triangles[t].end());
    }
    first += static_cast<std::size_t>(size);
  }
  side.modal.face_normals.resize(0, 3);  // the split faces' normals are the mesh's own
  side.mesh_M.vertices_W = surface.vertices.transpose();
  side.mesh_M.face_sizes = side.modal.face_sizes;
  side.mesh_M.face_vertices = side.modal.face_vertices;
  return side;
}

PlacedPcmSurface::PlacedPcmSurface(const MultibodySystem& system, const PcmSurface& surface, const ConstVectorRef& y)
    : surface_(surface) {
  if (surface.is_modal()) {
    modal_.emplace(system, surface.marker, surface.modal, surface.modal.phi.cols(), y);
  } else {
    frame_ = system.MarkerState(surface.marker, y);
    mesh_ = surface.mesh_M;
    mesh_.vertices_W = (frame_.R_WM * surface.mesh_M.vertices_W).colwise() + frame_.p_WM_W;
  }
  const MarkerKinematics& M = frame();
  const Eigen::Matrix3Xd r_W = mesh().vertices_W.colwise() - M.p_WM_W;
  velocities_W_.resize(3, r_W.cols());
  for (Eigen::Index v = 0; v < r_W.cols(); ++v) velocities_W_.col(v) = M.v_WM_W + M.w_WM_W.cross(r_W.col(v));
  if (modal_) {
    const Eigen::VectorXd modal_velocities_B = surface.modal.phi * modal_->modal_velocities();
    velocities_W_ += M.R_WM * modal_velocities_B.reshaped(3, r_W.cols());
  }
}

Eigen::Matrix3Xd PlacedPcmSurface::ModalJacobian(int face, const Eigen::Vector3d& weights) const {
  if (!modal_) return Eigen::Matrix3Xd(3, 0);
  const int* v = &surface_.modal.face_vertices[3 * static_cast<std::size_t>(face)];
  return modal_->ModalJacobian({v[0], v[1], v[2], v[0]}, Eigen::Vector4d(weights(0), weights(1), weights(2), 0.0));
}

Eigen::MatrixXd PlacedPcmSurface::PointJacobian(const Eigen::Vector3d& p_W, int face, const Eigen::Vector3d& weights) const {
  if (surface_.marker.is_ground()) return Eigen::MatrixXd();
  const MarkerKinematics& M = frame();
  Eigen::MatrixXd J = M.jacobian.topRows<3>() - Skew(p_W - M.p_WM_W) * M.jacobian.bottomRows<3>();
  if (modal_) J.rightCols(surface_.modal.phi.cols()) += ModalJacobian(face, weights);
  return J;
}

Eigen::MatrixXd PlacedPcmSurface::PointJacobianGradient(int face, const Eigen::Matrix3d& weight_gradients, int axis) const {
  if (surface_.marker.is_ground()) return Eigen::MatrixXd();
  const MarkerKinematics& M = frame();
  Eigen::MatrixXd G = -Skew(Eigen::Vector3d::Unit(axis)) * M.jacobian.bottomRows<3>();
  if (modal_) G.rightCols(surface_.modal.phi.cols()) += ModalJacobian(face, weight_gradients.col(axis));
  return G;
}

}  // namespace flexmbs::mbs
