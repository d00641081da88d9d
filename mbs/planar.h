#pragma once
// Planar scenes (docs/mbs.md, "Planar scenes"; the thesis' planar chapters): every body moves in
// the plane z = 0 of W, keeping the velocity columns v_x, v_y, w_z of its block and its in-plane
// modes; the solves (ConstraintSolver, Moreau-Jean's KKT matrix, the sparse Newton matrix) gather
// those columns and scatter zeros back into the dropped ones, while u keeps its spatial layout.

#include <string>

#include "mbs/multibody_system.h"

namespace flexmbs::mbs {

/// A number below this share of its scale counts as zero in the planar checks of the input (an
/// out-of-plane component of gravity, a position, an axis or a velocity).
inline constexpr double kPlanarTolerance = 1e-9;
/// A body's mass matrix couples a kept and a dropped column by nothing when |M_ij| is below this
/// share of sqrt(M_ii M_jj): a reduced body's integrals over its mirror-symmetric mesh cancel to
/// the FE data's round-off (1.2e-9 measured on the slider-crank's hex20 rod), which moves the
/// dropped columns by as little.
inline constexpr double kPlanarCoupling = 1e-6;

/// A flexible body's mode is in-plane when its reflection z -> -z (the FE nodes mirrored about
/// B's xy plane, u_z negated) departs from it by at most this share of its norm, out-of-plane
/// when it departs as little from its negative: the eigenvectors of a mirror-symmetric mesh are
/// even or odd to round-off (~1e-13, tests/validation/slider_crank_model.cc).
inline constexpr double kPlanarModeSymmetry = 1e-6;
/// FE nodes pair with their mirror images within this share of the mesh's largest coordinate.
inline constexpr double kMirrorDistance = 1e-9;

/// Makes `system` planar in W's xy plane at the initial state y0 (MultibodySystem::
/// set_kept_velocities) after checking that the scene is planar there. Throws a one-line
/// InputError "<item>: <problem>" naming the item and its value for: gravity with a
/// z component; a body whose centre of mass starts off z = 0, whose rotation axis is not z, with
/// an initial v_z, w_x, w_y or a dropped mode's q or qdot; a flexible body without mode shapes,
/// with a mesh that is not mirror-symmetric about its xy plane or with a mode that is neither
/// in-plane nor out-of-plane (kPlanarModeSymmetry); a body whose mass
/// matrix couples a kept and a dropped column (a rigid body: centre of mass off its xy plane,
/// J_xz or J_yz); a revolute joint whose axis is not z, a prismatic one whose axis is not in the
/// plane, a cylindrical one whose axis is neither; a universal joint; a unilateral contact whose
/// normal at y0 is not in the plane. Force elements are not checked (their out-of-plane loads are
/// dropped with the columns).
void MakePlanar(MultibodySystem& system, const ConstVectorRef& y0);

/// The in-plane tangent of a planar contact with normal n_W (in the plane): t = z x n, so that
/// (n, t, z) is right-handed.
Eigen::Vector3d PlanarTangent(const Eigen::Vector3d& n_W);

/// The dimension d of a system's contact problems (FrictionContactProblem): 2 in a planar scene
/// (the normal and the one in-plane tangent: Coulomb's two-sided cone, exact), 3 otherwise.
Eigen::Index ContactDimension(const MultibodySystem& system);

/// A contact point's d - 1 tangents: their directions in W and the rows of the tangential
/// relative velocity through u.
struct ContactTangents {
  Eigen::Matrix3Xd t_W;  ///< 3 x (d - 1)
  Eigen::MatrixXd W_T;   ///< (d - 1) x num_velocities()
};
/// d = 3: t1_W, t2_W and W_T as the contact gives them; d = 2: t = PlanarTangent(n_W) and its row
/// (t . t1) W_T1 + (t . t2) W_T2.
ContactTangents Tangents(const UnilateralContactKinematics& c, Eigen::Index d);

/// Turns a planar contact point's tangent frame about n_W to t1 = PlanarTangent(n_W) (in the
/// plane), t2 = z (n x t1 = t2 as before), with W_T's rows turned alike: the same kinematics in
/// the frame whose first tangent is the planar problem's (event-driven's d = 2 rows W_N, W_T1).
void UsePlanarTangents(UnilateralContactKinematics& c);

}  // namespace flexmbs::mbs
