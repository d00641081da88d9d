#pragma once
// The contact reactions of one local problem U = W r + q, shared by Moreau-Jean's steps and the
// event-driven method's acceleration-level and impact problems (docs/contact.md): frictionless an
// LCP in the normal rows, otherwise the friction-contact problem.

#include <Eigen/Core>

#include "contact/complementarity/solution.h"

namespace flexmbs::mbs {

/// The reactions r (d per point: normal, then the d - 1 tangents; d = 3 in space, 2 in a planar
/// scene) of U = W r + q (W dn x dn, q dn, mu n >= 0):
/// with every mu = 0 the LCP (W_NN, q_N) by contact::SolveLcp (Lemke, then proximal Newton on a
/// singular W_NN; r_T = 0), otherwise the friction-contact problem of dimension d by
/// contact::SolveFrictionContact (NSGS for at most nsgs_sweeps sweeps, then proximal Newton on a
/// rank-deficient W). The status's message names the problem and its solver.
contact::SolveStatus SolveContactReactions(const Eigen::MatrixXd& W, const Eigen::VectorXd& q,
                                           const Eigen::VectorXd& mu, double tolerance, int nsgs_sweeps,
                                           Eigen::VectorXd* r, Eigen::Index d = 3);

}  // namespace flexmbs::mbs
