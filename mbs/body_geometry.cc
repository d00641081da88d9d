#include "mbs/body_geometry.h"

#include <algorithm>

#include "core/rotation.h"
#include "mbs/flexible_body.h"
#include "mbs/rigid_body.h"

namespace flexmbs::mbs {

BodyDrawing::BodyDrawing(const Body& body) : body_(body) {
  const auto* flexible = dynamic_cast<const FlexibleBody*>(&body);
  if (flexible != nullptr && !flexible->data().visual_surface.empty()) {
    const sid::ReducedBody& data = flexible->data();
    // The FE nodes the polygons use, ascending, and the polygons renumbered onto them.
    std::vector<int> nodes = data.visual_surface.face_nodes;
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    const auto count = static_cast<Eigen::Index>(nodes.size());
    p_BoN_B_.resize(3, count);
    phi_.resize(3 * count, data.phi.cols());
    for (Eigen::Index v = 0; v < count; ++v) {
      const int node = nodes[static_cast<std::size_t>(v)];
      p_BoN_B_.col(v) = data.node_positions.col(node);
      phi_.middleRows<3>(3 * v) = data.phi.middleRows<3>(3 * static_cast<Eigen::Index>(node));
    }
    polygon_sizes_ = data.visual_surface.face_sizes;
    polygon_points_.reserve(data.visual_surface.face_nodes.size());
    for (int node : data.visual_surface.face_nodes) {
      polygon_points_.push_back(static_cast<int>(std::lower_bound(nodes.begin(), nodes.end(), node) - nodes.begin()));
    }
    return;
  }
  if (flexible != nullptr) {
    const std::vector<sid::Node>& nodes = flexible->data().nodes;
    p_BoK_B_.resize(3, static_cast<Eigen::Index>(nodes.size()));
    for (std::size_t k = 0; k < nodes.size(); ++k) {
      p_BoK_B_.col(static_cast<Eigen::Index>(k)) = nodes[k].origin.m0.col(0);
    }
  } else if (const auto* rigid = dynamic_cast<const RigidBody*>(&body)) {
    const std::vector<RigidBodyMarker>& markers = rigid->markers();
    p_BoK_B_.resize(3, static_cast<Eigen::Index>(markers.size()));
    for (std::size_t k = 0; k < markers.size(); ++k) {
      p_BoK_B_.col(static_cast<Eigen::Index>(k)) = markers[k].p_BoM_B;
    }
  }
}

BodyGeometry BodyDrawing::At(const ConstVectorRef& x_b) const {
  return polygon_sizes_.empty() ? StickFigureAt(x_b) : SurfaceAt(x_b);
}

BodyGeometry BodyDrawing::SurfaceAt(const ConstVectorRef& x_b) const {
  const Eigen::Vector3d p_WBo_W = x_b.head<3>();
  const Eigen::Matrix3d R_WB = RotationFromEulerParameters(x_b.segment<4>(3));
  const Eigen::VectorXd u_B = phi_ * x_b.tail(body_.num_modes());
  const Eigen::Map<const Eigen::Matrix3Xd> u_N_B(u_B.data(), 3, p_BoN_B_.cols());
  BodyGeometry geometry;
  geometry.u_P_W = R_WB * u_N_B;
  geometry.p_WP_W = (R_WB * p_BoN_B_ + geometry.u_P_W).colwise() + p_WBo_W;
  geometry.polygon_sizes = polygon_sizes_;
  geometry.polygon_points = polygon_points_;
  return geometry;
}

BodyGeometry BodyDrawing::StickFigureAt(const ConstVectorRef& x_b) const {
  const Eigen::Vector3d p_WBo_W = x_b.head<3>();
  const Eigen::Matrix3d R_WB = RotationFromEulerParameters(x_b.segment<4>(3));
  const Eigen::VectorXd u_b = Eigen::VectorXd::Zero(body_.num_velocities());
  const Eigen::Index count = p_BoK_B_.cols();
  BodyGeometry geometry;
  geometry.p_WP_W.resize(3, count + 1);
  geometry.u_P_W = Eigen::Matrix3Xd::Zero(3, count + 1);
  geometry.p_WP_W.col(0) = p_WBo_W;
  for (Eigen::Index k = 0; k < count; ++k) {
    const Eigen::Vector3d p_WK_W = body_.Marker(static_cast<int>(k), x_b, u_b).p_WM_W;
    geometry.p_WP_W.col(k + 1) = p_WK_W;
    if (body_.num_modes() > 0) geometry.u_P_W.col(k + 1) = p_WK_W - (p_WBo_W + R_WB * p_BoK_B_.col(k));
    geometry.line_points.push_back(0);
    geometry.line_points.push_back(static_cast<int>(k + 1));
  }
  if (count == 0) geometry.vertex_points.push_back(0);
  return geometry;
}

}  // namespace flexmbs::mbs
