#pragma once

#include <Eigen/Core>

#include "contact/complementarity/friction_contact_problem.h"
#include "contact/complementarity/solution.h"

namespace flexmbs::contact {

/// Options of SolveFrictionNewton.
struct FrictionNewtonOptions {
  double tolerance = 1e-10;     ///< stop when FrictionContactError <= tolerance
  int max_iterations = 200;     ///< most Newton steps (rejected steps included)
  /// First proximal weight sigma, relative to the mean diagonal of W. Divided by 10 after each
  /// accepted step (down to 1e-12 relative), multiplied by 10 after each rejected one.
  double proximal = 1e-4;
  Eigen::VectorXd initial_r;    ///< warm start, d n entries; empty: r = 0
};

/// Semi-smooth Newton on Alart & Curnier's augmented-Lagrangian function of all contacts at once
/// (Alart & Curnier 1991; Christensen, Klarbring, Pang & Strömberg 1998; Acary & Brogliato 2008,
/// §13.7), regularised as an inexact proximal point method (Rockafellar 1976; Siconos'
/// fc3d_proximal): each step is one Newton step on the subproblem with W + sigma I and its centre at
/// the current r, so the Jacobian
///   J = I - D + rho D (W + sigma I)
/// stays regular on rank-deficient Delassus operators (more contacts than degrees of freedom);
/// with a sigma -> 0 schedule it is Newton's method near the solution. Steps are damped by Armijo
/// backtracking on ||Phi||^2; rho = 1 / ||W_ii||_F per contact. Dense LU: O((d n)^3) per step.
/// iterations counts Newton steps.
FrictionContactSolution SolveFrictionNewton(const FrictionContactProblem& problem,
                                            const FrictionNewtonOptions& options = {});

}  // namespace flexmbs::contact
