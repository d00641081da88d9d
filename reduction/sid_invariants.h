#pragma once

// The kinematic SID inertia invariants of a reduced flexible body (docs/sid.md, "/invariants"),
// exact from the FE mass matrix.
//
// Every invariant is an integral over the undeformed body of a product of two fields the mesh
// interpolates exactly: 1, r (isoparametric elements reproduce the position) and the modes
// phi_j. With M = M_s (x) I_3 (the element mass is m_e (x) I_3; checked), the integral of a
// product of components is int f_a g_b dm = f_a^T M_s g_b, f_a the nodal values of component a.
// So every invariant is read from two sets of such moments, formed once (N nodes, n modes,
// nnz = nonzeros of M_s, about nnz(M) / 9):
//
//   position moments  int dm, int r dm, int r r^T dm, int phi_j dm, int r phi_j^T dm:
//                     M_s [1 r] and a (4 x N)(N x 3n) product          O(nnz + N n)
//   mode products     int phi_j phi_k^T dm: M_s S, S the N x 3n matrix of the modes'
//                     components, and the symmetric product S^T (M_s S),
//                     both in blocks of nodes                            O(nnz n + N n^2)
//
// and the Taylor blocks are sums of entries of those (O(n^2) entries). mdCM, J (orders 0 and 1),
// Ct, and the order-0 blocks of Cr, Gr and Oe need only the position moments; Me, Ge, J's order
// 2 and the order-1 blocks of Cr, Gr and Oe need the mode products.
//
// Signs and index orders agree with MBSim's FlexibleBodyFFR (determineSID, updateMb) and with
// the SID written by J. Geisler's FEMBeam2SID (after Schwertassek & Wallrapp), including
// w_q = [w1^2, w2^2, w3^2, w1 w2, w2 w3, w3 w1]. MBSim stores Cr's order-1 part, Ge and Oe's
// order-1 part per axis as n x n matrices and J's order-2 term unsymmetrised
// (int phi_j~ phi_k~^T dm); the evaluated fields are the same.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>

#include "core/centrifugal.h"  // CentrifugalBasis, AngularVelocityProducts (Oe's columns)
#include "eigensolvers/model_operators.h"
#include "sid/taylor.h"

namespace flexmbs::reduction {

/// The kinematic (non-stiffening) SID inertia invariants of a basis Phi (docs/sid.md): with
/// rho = r + Phi q, the integrals below over the undeformed body, as Taylor blocks in q. "q" in
/// a unit is the unit of a modal coordinate.
struct InertiaInvariants {
  double mass = 0.0;  ///< m = int dm [kg]
  /// int rho dm (3 x 1) [kg m]: m0 = int r dm, m1[j] = int phi_j dm.
  sid::TaylorMatrix mdCM;
  /// int rho~ rho~^T dm (3 x 3) [kg m^2], inertia about Bo: m0 = int r~ r~^T dm,
  /// m1[j] = int (r~ phi_j~^T + phi_j~ r~^T) dm, m2[j n + k] = 1/2 int (phi_j~ phi_k~^T +
  /// phi_k~ phi_j~^T) dm (symmetric in j, k).
  sid::TaylorMatrix J;
  /// int Phi^T dm (n x 3) [kg m/q]: m0 only (its order-1 terms are stiffening).
  sid::TaylorMatrix Ct;
  /// int Phi^T rho~^T dm (n x 3) [kg m^2/q]: row i of m0 = (int r x phi_i dm)^T; row i of
  /// m1[j] = (int phi_j x phi_i dm)^T (kinematic part; antisymmetric in i, j).
  sid::TaylorMatrix Cr;
  /// int Phi^T Phi dm (n x n) [kg m^2/q^2].
  sid::TaylorMatrix Me;
  /// [Gr_1 .. Gr_n] (3 x 3n) [kg m^2/q], Gr_j = 2 int rho~^T phi_j~ dm, so that
  /// int rho~ (2 w~ Phi qdot) dm = sum_j Gr_j w qdot_j: block j of m0 = 2 int r~^T phi_j~ dm,
  /// block j of m1[k] = 2 int phi_k~^T phi_j~ dm.
  sid::TaylorMatrix Gr;
  /// [Ge_1 .. Ge_n] (n x 3n) [kg m^2/q^2], Ge_j = 2 int Phi^T phi_j~^T dm, so that
  /// 2 int Phi^T w~ Phi qdot dm = sum_j Ge_j w qdot_j: m0 only.
  sid::TaylorMatrix Ge;
  /// Oe (n x 6) [kg m^2/q], int Phi^T w~ w~ rho dm = Oe w_q (CentrifugalBasis): column l of m0
  /// = int Phi^T W_l r dm; m1[j](i, l) = int phi_i^T W_l phi_j dm (kinematic part).
  sid::TaylorMatrix Oe;
};

/// The scalar mass matrix M_s (N x N) of a mass matrix M (3N x 3N, DOF 3 node + axis) with
/// M = M_s (x) I_3, as every FE mass matrix of flexmbs (consistent or lumped). Checks that
/// structure (cross-axis entries zero, the three axes' entries equal, to 1e-13 of max |M|):
/// a broken one is a bug (InternalError). O(nnz(M)).
Eigen::SparseMatrix<double> ScalarMassMatrix(const Eigen::SparseMatrix<double>& M);

/// The modes' nodal components, N x 3n row-major: entry (v, a n + j) = Phi(3 v + a, j), i.e.
/// column a n + j is component a of mode j (Phi in row-major storage, reinterpreted).
using ModeComponents = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
ModeComponents SplitModeComponents(const Eigen::MatrixXd& Phi);

/// Mass moments of the fields 1 and r with themselves and with the modes.
struct PositionMoments {
  double mass = 0.0;                                       ///< int dm [kg]
  Eigen::Vector3d first_moment = Eigen::Vector3d::Zero();  ///< int r dm [kg m]
  Eigen::Matrix3d second_moment = Eigen::Matrix3d::Zero();  ///< int r r^T dm [kg m^2]
  Eigen::MatrixXd mode_integrals;  ///< 3 x n: column j = int phi_j dm [kg m/q]
  /// 3 x 3n: entry (b, a n + j) = int r_b phi_j,a dm [kg m^2/q].
  Eigen::MatrixXd position_mode_products;
};

/// The position moments from the scalar mass matrix M_s, the nodes p_BoN_B (3 x N) [m] and the
/// modes' components S (SplitModeComponents). O(nnz(M_s) + N n).
PositionMoments ComputePositionMoments(const Eigen::SparseMatrix<double>& M_s, const Eigen::Matrix3Xd& nodes,
                                       const ModeComponents& S);

/// The mode products (3n x 3n, symmetric): entry (a n + j, b n + k) = int phi_j,a phi_k,b dm
/// [kg m^2/q^2]. O(nnz(M_s) n + N n^2).
Eigen::MatrixXd ComputeModeProducts(const Eigen::SparseMatrix<double>& M_s, const ModeComponents& S);

/// The invariants read from the moments (n = mode_products.rows() / 3). O(n^2) entries.
InertiaInvariants InvariantsFromMoments(const PositionMoments& position, const Eigen::MatrixXd& mode_products);

/// The invariants of the basis Phi (3N x n [m/q], DOF 3 node + axis) of a body with mass matrix
/// M (3N x 3N [kg], full symmetric storage, as fem::AssembleSystem gives) and nodes p_BoN_B
/// (3 x N) [m]. Exact for the consistent mass of an isoparametric mesh: every integrand is a
/// product of two interpolated fields, the integral the one M's quadrature defines (with a
/// lumped M: the integrals of the lumped mass distribution).
InertiaInvariants ComputeInertiaInvariants(const Eigen::SparseMatrix<double>& M, const Eigen::Matrix3Xd& nodes,
                                           const Eigen::MatrixXd& Phi);
/// The same with M known by its products (ModelOperators: the distributed path of `reduce`):
/// the position moments from M times the fields 1, x, y, z on the x DOF, the mode products from
/// S^T (M Phi). Requires M = M_s (x) I_3 (not checked here). Agrees with the M_s form to round-off.
InertiaInvariants ComputeInertiaInvariants(const eigensolvers::SymmetricOperator& M, const Eigen::Matrix3Xd& nodes,
                                           const Eigen::MatrixXd& Phi);

}  // namespace flexmbs::reduction
