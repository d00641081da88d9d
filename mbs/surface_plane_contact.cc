#include "mbs/surface_plane_contact.h"

#include <fmt/format.h>

#include <utility>

#include "contact/geometry/point_contact.h"
#include "core/error.h"
#include "mbs/multibody_system.h"

namespace flexmbs::mbs {

SurfacePlaneUnilateral::SurfacePlaneUnilateral(std::string name, MarkerRef origin, sid::ContactSurface surface,
                                               Eigen::Index num_modes, MarkerRef plane, UnilateralLaw law)
    : UnilateralContact(std::move(name), std::move(origin), std::move(plane), law),
      surface_(std::move(surface)), num_modes_(num_modes) {
  if (surface_.vertices.rows() == 0) {
    throw InputError(fmt::format("contact '{}': surface '{}' has no vertices", this->name(), surface_.name));
  }
  if (surface_.phi.rows() != 3 * surface_.vertices.rows() || surface_.phi.cols() != num_modes_) {
    throw InputError(fmt::format("contact '{}': surface '{}' has phi {} x {} for {} vertices and {} modes",
                                 this->name(), surface_.name, surface_.phi.rows(), surface_.phi.cols(),
                                 surface_.vertices.rows(), num_modes_));
  }
}

std::vector<UnilateralContactKinematics> SurfacePlaneUnilateral::EvaluatePoints(const MultibodySystem& system,
                                                                                const ConstVectorRef& y) const {
  const MarkerKinematics body = system.MarkerState(marker_a(), y), plane = system.MarkerState(marker_b(), y);
  const Eigen::VectorXd q = system.BodyPositions(y, marker_a().body).tail(num_modes_);
  const Eigen::Matrix3d& R_WB = body.R_WM;
  const Eigen::Index modal_column = system.velocity_offset(marker_a().body) + 6;
  UnilateralContactKinematics k;
  k.n_W = plane.R_WM.col(2);
  contact::TangentBasis(k.n_W, &k.t1_W, &k.t2_W);
  Eigen::Matrix3d frame_W;  // rows n, t1, t2
  frame_W << k.n_W.transpose(), k.t1_W.transpose(), k.t2_W.transpose();

  std::vector<UnilateralContactKinematics> points;
  points.reserve(static_cast<std::size_t>(num_points()));
  for (Eigen::Index v = 0; v < surface_.vertices.rows(); ++v) {
    const Eigen::Vector3d s_B = surface_.vertices.row(v).transpose() + surface_.phi.middleRows(3 * v, 3) * q;
    k.p_WA_W = body.p_WM_W + R_WB * s_B;
    k.g_N = k.n_W.dot(k.p_WA_W - plane.p_WM_W);
    k.p_WB_W = k.p_WA_W - k.g_N * k.n_W;
    k.W_N = Eigen::RowVectorXd::Zero(system.num_velocities());
    k.W_T = Eigen::MatrixXd::Zero(2, system.num_velocities());
    AddPointJacobian(system, marker_a(), body, k.p_WA_W, 1.0, &k);
    const Eigen::Matrix3Xd local_per_qdot = frame_W * R_WB * surface_.phi.middleRows(3 * v, 3);
    k.W_N.segment(modal_column, num_modes_) += local_per_qdot.row(0);
    k.W_T.middleCols(modal_column, num_modes_) += local_per_qdot.bottomRows<2>();
    AddPointJacobian(system, marker_b(), plane, k.p_WB_W, -1.0, &k);
    points.push_back(k);
  }
  return points;
}

}  // namespace flexmbs::mbs
