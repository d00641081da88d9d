#pragma once
// Geometric stiffening as the inertia of a second-order displacement field (docs/mbs.md,
// "Geometric stiffening"). A body held as in its reduction, carrying the static stress sigma_c
// of a unit load case c (body force f_c), has K0_c = Phi^T K_G(sigma_c) Phi; the work of f_c
// on the second-order displacement u2(q) that makes the strain of the deformation linear in q
// is -1/2 q^T K0_c q. SID's load cases are the inertia loads of the frame's motion, so their
// K0 are moments of u2 over the mass (dm = rho dV):
//
//   dc_a     = int u2_a dm               = 1/2 q^T K0t_a q            (f = -rho e_a),
//              int (r x u2)_a dm         = 1/2 q^T K0r_a q            (f = -rho e_a x r),
//   w^T dJ w = 2 int (w x r).(w x u2) dm = -sum_l w_q,l q^T K0w_l q   (f = -rho W_l r),
//
// and the field adds to the kinetic energy (first order in u2)
//
//   dT = v_B . (w x dc + dCt^T qdot) + w . dCr^T qdot + 1/2 w^T dJ w,   dCt = [K0t_a q]_a,
//
// dCr = [K0r_a q]_a (n x 3), v_B = R^T v, and to the potential of gravity -g_W . R dc.
// Lagrange's equations of these terms give, in the elastic row, SID's stiffening forces
// -dCt (a_B - g_B) - dCr alpha - sum_l w_q,l K0w_l q (a_B = R^T v', alpha = w'), and partners
// in the rigid rows. Kept of the partners: gravity's torque dc x g_B (the potential is then
// exact) and the gyroscopic torque -(dJ' w + w x dJ w) of the centrifugal stiffening, which
// makes the coupling of w and q through K0w skew: without it a loop-held spinning body's top
// modes flutter (docs/mbs.md, measured). Left out: the partners proportional to accelerations,
// -R (alpha x dc + dCt^T q'') and -(dc x a_B + dCr^T q'' + dJ alpha), and the translational
// velocity terms. The field's kinetic energy is not positive without the elastic-elastic terms
// SID does not carry (int Phi^T du2/dq dm, first order in q): on the slider-crank rod
// M_kin + dM is indefinite from 0.07 s on, and dJ alpha solved by the one-step corrector gives
// a 35 % wrong peak deflection; the other left-out terms change nothing measurable there.
//
// Sources: Wallrapp & Schwertassek, Int. J. Numer. Meth. Eng. 32, 1991 (the K0 of SID's load
// cases); Wu & Haug, Int. J. Numer. Meth. Eng. 26, 1988 (stiffening from the second-order
// field).

#include <Eigen/Core>
#include <array>

#include "sid/reduced_body.h"

namespace flexmbs::mbs {

/// The stiffening field's terms of one body that flexmbs keeps (file comment). Rows of a
/// generalised force: [translation (W); rotation (B); elastic], as in FlexibleBody.
class StiffeningInertia {
 public:
  /// The matrices (n x n each, symmetric as every geometric stiffness) of a body with n modes.
  explicit StiffeningInertia(const sid::GeometricStiffening& K0);

  /// The field's moments at q that the state-dependent terms need (dCr = [K0r_a q] only enters
  /// the acceleration terms, which form it themselves).
  struct Moments {
    Eigen::Vector3d dc;     ///< int u2 dm [kg m]
    Eigen::MatrixX3d dCt;   ///< n x 3: [K0t_a q]
    Eigen::Matrix3d dJ;     ///< second-order change of the inertia tensor about Bo [kg m^2]
    Eigen::MatrixXd K0w_q;  ///< n x 6: [K0w_l q]
  };
  /// The moments at q: 9 products of an n x n matrix with q.
  Moments At(const Eigen::VectorXd& q) const;

  /// The state-dependent terms added to h: rotation dc x g_B - (dJ' w + w x dJ w); elastic
  /// dCt g_B - sum_l w_q,l K0w_l q. g_B = R^T g_W [m/s^2], w [rad/s], qdot for dJ'.
  void AddStateForces(const Moments& m, const Eigen::VectorXd& qdot, const Eigen::Vector3d& w,
                      const Eigen::Vector3d& g_B, Eigen::Ref<Eigen::VectorXd> h) const;

  /// The elastic row's acceleration terms -(dCt a_B + dCr alpha) = -sum_a (a_B,a K0t_a +
  /// alpha_a K0r_a) q added to h_e (n) at q: a_B = R^T v' [m/s^2], alpha = w' [rad/s^2]. Six
  /// products with q (the moments of At are not needed).
  void AddAccelerationForces(const Eigen::VectorXd& q, const Eigen::Vector3d& a_B, const Eigen::Vector3d& alpha,
                             Eigen::Ref<Eigen::VectorXd> h_e) const;

  /// -g_W . R dc [J], the field's potential in gravity.
  double PotentialEnergy(const Moments& m, const Eigen::Matrix3d& R, const Eigen::Vector3d& g_W) const;

  /// The elastic row's stiffness -sum_l w_q,l K0w_l + sum_a (g_B - a_B)_a K0t_a - sum_a
  /// alpha_a K0r_a (n x n), added to `stiffness`; a_B = R^T v' and alpha = w' held fixed.
  void AddElasticStiffness(const Eigen::Vector3d& w, const Eigen::Vector3d& g_minus_a_B, const Eigen::Vector3d& alpha,
                           Eigen::Ref<Eigen::MatrixXd> stiffness) const;

 private:
  std::array<Eigen::MatrixXd, 3> K0t_, K0r_;
  std::array<Eigen::MatrixXd, 6> K0w_;
};

}  // namespace flexmbs::mbs
