#pragma once
// The contact reactions of one local problem U = W r + q, shared by Moreau-Jean's steps and the
// event-driven method's acceleration-level and impact problems (docs/contact.md): frictionless an
// LCP in the normal rows, otherwise the friction-contact problem.

#include <Eigen/Core>

#include "contact/complementarity/solution.h"

namespace flexmbs::mbs {

/// The reactions r (3 per point: normal, t1, t2) of U = W r + q (W 3n x 3n, q 3n, mu n >= 0):
/// with every mu = 0 the LCP (W_NN, q_N) by contact::SolveLcp (Lemke, then proximal Newton on a
/// singular W_NN; r_T = 0), otherwise the friction-contact problem (d = 3) by
/// contact::SolveFrictionContact (NSGS for at most nsgs_sweeps sweeps, then proximal Newton on a
/// rank-deficient W). The status's message names the problem and its solver.
contact::SolveStatus SolveContactReactions(const Eigen::MatrixXd& W, const Eigen::VectorXd& q,
                                           const Eigen::VectorXd& mu, double tolerance, int nsgs_sweeps,
                                           Eigen::VectorXd* r);

}  // namespace flexmbs::mbs
