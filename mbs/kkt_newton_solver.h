#pragma once
// The implicit integrator's Newton systems (I - gamma J) [dx; du] = [r_x; r_u] of a multibody
// system, solved through a sparse augmented (KKT) system instead of the dense LU of
// I - gamma J (docs/mbs.md, "The sparse Newton solve"). J is the model Jacobian of
// mbs/system_jacobian.h: the x' rows exactly (p' = v, e' = 1/2 e (x) (0, w_B), q' = qdot), the u'
// rows as
//   du'/du = A (dh/du) + Z (dgamma_c/du - 2 omega_B G),   du'/dtheta = A dh/dx - omega_B^2 Z G
// (A = M^-1 - Z G M^-1, Z = M^-1 G^T S^-1 over the kept constraint rows, gamma_c the joints'
// acceleration terms, theta the velocity-space position increments of
// MultibodySystem::DisplacePositions). dh/dx, dh/du are the bodies' and force elements' stiff
// parts; in the bodies' v and w_B columns, where SystemJacobian takes forward differences of the
// whole u', this solve takes the same differences of what depends on them locally: each body's h
// (gyroscopic and centrifugal terms) and each joint's gamma_c (the columns of its two bodies).
// They agree with SystemJacobian's columns to the differences' accuracy but for the geometric
// stiffening's acceleration corrector, whose u'_0 SystemJacobian's differences move too
// (A N du'_0/du, first order in the deformation; the elastic columns leave it out either way).
//
// Eliminating dx (the quaternion block exactly: E = (I4 - gamma D(w_B))^-1 in closed form) and
// writing u' = A a + Z s as the saddle-point solve it is gives, per Newton system,
//
//   [ K    G^T ] [du]   [ M r_u + gamma dh/dx rho       ]
//   [ G_c  0   ] [nu] = [ G (r_u - gamma omega_B^2 rho) ],
//
//   K   = M - gamma dh/du - gamma^2 dh/dx W,
//   G_c = G ((1 + 2 gamma omega_B) I + gamma^2 omega_B^2 W) - gamma dgamma_c/du,
//
// with W = blkdiag over bodies (I3, L^+ E L, I_n) and rho = [r_p; L^+ E r_e; r_q] (L = de/dtheta,
// L^+ its left inverse), then dx = [r_p + gamma dv; E (r_e + gamma L dw); r_q + gamma dqdot].
// M and the bodies' dh blocks are block diagonal, G has nonzeros only at the two bodies of a
// joint and a force element couples the bodies it loads, so the matrix is sparse: assembled per
// Factorize and factorised by a sparse LU (the pattern analysed once while it stays the same).
// In a planar scene the dropped velocities' rows and columns are identity (du = r_u there, zero
// in a run), so the factorised system is the in-plane one (docs/mbs.md, "Planar scenes").

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

#include "mbs/multibody_system.h"
#include "mbs/ode_integrator.h"

namespace flexmbs::mbs {

/// Wall time spent in each part of a KktNewtonSolver since construction [s], and the calls.
struct KktNewtonTimes {
  double evaluate = 0.0, factorize = 0.0, solve = 0.0;
  long evaluations = 0, factorizations = 0, solves = 0;
};

/// The sparse Newton solver of a multibody system (file comment); an OdeNewtonSolver for
/// OdeNewton::kSparse. Holds a reference to the system, which must outlive it. Systems whose
/// force elements have states of their own are not taken (FLEXMBS_CHECK; Simulate solves them
/// densely).
class KktNewtonSolver final : public OdeNewtonSolver {
 public:
  explicit KktNewtonSolver(const MultibodySystem& system);
  ~KktNewtonSolver() override;
  KktNewtonSolver(const KktNewtonSolver&) = delete;
  KktNewtonSolver& operator=(const KktNewtonSolver&) = delete;

  /// Evaluates and keeps the pieces of J at (t, y): the bodies' mass matrices, the bodies' and
  /// force elements' dh/dx, dh/du (at the accelerations of (t, y), as SystemJacobian; the bodies'
  /// v, w_B columns by differences), G and dgamma_c/du (v, w_B columns, by differences) over the
  /// kept constraint rows, the quaternion blocks: 1 evaluation of the accelerations, 7 of each
  /// body's forces, 13 of each joint. Throws SimulationError as MultibodySystem::Accelerations
  /// does.
  void Evaluate(double t, Eigen::Ref<const Eigen::VectorXd> y) override;
  /// Assembles and factorises the augmented matrix for gamma [s] > 0. Throws SimulationError
  /// (at the evaluated time) if the sparse LU finds it singular.
  void Factorize(double gamma) override;
  /// r = [r_x; r_u] (state size) -> [dx; du] solving (I - gamma J) [dx; du] = r.
  void Solve(Eigen::Ref<Eigen::VectorXd> r) override;

  /// The augmented matrix of the last Factorize ((n_u + m_kept) square), for tests and benches.
  const Eigen::SparseMatrix<double>& augmented_matrix() const { return kkt_; }
  /// Time spent in Evaluate, Factorize and Solve since construction.
  const KktNewtonTimes& times() const { return times_; }

 private:
  /// Per body: offsets, mass matrix, its own dh blocks, the quaternion blocks.
  struct BodyBlocks {
    Eigen::Index px = 0, pu = 0, nu = 0;
    Eigen::MatrixXd M, dh_dx, dh_du;
    Eigen::Matrix<double, 4, 3> L;        ///< de = L dtheta
    Eigen::Matrix<double, 3, 4> L_plus;   ///< (L^T L)^-1 L^T
    Eigen::Matrix4d D;                    ///< d e' / d e
    double w_squared = 0.0;               ///< |w_B|^2 [rad^2/s^2]: D^2 = -w_squared / 4 I
    Eigen::Matrix4d E;                    ///< (I4 - gamma D)^-1 (Factorize)
    Eigen::Matrix3d W;                    ///< L_plus E L (Factorize)
  };
  struct Factor;

  /// Per body: M, the stiff dh blocks (v, w_B columns of dh/du by differences of its h at the
  /// accelerations u_dot), the quaternion blocks.
  void EvaluateBodies(double t, const Eigen::Ref<const Eigen::VectorXd>& y, const Eigen::VectorXd& u_dot);
  /// G over the kept rows and their dgamma_c/du.
  void EvaluateConstraints(double t, const Eigen::Ref<const Eigen::VectorXd>& y);
  /// The force elements' dh/dx, dh/du as (row, column, value) over the system's velocities.
  void EvaluateForceElements(double t, const Eigen::Ref<const Eigen::VectorXd>& y);
  /// dgamma_c/du in the v, w_B columns of each joint's bodies, over the kept rows (positions in
  /// `kept`), by forward differences of the joint's equations.
  void EvaluateGammaDifferences(double t, const Eigen::Ref<const Eigen::VectorXd>& y,
                                const std::vector<Eigen::Index>& kept);
  /// rho = [r_p; L^+ E r_e; r_q] per body from r_x.
  Eigen::VectorXd VelocitySpacePositionResidual(const Eigen::Ref<const Eigen::VectorXd>& r_x) const;

  const MultibodySystem& system_;
  std::vector<BodyBlocks> bodies_;
  std::vector<Eigen::Triplet<double>> element_dh_dx_, element_dh_du_;
  std::vector<Eigen::Triplet<double>> gamma_du_;  // kept row x n_u
  Eigen::MatrixXd element_scratch_dx_, element_scratch_du_;  // n_u x n_u, kept zero between uses
  Eigen::SparseMatrix<double, Eigen::RowMajor> G_;           // kept rows x n_u
  Eigen::SparseMatrix<double> dh_dx_;                        // n_u x n_u, bodies' and elements'
  double t_ = 0.0, gamma_ = 0.0, omega_ = 0.0;
  bool evaluated_ = false, factorized_ = false;
  Eigen::SparseMatrix<double> kkt_;
  std::vector<char> dropped_;  // per velocity: dropped by a planar scene (empty: spatial)
  std::unique_ptr<Factor> factor_;
  KktNewtonTimes times_;
};

}  // namespace flexmbs::mbs
