#pragma once

#include <Eigen/Core>

#include "contact/complementarity/friction_contact_problem.h"
#include "contact/complementarity/solution.h"

namespace flexmbs::contact {

/// Options of SolveFrictionContact.
struct FrictionContactOptions {
  double tolerance = 1e-10;       ///< on FrictionContactError, for both stages
  int nsgs_sweeps = 1000;         ///< NSGS sweeps before handing over to Newton
  int newton_max_unknowns = 1500; ///< Newton (dense LU, O((d n)^3)) only for d n up to this
  /// Most Newton steps. 500: from NSGS's reactions after 1000 sweeps the hardest stack of
  /// tests/contact (spatial, 20 contacts on 3 bodies, mu 1, second family, seed 1) needs 463.
  int newton_steps = 500;
};

/// flexmbs' default friction-contact solver, chosen by the measurements in docs/contact.md: NSGS
/// (SolveFrictionNsgs), the fastest on regular Delassus operators at every size measured; if it
/// has not converged after nsgs_sweeps sweeps (rank-deficient W, large mu) and the problem is
/// small enough, the proximal semi-smooth Newton solver (SolveFrictionNewton) continues from its
/// reactions. iterations counts NSGS sweeps plus Newton steps; message names both stages.
FrictionContactSolution SolveFrictionContact(const FrictionContactProblem& problem,
                                             const FrictionContactOptions& options = {});

}  // namespace flexmbs::contact
