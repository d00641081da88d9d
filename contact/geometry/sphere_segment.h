#pragma once
// A sphere (in a planar scene: a circle) against a finite segment whose ends act as corners
// (docs/contact.md, "Planar scenes").

#include <Eigen/Core>

#include "contact/geometry/point_contact.h"

namespace flexmbs::contact {

/// The top of a solid: the segment from end E1 at p_WE1_W to end E2 at p_WE2_W [m], extruded
/// without bound along the unit axis e_W (perpendicular to E2 - E1; in a planar scene W's z, where
/// it is the 2-D segment). Its outward normal n = e x d with d = (E2 - E1) / |E2 - E1|: the free
/// side is on the left walking from E1 to E2, seen from +e. The solid beneath is the slab
/// {0 <= d . (p - E1) <= |E2 - E1|, n . (p - E1) <= 0}: its top the segment, its sides the planes
/// through the ends with normals -d and +d, its edges the lines through the ends along e.
struct Segment {
  Eigen::Vector3d p_WE1_W = Eigen::Vector3d::Zero();
  Eigen::Vector3d p_WE2_W = Eigen::Vector3d::UnitX();
  Eigen::Vector3d e_W = Eigen::Vector3d::UnitZ();
};

/// Sphere A (centre C, radius r) against the segment's solid B, by where C projects, s = d . (C -
/// E1):
/// - on the segment (0 <= s <= L = |E2 - E1|): the line, SpherePlane with the plane through E1 of
///   normal n (g_N = n . (C - E1) - r);
/// - beyond an end E (s < 0: E1, s > L: E2) and above it (n . (C - E) > 0): the corner, the point Q
/// of
///   the edge through E along e nearest C (Q = E + e e . (C - E)), n_W = (C - Q) / |C - Q|,
///   g_N = |C - Q| - r, p_WA_W = C - r n_W, p_WB_W = Q (the ends act as corners: a circle rolls
///   over them about Q);
/// - beyond an end and not above it: that end's side, the plane through E of normal -d (E1) or +d
/// (E2). The three agree where the regions meet (g_N, n_W, the contact points continuous). Throws
/// DegenerateContactError when C lies on an edge (|C - Q| <= 1e-12 r: no normal). Preconditions
/// (InternalError): r > 0, |E2 - E1| > 0, |e_W| = 1 within 1e-9, e_W . d within 1e-9 of 0.
PointContactKinematics SphereSegment(const Sphere& sphere, const Segment& segment);

}  // namespace flexmbs::contact
