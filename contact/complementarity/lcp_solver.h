#pragma once

#include <Eigen/Core>

#include "contact/complementarity/lcp_problem.h"
#include "contact/complementarity/solution.h"

namespace flexmbs::contact {

/// Options of SolveLcp.
struct LcpSolveOptions {
  double tolerance = 1e-10;  ///< on LcpError, for both stages
};

/// flexmbs' LCP solve for contact (Moreau-Jean's frictionless steps, event-driven impacts and
/// closed contacts): Lemke's pivoting (SolveLcpLemke, exact on P-matrices) with pivot tolerances
/// 1e-9, then 1e-12, then 1e-6 of the entering column's largest entry, each attempt at most 20
/// pivots per row; where all miss the tolerance — a singular M from more contact points than the
/// directions they constrain (the coplanar vertices of a surface), where pivots on round-off
/// ruin the basis or near-ties cycle — the proximal semi-smooth
/// Newton solver (SolveFrictionNewton) on the planar friction problem with mu = 0 (the cone is the
/// normal half-line) and an identity tangential block (its impulse is 0), whose proximal term
/// keeps its Jacobian regular there. The best of them; iterations counts Lemke's pivots plus
/// Newton's steps, the message names every stage.
LcpSolution SolveLcp(const LcpProblem& problem, const LcpSolveOptions& options = {});

}  // namespace flexmbs::contact
