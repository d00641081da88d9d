#pragma once

#include <Eigen/Core>
#include <array>
#include <stdexcept>
#include <string>

namespace flexmbs::contact {

/// A sphere: centre p_WS_W [m] and radius [m] > 0, in the world frame W.
struct Sphere {
  Eigen::Vector3d p_WS_W = Eigen::Vector3d::Zero();
  double radius = 0.0;
};

/// A plane through the point p_WP_W [m] with unit normal n_W pointing out of the solid (the
/// half space below the plane is the obstacle).
struct Plane {
  Eigen::Vector3d p_WP_W = Eigen::Vector3d::Zero();
  Eigen::Vector3d n_W = Eigen::Vector3d::UnitZ();
};

/// The kinematics of one point contact between shape A and shape B, all in W (Glocker 2001,
/// "Set-Valued Force Laws", ch. 7; Acary & Brogliato 2008, §3.1): the gap g_N [m] (> 0 apart,
/// < 0 interpenetrating), the unit normal n_W pointing from B to A (A moves away from B along
/// +n_W), the tangents t1_W, t2_W with (n_W, t1_W, t2_W) a right-handed orthonormal frame
/// (n_W x t1_W = t2_W; TangentBasis), and the contact points p_WA_W on A's surface and p_WB_W on
/// B's surface (p_WA_W - p_WB_W = g_N n_W).
struct PointContactKinematics {
  double g_N = 0.0;
  Eigen::Vector3d n_W = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d t1_W = Eigen::Vector3d::UnitX();
  Eigen::Vector3d t2_W = Eigen::Vector3d::UnitY();
  Eigen::Vector3d p_WA_W = Eigen::Vector3d::Zero();
  Eigen::Vector3d p_WB_W = Eigen::Vector3d::Zero();
};

/// A contact whose normal is undefined (two sphere centres that coincide): the caller names the
/// pair and the time.
class DegenerateContactError : public std::runtime_error {
 public:
  explicit DegenerateContactError(const std::string& what) : std::runtime_error(what) {}
};

/// Two unit tangents t1, t2 to the unit normal n (|n| = 1 to round-off) with n x t1 = t2, by the
/// branch-free construction of Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 6(1),
/// 2017 (Frisvad's basis without its singularity at n_z = -1; discontinuous only where n_z
/// changes sign). n = +z gives t1 = +x, t2 = +y; the tangents depend on n alone, so a fixed plane
/// keeps its tangents for the whole run.
void TangentBasis(const Eigen::Vector3d& n_W, Eigen::Vector3d* t1_W, Eigen::Vector3d* t2_W);

/// Sphere A against plane B: g_N = n . (p_S - p_P) - r, n_W = the plane's normal, p_WA_W =
/// p_S - r n (the sphere's lowest point), p_WB_W = p_S - (g_N + r) n (its foot on the plane).
/// Preconditions (InternalError): radius > 0, |plane.n_W| = 1 within 1e-9.
PointContactKinematics SpherePlane(const Sphere& sphere, const Plane& plane);

/// Point A at p_WA_W (a corner of a box, a vertex of a mesh) against plane B: g_N = n . (p - p_P),
/// n_W = the plane's normal, p_WB_W = p - g_N n (its foot on the plane). Precondition
/// (InternalError): |plane.n_W| = 1 within 1e-9.
PointContactKinematics PointPlane(const Eigen::Vector3d& p_WA_W, const Plane& plane);

/// The 8 corners of a box with the half extents h [m] (> 0) about its frame's origin, in that
/// frame: (±h_x, ±h_y, ±h_z), x changing fastest, then y, then z (the first four the -z face).
std::array<Eigen::Vector3d, 8> BoxCorners(const Eigen::Vector3d& half_extents);

/// The support points of a cylinder of radius r and half length h [m] (> 0) about its frame C's
/// origin, its axis C's z axis, against a plane whose unit normal is n_C in C's components: on
/// each end circle (z = -h, then z = +h) the point lowest along n_C, r d with d the unit
/// projection of -n_C onto the circle's plane, then the two 120 degrees on either side of it,
/// in C [m]. Rolling on its side the lowest points are the contact line's ends; standing on an
/// end face (n_C along the axis, where d is C's x axis) the three points of that face hold it.
/// The lowest point moves along the rim perpendicular to n: its velocity along n is that of the
/// material point there.
std::array<Eigen::Vector3d, 6> CylinderSupportPoints(double radius, double half_length, const Eigen::Vector3d& n_C);

/// Sphere A against sphere B: with d = p_SA - p_SB, l = |d|: g_N = l - r_A - r_B, n_W = d / l,
/// p_WA_W = p_SA - r_A n, p_WB_W = p_SB + r_B n. Throws DegenerateContactError if l <= 1e-12
/// (r_A + r_B): coincident centres have no normal. Precondition (InternalError): radii > 0.
PointContactKinematics SphereSphere(const Sphere& a, const Sphere& b);

}  // namespace flexmbs::contact
