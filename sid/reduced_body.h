#pragma once
// The content of a `.sid.h5` file (docs/sid.md): everything a floating-frame-of-reference
// solver needs about one flexible body, as SID Taylor blocks (Wallrapp 1994; Schwertassek &
// Wallrapp, "Dynamik flexibler Mehrkoerpersysteme", 1999), plus the FE nodes, the basis, the
// geometric-stiffening split, marker nodes, contact surfaces and provenance.
//
// Frames and coordinates. B is the body frame of the FE model (the mesh's coordinates), Bo its
// origin. A material point at r (undeformed, in B) moves by u(r) = Phi(r) q; phi_j is mode j's
// displacement field, x~ the skew matrix of x (x~ y = x cross y). Every integral runs over the
// undeformed body, dm = rho dV, and is evaluated exactly from the consistent mass matrix.

#include <Eigen/Core>
#include <array>
#include <map>
#include <string>
#include <vector>

#include "sid/taylor.h"

namespace flexmbs::sid {

/// The stress-stiffening matrices of the body (n x n each, [N/m per unit q^2 per unit load]):
/// K0 = Phi^T K_G(sigma) Phi, with sigma the static stress field of one unit load case of the
/// body held as in its reduction (free bodies: inertia relief). A solver adds
/// sum_c load_c K0_c to the elastic stiffness (tension stiffens).
struct GeometricStiffening {
  /// Per axis a of B: the body force -rho e_a, i.e. a unit acceleration [m/s^2] of Bo along a.
  std::array<Eigen::MatrixXd, 3> K0t;
  /// Per axis a of B: the body force -rho e_a x r, a unit angular acceleration [rad/s^2].
  std::array<Eigen::MatrixXd, 3> K0r;
  /// Per product l of omega_q = [w1^2, w2^2, w3^2, w1 w2, w2 w3, w3 w1] [rad^2/s^2]: the body
  /// force -rho dW/d(omega_q,l) r with W = w~ w~ (the centrifugal load of unit products).
  std::array<Eigen::MatrixXd, 6> K0omega;
  bool empty() const { return K0t[0].size() == 0; }
};

/// A marker or interface node: where joints and forces attach (the SID `frame` node data).
struct Node {
  std::string name;
  std::vector<int> fe_nodes;  ///< the FE nodes it is coupled to (0-based into node_positions)
  std::string coupling;       ///< "node" (one FE node), "rigid" or "averaging"
  /// origin: m0 = p_BoK_B (3 x 1) [m]; m1[j] = the node's displacement in mode j [m/q].
  TaylorMatrix origin;
  /// phi: m0 = translational mode shapes (3 x n) [m/q]; m1[j](a, i) = -K0F_a(i, j), the
  /// stiffening by a unit force at the node along axis a of B (empty if not computed).
  TaylorMatrix phi;
  /// psi: m0 = rotational mode shapes (3 x n) [rad/q]; m1[j](a, i) = -K0M_a(i, j), the
  /// stiffening by a unit moment at the node about axis a (empty if not computed).
  TaylorMatrix psi;
  /// AP: m0 = orientation of the node frame in B (3 x 3); m1[j] = psi_j~ (the small rotation
  /// of mode j).
  TaylorMatrix AP;
};

/// A named contact surface: a polygon mesh of boundary faces with the modal displacements of
/// its vertices, so contact can deform it without the full mesh.
struct ContactSurface {
  std::string name;
  std::vector<int> fe_nodes;          ///< per vertex: its FE node (0-based)
  Eigen::MatrixX3d vertices;          ///< V x 3: p_BoV_B [m], undeformed
  std::vector<int> face_sizes;        ///< per face: its number of vertices (3 or 4)
  std::vector<int> face_vertices;     ///< the faces' vertex indices (0-based into vertices), concatenated,
                                      ///< counter-clockwise seen from outside
  Eigen::MatrixX3d face_normals;      ///< F x 3: unit outward normals in B, undeformed
  Eigen::MatrixXd phi;                ///< 3 V x n: row 3 v + a is vertex v along axis a [m/q]
};

/// The outer surface of the mesh for visualisation: every boundary face of the mesh as linear
/// polygons through FE nodes (quadratic faces split through their mid-side nodes, as
/// fem::BoundarySurface does), counter-clockwise seen from outside. A vertex N moves with the
/// body's basis: p_BoN_B + phi_N q (ReducedBody::node_positions, ReducedBody::phi).
struct VisualSurface {
  std::vector<int> face_sizes;  ///< per polygon: its number of nodes (3 or 4)
  std::vector<int> face_nodes;  ///< the polygons' FE nodes (0-based into node_positions), concatenated
  bool empty() const { return face_sizes.empty(); }
};

/// A reduced flexible body: the SID data and what it was made from (docs/sid.md).
struct ReducedBody {
  std::string name;

  // --- refmod -------------------------------------------------------------------------------
  double mass = 0.0;                       ///< m [kg]
  Eigen::Vector3d center_of_mass = Eigen::Vector3d::Zero();  ///< p_BoCm_B [m]
  Eigen::Matrix3d inertia_about_center_of_mass = Eigen::Matrix3d::Zero();  ///< I_Cm_B [kg m^2]
  std::vector<std::string> mode_names;     ///< one per modal coordinate, unique
  std::vector<std::string> mode_kinds;     ///< "rigid", "normal", "constraint", "static_correction"
  Eigen::VectorXd frequency_hz;            ///< per mode; NaN for constraint and correction modes
  Eigen::VectorXd relative_residuals;      ///< per mode; NaN where not an eigenpair of the full model
  std::string damping;                     ///< how De was made, one line ("none", "modal 2 %", ...)

  // --- SID invariants (Taylor blocks in q; definitions in docs/sid.md) ----------------------
  TaylorMatrix mdCM;    ///< 3 x 1 [kg m]
  TaylorMatrix J;       ///< 3 x 3 [kg m^2], order 2
  TaylorMatrix Ct;      ///< n x 3 [kg]
  TaylorMatrix Cr;      ///< n x 3 [kg m]
  TaylorMatrix Me;      ///< n x n [kg]
  TaylorMatrix Gr;      ///< 3 x 3n [kg m]
  TaylorMatrix Ge;      ///< n x 3n [kg]
  TaylorMatrix Oe;      ///< n x 6 [kg m]
  TaylorMatrix Ke;      ///< n x n [N/m]
  TaylorMatrix De;      ///< n x n [N s/m]
  TaylorMatrix ksigma;  ///< n x 1 [N]: generalised forces of the initial stress
  /// The stiffening part of the order-1 terms of Ct, Cr, Oe, kept apart so a solver can leave
  /// it out; empty if the body file switched it off.
  GeometricStiffening stiffening;

  // --- basis and mesh -----------------------------------------------------------------------
  Eigen::Matrix3Xd node_positions;   ///< p_BoN_B of every FE node [m]
  std::map<std::string, std::vector<int>> node_sets;  ///< named FE node indices
  /// 3 n_nodes x n: DOF 3 node + axis per unit modal coordinate [m/q].
  Eigen::MatrixXd phi;

  std::vector<Node> nodes;
  std::vector<ContactSurface> surfaces;
  /// The mesh's boundary for viewing the deformed body; empty for files of schema 2.
  VisualSurface visual_surface;

  /// Free-form provenance: source files and their hashes, mesh counts, material, reduction
  /// settings, eigensolver, residuals, tool version.
  std::map<std::string, std::string> provenance;

  Eigen::Index num_modes() const { return phi.cols(); }
};

}  // namespace flexmbs::sid
