#pragma once

// Geometric (stress) stiffening of a reduced body: the SID stiffening matrices
//
//     K0_c = Phi^T K_G(sigma_c) Phi   (n x n),
//
// sigma_c the linear-elastic stress of the static response x_c of the body, held as in its
// reduction (static_response.h: supports clamped and interfaces held; a free-free body by
// inertia relief), to unit load case c (Wallrapp 1994; Schwertassek & Wallrapp, "Dynamik
// flexibler Mehrkoerpersysteme", 1999; K_G: fem/geometric_stiffness.h). The load cases, in B
// with r = p_BoP_B the undeformed position of a material point:
//
//   K0t_a      body force density -rho e_a          (unit acceleration [m/s^2] of Bo along a)
//   K0r_a      body force density -rho e_a x r      (unit angular acceleration [rad/s^2] about a)
//   K0omega_l  body force density -rho W_l r        (unit product l of omega_q, W_l = d(w~ w~)/d omega_q,l:
//              W_1 = diag(0,-1,-1), W_2 = diag(-1,0,-1), W_3 = diag(-1,-1,0), W_4 = e1 e2^T + e2 e1^T,
//              W_5 = e2 e3^T + e3 e2^T, W_6 = e3 e1^T + e1 e3^T)
//   K0F_a      unit force [N] along a at a node
//   K0M_a      unit moment [N m] about a at a node
//
// A body force density rho b(r) with b linear in r has the consistent nodal load M b_nodes
// exactly (isoparametric elements interpolate a linear field exactly: f_a = int N_a rho b dV =
// sum_b int rho N_a N_b dV b(x_b)); this needs the consistent M. A node's load enters through
// its coupling as W^T [F; M] (W: RigidFitOperator, the RBE3 distribution, statically
// equivalent to the load at the marker and the transpose of the marker motion W Phi that is the
// node's SID phi/psi); a single FE node (kNodes) takes the force on its own DOF and no moment.
// Loads on held DOF, or at a held interface, go straight into the hold and cause no stress
// (G^T f = 0): their K0 is zero. The solver adds sum_c load_c K0_c to Ke (tension stiffens).

#include <Eigen/Core>
#include <array>
#include <span>
#include <vector>

#include "fem/mesh.h"
#include "reduction/interface_coupling.h"
#include "reduction/modal_basis.h"
#include "sid/reduced_body.h"

namespace flexmbs::reduction {

/// The stiffening of one node by unit loads there, n x n each [N/m per q^2 per N or N m].
struct NodeStiffening {
  std::array<Eigen::MatrixXd, 3> K0F;  ///< unit force along axis a of B
  /// Unit moment about axis a of B; empty (0 x 0) for a single FE node, which takes no moment.
  std::array<Eigen::MatrixXd, 3> K0M;
};

/// The stiffening matrices of a body and of its nodes.
struct StiffeningResult {
  sid::GeometricStiffening body;
  std::vector<NodeStiffening> nodes;  ///< one per requested node, in order
};

/// The unit load vectors of the stiffening load cases (3 num_nodes x (12 + 6 per node), DOF
/// 3 n + i) [N per unit load]: columns t_x, t_y, t_z, r_x, r_y, r_z, omega_1 .. omega_6 (see the
/// file comment; f = M b_nodes), then per node F_x, F_y, F_z, M_x, M_y, M_z (a kNodes node: its
/// three force columns only). Throws InputError (naming the node) for a kNodes node without
/// exactly one FE node, a node index out of range, and the errors of RigidFitOperator.
/// Precondition: a valid model.
Eigen::MatrixXd BuildStiffeningLoads(const FeModel& model, std::span<const InterfaceSpec> nodes);

/// How ProjectedStiffeningMatrices forms Phi^T K_G(sigma(x_c)) Phi; the results agree to round-off.
enum class StiffeningProjection {
  /// kAssembled where AssembledProjectionIsFaster, else kElementByElement.
  kAuto,
  /// fem::ProjectedGeometricStiffness: per quadrature point, O(points n^2 (C + 6)) in all.
  kElementByElement,
  /// Per case: K_G assembled (fem::AssembleGeometricStiffness), its scalar part K_Gs
  /// (K_G = K_Gs (x) I_3), then sum_a Phi_a^T K_Gs Phi_a over the components a of the modes:
  /// O(C (nnz(K_G) + nnz(K_Gs) n + num_nodes n^2)) in all.
  kAssembled,
};

/// Whether kAssembled is the faster way for n modes and C load cases: n >= min(24 + C / 3, 40)
/// (the measurement: geometric_stiffening.cc).
bool AssembledProjectionIsFaster(Eigen::Index num_modes, Eigen::Index num_cases);

/// Phi^T K_G(sigma(x_c)) Phi (n x n, symmetric) [N/m per unit modal coordinate squared, per unit
/// load] for every column x_c of X (3 num_nodes x C) [m], Phi (3 num_nodes x n) [m per unit
/// modal coordinate]; a zero column gives a zero matrix. Throws InputError for rows other than
/// the mesh's DOF and for an element with a non-positive Jacobian (fem/geometric_stiffness.h).
std::vector<Eigen::MatrixXd> ProjectedStiffeningMatrices(const fem::Mesh& mesh, const Eigen::MatrixXd& X,
                                                         const Eigen::MatrixXd& Phi,
                                                         StiffeningProjection how = StiffeningProjection::kAuto);

/// K0t, K0r, K0omega of the body and K0F, K0M of every node in `nodes` for the basis Phi
/// (3 num_nodes x n), all load cases solved with one factorisation (SolveStaticResponses) of
/// the body held as `held_by` (the basis's held_by), and projected by
/// ProjectedStiffeningMatrices (kAuto). `model` is the FE model of `mesh` with its consistent
/// mass matrix. `held`: the basis's factorisation of the held body
/// (ReducedBasis::held_factorization), reused instead of a new one; null: factorise here.
/// Throws a one-line InputError for: a bad model, a mesh of another node count, a basis of
/// another size, bad nodes (BuildStiffeningLoads), conditions that do not hold the body, and
/// the static solve's errors. Precondition: `held`, if given, was made for `held_by` and K.
StiffeningResult ComputeGeometricStiffening(const fem::Mesh& mesh, const FeModel& model,
                                            const BoundaryConditions& held_by, const Eigen::MatrixXd& Phi,
                                            std::span<const InterfaceSpec> nodes = {},
                                            const HeldFactorization* held = nullptr);

}  // namespace flexmbs::reduction
