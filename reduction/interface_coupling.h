#pragma once

// How a body is held and where it connects: supports (node sets held in all or some of x, y, z)
// and interfaces (node sets, or markers coupled to node sets rigidly or by averaging), turned
// into one linear transformation of the FE displacements that every reduction (fixed-interface
// modes, Craig-Bampton, static correction modes) works with.
//
// Equations. DOF 3 n + i is node n along axis i of the body frame B (fem::Mesh). A marker at
// x_m has the six coordinates q = [t; theta] (translation [m], small rotation [rad], in B). A
// point at r = x - x_m moved rigidly with the marker has
//
//     u = t + theta x r = S(r) q,   S(r) = [I_3, -r~]  (3 x 6, r~ the skew matrix of r).
//
// * Node set (kNodes): the interface DOF are the 3 DOF of every node; q_b = u_c.
// * Rigid coupling (kRigid), MSC Nastran RBE2 with all six dependent components: every node
//   follows the marker rigidly, u_n = S(x_n - x_m) q, and the marker's six DOF are the boundary
//   DOF (MSC Nastran Quick Reference Guide, bulk data entry RBE2; Craig & Kurdila,
//   "Fundamentals of Structural Dynamics", 2nd ed. 2006, on constraints by coordinate
//   transformation).
// * Averaging (kAveraging), MSC Nastran RBE3 with translational weights (REFC = 123456,
//   Ci = 123): the marker motion is the weighted least-squares rigid fit of the nodes' motion,
//
//     q = argmin sum_n w_n |u_n - S(r_n) q|^2 = A^-1 sum_n w_n S(r_n)^T u_n =: W u,
//     A = sum_n w_n S(r_n)^T S(r_n)  (6 x 6, invertible iff the nodes are not on one line),
//
//   and the nodes stay free to deform (MSC Nastran Quick Reference Guide, RBE3; MSC Nastran
//   Reference Manual, "R-type elements"). A force/moment F at the marker acts on the nodes as
//   W^T F, which is the RBE3 load distribution. W is exact for rigid motions: W S q = q.
//
// The constrained displacements are parametrised by the boundary coordinates q_b (all
// interfaces, in order) and the interior DOF u_o:
//
//     u = B q_b + G u_o,
//
// with u = 0 on the supports' held components, u_c = T q_b on node-set and rigid interfaces
// (T = I or the stacked S(r_n)), and W u = q_b on averaging interfaces. For an averaging
// interface the constraint W u = q_b is solved for six of its node DOF ("dependent" DOF, chosen
// by column-pivoted QR of W so that the 6 x 6 block W_d is well conditioned):
// u_d = W_d^-1 (q_b - W_o u_o). This is
// Nastran's RBE3 with the dependent DOF moved to independent nodes ("UM" option); the interior
// problem G^T K G, G^T M G stays symmetric positive definite (no Lagrange multipliers), at the
// cost of a dense block over the averaging interface's node DOF.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace flexmbs::reduction {

/// How an interface's nodes are tied to its boundary DOF.
enum class Coupling {
  kNodes,      ///< the node set itself: 3 boundary DOF per node
  kRigid,      ///< RBE2-like: the nodes follow the marker rigidly; the marker's 6 DOF are boundary DOF
  kAveraging,  ///< RBE3-like: the marker moves with the weighted rigid fit of the nodes; nodes deform
};

/// "nodes", "rigid" or "averaging": the names used in files and messages.
std::string_view CouplingName(Coupling coupling);

/// One interface of a body: where joints, forces or other bodies attach.
struct InterfaceSpec {
  std::string name;        ///< unique among a body's interfaces and supports; names its modes
  std::vector<int> nodes;  ///< node indices (0-based into the mesh's nodes), no duplicates
  Coupling coupling = Coupling::kNodes;
  /// The marker p_BoMarker_B [m] (kRigid, kAveraging). Unset: the weighted centroid of the nodes.
  std::optional<Eigen::Vector3d> marker_position;
  /// kAveraging only: a weight w_n > 0 per node (e.g. the node's tributary area); empty: all 1.
  std::vector<double> weights;
};

/// A node set held to the ground: u = 0 along each held component of every node (all three:
/// clamped; some: as a Nastran SPC on components 1-3 holds them). Not a boundary DOF: no
/// constraint modes belong to it.
struct SupportSpec {
  std::string name;
  std::vector<int> nodes;  ///< node indices, no duplicates
  std::array<bool, 3> components = {true, true, true};  ///< held along x, y, z of B; at least one
};

/// What holds a body during a reduction. Empty: the body is free-free.
struct BoundaryConditions {
  std::vector<SupportSpec> supports;
  std::vector<InterfaceSpec> interfaces;
  bool empty() const { return supports.empty() && interfaces.empty(); }
};

/// S(r) = [I_3, -r~] (3 x 6): the displacement t + theta x r of a point at r from a marker that
/// moves by [t; theta].
Eigen::Matrix<double, 3, 6> RigidMotionMatrix(const Eigen::Vector3d& r);

/// The interface's marker position [m]: `marker_position` if set, else the weighted centroid of
/// its nodes (weights 1 unless kAveraging with weights). Preconditions: nodes in range.
Eigen::Vector3d MarkerPosition(const Eigen::Matrix3Xd& nodes, const InterfaceSpec& interface);

/// W (6 x 3 num_nodes, sparse): the weighted least-squares rigid fit [t; theta] = W u of the
/// interface nodes' motion about the marker (see the file comment), with the interface's
/// weights (kAveraging) or unit weights. For kRigid interfaces, whose nodes move rigidly, it
/// recovers the marker motion exactly. Throws InputError if the nodes lie on one line.
Eigen::SparseMatrix<double> RigidFitOperator(const Eigen::Matrix3Xd& nodes, const InterfaceSpec& interface);

/// The marker motion of each column of `Phi` (3 num_nodes x n): W Phi (6 x n), rows
/// [t_x, t_y, t_z, theta_x, theta_y, theta_z] in B [m, rad per unit modal coordinate]: the SID
/// `phi` (rows 0-2) and `psi` (rows 3-5) of the marker node. Throws InputError for a kNodes
/// interface (it has no marker).
Eigen::MatrixXd MarkerMotion(const Eigen::Matrix3Xd& nodes, const InterfaceSpec& interface,
                             const Eigen::MatrixXd& Phi);

/// The constrained displacement field u = B q_b + G u_o of a body with supports and interfaces
/// (see the file comment).
struct ConstraintTransform {
  /// One interface's boundary coordinates: q_b(first .. first + count - 1).
  struct InterfaceRange {
    std::string name;
    Coupling coupling = Coupling::kNodes;
    Eigen::Index first = 0;
    Eigen::Index count = 0;
  };

  Eigen::SparseMatrix<double> B;  ///< num_dofs x num_boundary: u for unit q_b, u_o = 0
  Eigen::SparseMatrix<double> G;  ///< num_dofs x num_interior: u for unit u_o, q_b = 0
  /// Per boundary coordinate: "<interface>_n<node>_<x|y|z>" (kNodes, node index 0-based) or
  /// "<interface>_<tx|ty|tz|rx|ry|rz>" (markers).
  std::vector<std::string> boundary_names;
  std::vector<InterfaceRange> interfaces;
  Eigen::Index num_support_dofs = 0;  ///< DOF held by supports (their held components)

  Eigen::Index num_dofs() const { return G.rows(); }
  Eigen::Index num_boundary() const { return B.cols(); }
  Eigen::Index num_interior() const { return G.cols(); }
};

/// Builds the transformation of `conditions` for a mesh with node positions `nodes` (3 x n).
/// Throws a one-line InputError naming the interface or support for: an empty name, a name
/// used twice, no nodes, a node index out of range or listed twice, a node in two interfaces or
/// in an interface and a support (supports may share nodes: the union of their components is
/// held), a support that holds no component, weights on a non-averaging interface or of the wrong count or not finite and > 0,
/// a non-finite marker, and (rigid, averaging) nodes on one line, which leave the marker's
/// rotation about the line undetermined.
ConstraintTransform BuildConstraintTransform(const Eigen::Matrix3Xd& nodes, const BoundaryConditions& conditions);

/// "interface 'a'", "interfaces 'a' and 'b'", "interface 'a' and support 's'": the conditions
/// named in messages.
std::string DescribeConditions(const BoundaryConditions& conditions);

}  // namespace flexmbs::reduction
