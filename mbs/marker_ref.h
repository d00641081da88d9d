#pragma once
// Where a joint or force element attaches: a marker of a body of the system, or a frame fixed
// in the world (the ground).

#include <Eigen/Core>

namespace flexmbs::mbs {

/// The body index of the ground.
inline constexpr int kGround = -1;

/// Marker `marker` (an index from Body::FindMarker) of body `body` (an index into the system's
/// bodies), or, with body == kGround, the fixed frame (p_WM_W [m], R_WM).
struct MarkerRef {
  int body = kGround;
  int marker = -1;
  Eigen::Vector3d p_WM_W = Eigen::Vector3d::Zero();
  Eigen::Matrix3d R_WM = Eigen::Matrix3d::Identity();

  /// A fixed frame of the ground.
  static MarkerRef Ground(const Eigen::Vector3d& p_WM_W, const Eigen::Matrix3d& R_WM = Eigen::Matrix3d::Identity()) {
    return {kGround, -1, p_WM_W, R_WM};
  }
  /// Marker `marker` of body `body`.
  static MarkerRef OnBody(int body, int marker) { return {body, marker, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity()}; }
  bool is_ground() const { return body == kGround; }
};

}  // namespace flexmbs::mbs
