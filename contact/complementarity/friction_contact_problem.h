#pragma once

#include <Eigen/Core>

namespace flexmbs::contact {

/// A vector of one contact's local coordinates (d = 2 or 3 entries, no heap allocation).
using LocalVector = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, 3, 1>;
/// A d x d matrix of one contact (d = 2 or 3, no heap allocation).
using LocalMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, 3, 3>;

/// The friction-contact problem in Siconos' FrictionContact convention (Acary & Brogliato 2008,
/// §13.4): n contacts in dimension d = 2 (planar: normal, tangent) or 3 (normal, two tangents),
/// each contact's local coordinates contiguous with the normal first. Find reactions r and local
/// velocities u = W r + q such that each contact's (u_i, r_i) satisfies Coulomb's law in De Saxcé's
/// modified form (De Saxcé & Feng 1991):
///   K_mu_i ∋ r_i ⊥ û_i ∈ K*_mu_i,   û_i = (u_N + mu_i ||u_T||, u_T),
/// with K_mu = {||r_T|| <= mu r_N} and K* its dual cone. Its solutions are exactly Signorini's
/// condition with Coulomb friction (take-off, stick, slide); the planar tangent is two-sided.
struct FrictionContactProblem {
  int dimension = 3;   ///< d: 2 or 3
  Eigen::MatrixXd W;   ///< Delassus operator G M^-1 G^T, d n x d n, symmetric positive semi-definite
  Eigen::VectorXd q;   ///< local free velocity, d n
  Eigen::VectorXd mu;  ///< friction coefficient per contact, n, each >= 0

  /// n, the number of contacts.
  int contacts() const { return static_cast<int>(mu.size()); }
};

/// Throws InternalError unless d is 2 or 3, W is d n x d n, q has d n rows, mu >= 0 and every
/// entry is finite.
void CheckFrictionContact(const FrictionContactProblem& problem);

/// The friction-contact error as Siconos numerics 4.4 computes it (fc3d_compute_error,
/// fc2d_compute_error): the natural map (projection) residual of De Saxcé's formulation,
///   e = sqrt(sum_i ||r_i - P_K(r_i - û_i)||^2) / max(||q||, ||r||, ||u||)
/// (the division only when the maximum exceeds DBL_EPSILON). Zero exactly at a solution.
double FrictionContactError(const FrictionContactProblem& problem, const Eigen::VectorXd& r);

/// ||r_i - P_K(r_i - û_i)||^2 for one contact: its term in FrictionContactError. r_i and u_i have
/// d entries.
double ContactNaturalMapErrorSquared(const LocalVector& r_i, const LocalVector& u_i, double mu);

}  // namespace flexmbs::contact
