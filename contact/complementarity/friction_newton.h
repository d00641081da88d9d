#pragma once

#include <Eigen/Core>

#include "contact/complementarity/friction_contact_problem.h"
#include "contact/complementarity/solution.h"

namespace flexmbs::contact {

/// Options of SolveFrictionNewton.
struct FrictionNewtonOptions {
  double tolerance = 1e-10;     ///< stop when FrictionContactError <= tolerance
  int max_iterations = 200;     ///< most Newton steps (rejected steps included)
  /// First proximal weight sigma, relative to the mean diagonal of W. Divided by 10 each time a
  /// subproblem is solved (down to min_proximal and a floor left by stalls), multiplied by 10 when
  /// Newton stalls on one.
  double proximal = 1e-2;
  double min_proximal = 1e-6;  ///< the least sigma, relative to the mean diagonal of W
  /// A subproblem counts as solved when Newton has reduced ||Phi||^2 by this factor from its centre.
  double subproblem_reduction = 1e-4;
  /// Sigma's rule after each subproblem. 0: the rule above (shrink tenfold, floors left by
  /// stalls). > 0: sigma follows the error, as in Siconos' fc3d_proximal (alpha = 5 error): after
  /// a solved subproblem the smaller of sigma / 10 and proximal_per_error FrictionContactError
  /// W's mean diagonal (not below min_proximal); a stall multiplies sigma by ten for the next
  /// subproblem only. Fewer steps from reactions far from the solution (NSGS's; docs/contact.md),
  /// but Newton stops nearer the tolerance, which the event-driven stick detection does not take.
  double proximal_per_error = 0.0;
  Eigen::VectorXd initial_r;    ///< warm start, d n entries; empty: r = 0
};

/// Semi-smooth Newton on Alart & Curnier's augmented-Lagrangian function of all contacts at once
/// (Alart & Curnier 1991; Christensen, Klarbring, Pang & Strömberg 1998; Acary & Brogliato 2008,
/// §13.7) inside an inexact proximal point method (Rockafellar 1976; Siconos' fc3d_proximal):
/// Newton solves the subproblem with W + sigma I and q - sigma c (centre c) whose Jacobian
///   J = I - D + rho D (W + sigma I)
/// stays regular on rank-deficient Delassus operators (more contacts than degrees of freedom);
/// once ||Phi||^2 has dropped by subproblem_reduction the centre moves to r and sigma shrinks
/// tenfold. Where Newton stalls (Armijo backtracking on ||Phi||^2 finds no descent, or only a
/// step shorter than 1/32) the centre moves too and sigma grows tenfold; sigma stays above that
/// value until a subproblem is solved, and each solved one lowers the floor tenfold (down to
/// min_proximal). rho = 1 / ||W_ii||_F per contact. Dense LU: O((d n)^3) per step. iterations
/// counts Newton steps.
FrictionContactSolution SolveFrictionNewton(const FrictionContactProblem& problem,
                                            const FrictionNewtonOptions& options = {});

}  // namespace flexmbs::contact
