#pragma once

#include "contact/complementarity/lcp_problem.h"
#include "contact/complementarity/solution.h"

namespace flexmbs::contact {

/// Options of SolveLcpLemke.
struct LemkeOptions {
  /// Most pivots before giving up; 0: 10 (n + 1)^2, far above the O(n) pivots a P-matrix usually needs.
  int max_pivots = 0;
  /// An entry of the entering column counts as positive (may block) above this, times the column's
  /// largest magnitude.
  double pivot_tolerance = 1e-12;
  /// After the last pivot z_J is recomputed from M_JJ z_J = -q_J on the final basis J (an LU solve)
  /// and kept when its LcpError is smaller: the tableau's round-off no longer reaches z.
  bool refine = true;
  /// converged requires LcpError <= tolerance at the end (the solution is exact up to round-off).
  double tolerance = 1e-10;
};

/// Lemke's complementary pivoting method with covering vector e and the lexicographic ratio test
/// against cycling on degenerate problems (Cottle, Pang & Stone 1992, Algorithm 4.4.5 and §4.9).
/// Dense tableau: O(n^2) per pivot. Finds a solution for every P-matrix and, when the LCP is
/// feasible, for copositive-plus M. On ray termination (no blocking row: the LCP has no solution
/// for this M and q, or M is outside those classes) it returns converged = false with a message
/// that says so. iterations counts pivots.
LcpSolution SolveLcpLemke(const LcpProblem& problem, const LemkeOptions& options = {});

}  // namespace flexmbs::contact
