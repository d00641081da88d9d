#pragma once
// A floating-frame-of-reference flexible body (docs/mbs.md, "Equations of motion of a body"):
// the SID invariants of a reduced body (docs/sid.md) turned into M_b(x) and h_b(t, x, u).
//
// Positions x = [p_WBo_W, e, q], velocities u = [v_WBo_W, w_WB_B, qdot] (mbs/body.h). With
// R = R_WB(e) and the Taylor blocks at q,
//
//   M_b = [ m I          R mdCM~^T   R Ct^T ]    h_b = [ m g_W - R (w~ w~ mdCM + 2 w~ Ct^T qdot)                     ]
//         [ mdCM~ R^T    J           Cr^T   ]          [ mdCM~ R^T g_W - w~ J w - sum_j Gr_j w qdot_j                ]
//         [ Ct R^T       Cr          Me     ]          [ Ct R^T g_W - Oe w_q - sum_j Ge_j w qdot_j - Ke q - De qdot - ksigma ]
//
// with mdCM, J, Ct, Cr the kinematic blocks (the exact integrals of the FE model's mass: the
// file's order-1 Ct and Cr less the stiffening matrices; Oe's order-1 block less K0omega), so
// M_b is symmetric positive definite and the first two rows are the exact momentum balance.
// Geometric stiffening (docs/mbs.md, docs/sid.md), when on, is the inertia of the second-order
// displacement field of mbs/stiffening_inertia.h. In the elastic row that field gives SID's
// stiffening forces
//
//   - sum_a (a_B - g_B)_a K0t_a q - sum_a alpha_a K0r_a q - sum_l w_q,l K0omega_l q,
//
// a_B = R^T v', alpha = w', g_B = R^T g_W (the acceleration terms in
// AddAccelerationDependentForces: the system solves for u' by a corrector), and in the
// rotational row the torques dc x g_B - (dJ' w + w x dJ w) (Forces; dc, dJ the field's mass
// moment and inertia change): the centrifugal stiffening's gyroscopic partner, without which
// loop-held spinning bodies flutter.
//
// Markers: the SID nodes, in their order, then the body frame itself, named "origin". A node K
// with p_BoK_B(q) = s = o0 + Phi_K q (+ u2_K with stiffening on, below) and small rotation
// theta = Psi_K q (+ theta2_K, below; Psi_K = psi.m0) has the frame
//
//   p_WK_W = p_WBo_W + R s,   R_WK = R exp(theta~) AP0,
//
// the exponential map making R_WK a rotation for any q (exp(theta~) = I + theta~ + O(theta^2),
// SID's AP(q) to first order), and velocities exactly the derivatives of that pose:
//
//   v_WK_W = v + R (w~ s + Phi_K(q) qdot),   w_WK_W = R (w + T(theta) Psi_K(q) qdot),
//
// T(theta) = I + (1 - cos t)/t^2 theta~ + (t - sin t)/t^3 theta~^2 (t = |theta|), the left
// Jacobian of SO(3) (the angular velocity of exp(theta~) in its fixed frame). A moment at the
// node thus does the work of Psi_K(q)^T T^T R^T tau, SID's psi(q)^T M to first order in theta.
// With stiffening on, the node's stiffening blocks (phi.m1[j] = -[K0F_a(:, j)]_a for unit nodal
// forces, psi.m1[j] = -[K0M_a(:, j)]_a for unit moments) are the node's second-order
// displacement and rotation, u2_K = 1/2 sum_j q_j phi1_j q and theta2_K = 1/2 sum_j q_j psi1_j q
// (the stiffening field of mbs/stiffening_inertia.h at the node; symmetric forms as K0F_a and
// K0M_a are): s and theta gain them, and Phi_K(q) = Phi_K + sum_j q_j phi1_j, Psi_K(q) = Psi_K +
// sum_j q_j psi1_j (SID's phi(q), psi(q)) in the velocities and the Jacobian, so every force and
// moment at the node, joint reactions included, does the stiffening work -K0F(f_B) q -
// K0M(T^T tau_B) q through J^T [f; tau].

#include <Eigen/Core>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "mbs/body.h"
#include "mbs/stiffening_inertia.h"
#include "sid/reduced_body.h"

namespace flexmbs::mbs {

/// Linear momentum P [kg m/s] and angular momentum about the world origin Wo [kg m^2/s] of a
/// body, both in W: P = int v_P dm, L = int r_WoP_W x v_P dm.
struct Momentum {
  Eigen::Vector3d linear_W = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_Wo_W = Eigen::Vector3d::Zero();
};

/// A reduced flexible body in a floating frame of reference.
class FlexibleBody final : public Body {
 public:
  /// The name of the marker of the body frame B (origin Bo, axes of B).
  static constexpr std::string_view kOriginMarker = "origin";

  /// The body `name` from SID data `data` restricted to the scene's modes (mode_selection.h),
  /// with geometric stiffening on or off. Throws InputError "body '<name>': ..." for blocks of
  /// the wrong shape or order (docs/sid.md: Me, Ge, Ke, De, ksigma of order 0; mdCM, Ct, Cr, Gr,
  /// Oe of at most 1; J of at most 2), stiffening matrices of the wrong size or order-1 Ct
  /// without them, a non-positive mass, linearly dependent modes or kept modes that move the
  /// body rigidly (CheckNoRigidBodyMotion), a node named "origin" or twice, and a node whose AP0
  /// is not a rotation.
  FlexibleBody(std::string name, sid::ReducedBody data, bool geometric_stiffening);

  const std::string& name() const override { return name_; }
  Eigen::Index num_modes() const override { return n_; }

  void MassMatrix(const ConstVectorRef& x, Eigen::Ref<Eigen::MatrixXd> M) const override;
  void Forces(double t, const ConstVectorRef& x, const ConstVectorRef& u, const Eigen::Vector3d& g_W,
              Eigen::Ref<Eigen::VectorXd> h) const override;
  /// With stiffening on: h_e -= (sum_a a_a K0t_a + sum_a alpha_a K0r_a) q, a = R^T v' [m/s^2],
  /// alpha = w' [rad/s^2] from u_dot (the inertia loads of the frame's acceleration stiffen the
  /// body; docs/sid.md); returns true. Off, or without stiffening matrices: false.
  bool AddAccelerationDependentForces(const ConstVectorRef& x, const ConstVectorRef& u, const ConstVectorRef& u_dot,
                                      Eigen::Ref<Eigen::VectorXd> h) const override;
  /// The elastic row's derivatives, exact: dh_e/dq = -Ke + sum_a g_B,a (Ct1_a + K0t_a)
  /// - sum_l w_q,l (Oe1_l + K0omega_l) - sum_a (a_B,a K0t_a + alpha_a K0r_a) (Ct1, Oe1
  /// kinematic; K0 with stiffening on, the accelerations a_B = R^T v', alpha = w' from u_dot held
  /// fixed) and dh_e/dqdot = -De - [Ge_j w]_j. Not the rigid rows nor the elastic row's rotation
  /// and w columns (gyroscopic, centrifugal and gravity terms, of the motion's own frequencies).
  void AddForceJacobian(const ConstVectorRef& x, const ConstVectorRef& u, const ConstVectorRef& u_dot,
                        const Eigen::Vector3d& g_W, Eigen::Ref<Eigen::MatrixXd> dh_dx,
                        Eigen::Ref<Eigen::MatrixXd> dh_du) const override;
  /// 1/2 u^T M_kin u + 1/2 w^T dJ w [J]: M_kin the mass matrix of the kinematic blocks, dJ the
  /// stiffening field's inertia change (zero with stiffening off).
  double KineticEnergy(const ConstVectorRef& x, const ConstVectorRef& u) const override;
  /// 1/2 q^T Ke q + ksigma^T q - g_W . (m p_WBo_W + R (mdCM(q) + dc(q))) [J] (dc: the
  /// stiffening field's, zero with stiffening off).
  double PotentialEnergy(const ConstVectorRef& x, const Eigen::Vector3d& g_W) const override;

  /// Node markers by their SID names (indices 0 .. nodes - 1), the body frame by kOriginMarker.
  int FindMarker(std::string_view name) const override;
  /// The marker's frame (file comment).
  MarkerKinematics Marker(int marker, const ConstVectorRef& x, const ConstVectorRef& u) const override;

  /// P = m v + R (w~ mdCM + Ct^T qdot), L = p x P + R (mdCM~ R^T v + J w + Cr^T qdot): the
  /// first two block rows of M_kin u (Schwertassek & Wallrapp 1999, ch. 6), with R dJ w added to
  /// L when stiffening is on (the stiffening field's inertia change).
  Momentum ComputeMomentum(const ConstVectorRef& x, const ConstVectorRef& u) const;

  /// The SID data as given.
  const sid::ReducedBody& data() const { return data_; }
  bool geometric_stiffening() const { return geometric_stiffening_; }

 private:
  /// A node marker's data, from sid::Node.
  struct NodeFrame {
    std::string name;
    Eigen::Vector3d o0;                 ///< p_BoK_B at q = 0 [m]
    Eigen::Matrix3Xd Phi;               ///< 3 x n: origin.m1 side by side [m/q]
    Eigen::Matrix3Xd Psi;               ///< 3 x n: psi.m0 [rad/q]
    Eigen::Matrix3d AP0;                ///< node frame in B
    std::vector<Eigen::Matrix3Xd> phi1, psi1;  ///< stiffening blocks (empty if none or off)
  };
  /// The blocks at q that M_b and h_b need.
  struct Blocks {
    Eigen::Vector3d mdCM;
    Eigen::Matrix3d J;
    Eigen::MatrixX3d Ct, Cr;  ///< n x 3
  };
  /// Constructor steps after the checks: the SID invariants into the members M_b and h_b use
  /// (order-1 parts kinematic only: the stiffening goes to stiffening_), then the node markers
  /// (InputError for a node named "origin" or twice, or an AP0 that is not a rotation).
  void CopyInvariants();
  void ReadNodes();
  /// The kinematic blocks at q.
  Blocks Evaluate(const Eigen::VectorXd& q) const;
  /// M_kin u, plus dJ w in the rotational row, split as [translation (W); rotation (B); elastic].
  Eigen::VectorXd Momenta(const ConstVectorRef& x, const ConstVectorRef& u) const;

  std::string name_;
  sid::ReducedBody data_;
  bool geometric_stiffening_;
  Eigen::Index n_;
  double mass_;
  Eigen::Vector3d mdCM0_;
  Eigen::Matrix3Xd mdCM1_;      ///< 3 x n
  Eigen::Matrix3d J0_;
  Eigen::MatrixXd J1_, J2_;     ///< 9 x n, 9 x n^2 (column j n + k: vec(m2[j n + k]))
  Eigen::MatrixX3d Ct0_, Cr0_;  ///< n x 3
  /// Order-1 parts as n x 3n [X_x X_y X_z], X_a(i, j) = m1[j](i, a), kinematic only.
  Eigen::MatrixXd Ct1_, Cr1_;
  /// The stiffening field, with stiffening on and matrices in the file.
  std::optional<StiffeningInertia> stiffening_;
  Eigen::MatrixXd Me_, Ke_, De_;
  Eigen::VectorXd ksigma_;
  Eigen::MatrixXd Gr0_;         ///< 3 x 3n
  Eigen::MatrixXd Gr1_;         ///< 9n x n: column k = vec(m1[k])
  Eigen::MatrixXd Ge0_;         ///< n x 3n
  Eigen::MatrixXd Oe0_;         ///< n x 6
  Eigen::MatrixXd Oe1_;         ///< n x 6n: [Oe_1 .. Oe_6], Oe_l(i, j) = m1[j](i, l), kinematic only
  std::vector<NodeFrame> nodes_;
};

}  // namespace flexmbs::mbs
