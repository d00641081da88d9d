#pragma once
// What a body looks like at a state, for viewing (docs/results.md, "ParaView files"): a
// flexible body as its deformed visual surface (sid::VisualSurface), any other body as a stick
// figure of its frame origin and markers.

#include <Eigen/Core>
#include <vector>

#include "mbs/body.h"

namespace flexmbs::mbs {

/// A body's drawing at one state, in W: points and cells as VTK poly data (point indices
/// 0-based into the points).
struct BodyGeometry {
  Eigen::Matrix3Xd p_WP_W;             ///< the points [m]
  Eigen::Matrix3Xd u_P_W;              ///< their elastic displacement R_WB phi_N q [m]; zero if rigid
  std::vector<int> vertex_points;      ///< one-point cells
  std::vector<int> line_points;        ///< two-point cells, two indices each
  std::vector<int> polygon_sizes;      ///< per polygon: its number of points
  std::vector<int> polygon_points;     ///< the polygons' points, concatenated
  Eigen::Index num_cells() const {
    return static_cast<Eigen::Index>(vertex_points.size() + line_points.size() / 2 + polygon_sizes.size());
  }
};

/// How one body is drawn, set up once from the body (which must outlive it):
/// - a FlexibleBody with a visual surface: its polygons through the surface's FE nodes N only,
///   at p_WN_W = p_WBo_W + R_WB (p_BoN_B + phi_N q), displaced by u_N_W = R_WB phi_N q
///   (docs/sid.md; the floating frame's kinematics, docs/mbs.md);
/// - any other body: a stick figure, the frame origin Bo (point 0) joined by a line to each of
///   its markers (rigid markers, or a flexible body's SID nodes at their deformed positions with
///   displacement p_WK_W - (p_WBo_W + R_WB o0)); a body without markers is the point Bo alone.
class BodyDrawing {
 public:
  explicit BodyDrawing(const Body& body);

  /// The drawing at the body's positions x_b = [p_WBo_W, e, q] (size body.num_positions()).
  BodyGeometry At(const ConstVectorRef& x_b) const;

 private:
  BodyGeometry SurfaceAt(const ConstVectorRef& x_b) const;
  BodyGeometry StickFigureAt(const ConstVectorRef& x_b) const;

  const Body& body_;
  // Visual surface (empty: stick figure). Per used FE node v: p_BoN_B and rows 3 v .. 3 v + 2 of phi.
  Eigen::Matrix3Xd p_BoN_B_;
  Eigen::MatrixXd phi_;
  std::vector<int> polygon_sizes_, polygon_points_;
  // Stick figure: the undeformed origins p_BoK_B of markers 0 .. K - 1.
  Eigen::Matrix3Xd p_BoK_B_;
};

}  // namespace flexmbs::mbs
