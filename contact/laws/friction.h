#pragma once
// Regularised Coulomb friction (docs/contact.md, "Compliant laws"): the tangential force of a
// sliding contact point as a smooth function of its slip velocity, with analytic derivatives.

#include <Eigen/Core>

namespace flexmbs::contact {

/// Coulomb friction regularised over the slip speed eps:
///   F_T = -mu F_N v_T / sqrt(|v_T|^2 + eps^2)
/// (|F_T| -> mu F_N for |v_T| >> eps; a viscous mu F_N / eps near rest). Chosen over tanh(|v|/eps)
/// and a linear ramp because it is smooth (C-infinity) everywhere, v_T = 0 included, isotropic
/// in the tangent plane, and its Jacobian needs no special case at rest (mu F_N / eps I there);
/// a ramp's kink at |v_T| = eps costs the adaptive and Newton steps. Its price: a body never
/// sticks, it creeps at v_T ~ eps F_T / (mu F_N) under a tangential load below mu F_N.
/// The limit eps -> 0 is Coulomb's law of sliding friction, |F_T| = mu F_N against the slip.
struct RegularisedCoulomb {
  double coefficient = 0.0;            ///< mu >= 0
  double regularisation_speed = 1e-4;  ///< eps > 0 [m/s]
};

/// mu >= 0 and eps > 0, finite; InputError naming the parameter and its value otherwise.
RegularisedCoulomb MakeRegularisedCoulomb(double coefficient, double regularisation_speed);

/// The tangential force and its derivatives at one contact point.
struct TangentialForce {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();          ///< F_T [N]
  Eigen::Matrix3d d_slip = Eigen::Matrix3d::Zero();         ///< dF_T/dv_T [N s/m]
  Eigen::Vector3d d_normal_force = Eigen::Vector3d::Zero(); ///< dF_T/dF_N [-]
};

/// F_T at slip velocity v_T [m/s] (the relative velocity of the body's contact point, in the
/// tangent plane) and normal force F_N >= 0 [N]:
///   dF_T/dv_T = -mu F_N (I / s - v_T v_T^T / s^3),  dF_T/dF_N = -mu v_T / s,  s = sqrt(|v_T|^2 + eps^2).
TangentialForce Evaluate(const RegularisedCoulomb& friction, const Eigen::Vector3d& slip_velocity,
                         double normal_force);

}  // namespace flexmbs::contact
