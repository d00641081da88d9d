#pragma once

#include <Eigen/Core>

#include "contact/complementarity/friction_contact_problem.h"
#include "contact/complementarity/solution.h"

namespace flexmbs::contact {

/// The handover's FrictionNewtonOptions::proximal_per_error: sigma = FrictionContactError W's mean
/// diagonal (measured on the 48 stacks of tests/contact against 0.5, 2 and Siconos' 5: 186 Newton
/// steps in all after the six handovers, against 264, 247 and 274; 521 under the shrink rule).
inline constexpr double kHandoverProximalPerError = 1.0;

/// Options of SolveFrictionContact.
struct FrictionContactOptions {
  double tolerance = 1e-10;       ///< on FrictionContactError, for both stages
  int nsgs_sweeps = 1000;         ///< NSGS sweeps before handing over to Newton
  int newton_max_unknowns = 1500; ///< Newton (dense LU, O((d n)^3)) only for d n up to this
  /// Most Newton steps. 500: from NSGS's reactions after 1000 sweeps the hardest stack of
  /// tests/contact (spatial, 20 contacts on 3 bodies, mu 1, second family, seed 1) needs 141
  /// (463 under the shrink rule); NSGS's reactions after 1 ... 3000 sweeps need up to 213.
  int newton_steps = 500;
};

/// flexmbs' default friction-contact solver, chosen by the measurements in docs/contact.md: NSGS
/// (SolveFrictionNsgs), the fastest on regular Delassus operators at every size measured; if it
/// has not converged after nsgs_sweeps sweeps (rank-deficient W, large mu) and the problem is
/// small enough, the proximal semi-smooth Newton solver (SolveFrictionNewton) continues from its
/// reactions, sigma following the error (kHandoverProximalPerError). iterations counts NSGS
/// sweeps plus Newton steps; message names both stages.
FrictionContactSolution SolveFrictionContact(const FrictionContactProblem& problem,
                                             const FrictionContactOptions& options = {});

}  // namespace flexmbs::contact
