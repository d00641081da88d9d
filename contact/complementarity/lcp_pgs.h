#pragma once

#include <Eigen/Core>

#include "contact/complementarity/lcp_problem.h"
#include "contact/complementarity/solution.h"

namespace flexmbs::contact {

/// Options of SolveLcpPgs.
struct PgsOptions {
  double tolerance = 1e-10;   ///< stop when LcpError <= tolerance (checked after every sweep)
  int max_iterations = 10000; ///< most sweeps
  double relaxation = 1.0;    ///< omega in (0, 2): 1 is Gauss-Seidel, above 1 over-relaxation (PSOR)
  Eigen::VectorXd initial_z;  ///< warm start, n entries; empty: z = 0
};

/// Projected Gauss-Seidel (PSOR with relaxation omega; Cottle, Pang & Stone 1992, §5.2): sweeps
///   z_i <- max(0, z_i - omega (M_i. z + q_i) / M_ii),  i = 1..n.
/// Converges for symmetric positive definite M (and for M with a dominant positive diagonal);
/// needs M_ii > 0, otherwise it returns at once with converged = false. iterations counts sweeps.
LcpSolution SolveLcpPgs(const LcpProblem& problem, const PgsOptions& options = {});

}  // namespace flexmbs::contact
