#pragma once

#include <Eigen/Core>

#include "contact/complementarity/friction_contact_problem.h"

namespace flexmbs::contact {

/// One contact's Alart-Curnier function and an element of its generalised Jacobian.
struct AlartCurnierContact {
  LocalVector phi;  ///< Phi(r, u) = r - P(r - rho u); zero exactly when (u, r) obeys Coulomb's law
  LocalMatrix D;    ///< dP/dx at x = r - rho u: dPhi = (I - D) dr + rho D du
};

/// Alart & Curnier's augmented-Lagrangian function of one contact (Alart & Curnier 1991; Acary &
/// Brogliato 2008, §13.7.2): with x = r - rho u,
///   P_N = max(0, x_N),  P_T = projection of x_T on the disk of radius mu P_N,
/// and Phi = r - P. rho > 0 (units of reaction over velocity) leaves the solutions unchanged and
/// scales the Newton iteration; D is an element of Clarke's generalised Jacobian of P, taken on
/// the smooth side at kinks. r and u have d = 2 or 3 entries, normal first.
AlartCurnierContact AlartCurnier(const LocalVector& r, const LocalVector& u, double mu, double rho);

/// rho = 1 / ||W_ii||_F for a contact's diagonal block of the Delassus operator: a scaling with
/// rho W_ii of order one (Acary & Brogliato 2008, §13.7 discuss the choice).
double AlartCurnierRho(const Eigen::Ref<const Eigen::MatrixXd>& W_ii);

}  // namespace flexmbs::contact
