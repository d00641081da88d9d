#include "contact/complementarity/lcp_pgs.h"

#include <algorithm>

#include <fmt/core.h>

#include "core/error.h"

namespace flexmbs::contact {

LcpSolution SolveLcpPgs(const LcpProblem& problem, const PgsOptions& options) {
  CheckLcp(problem);
  const Eigen::Index n = problem.q.size();
  FLEXMBS_CHECK(options.relaxation > 0.0 && options.relaxation < 2.0, "PGS: relaxation must be in (0, 2)");
  FLEXMBS_CHECK(options.initial_z.size() == 0 || options.initial_z.size() == n,
                "PGS: the initial z must have n entries");
  LcpSolution s;
  s.z = options.initial_z.size() == n ? Eigen::VectorXd(options.initial_z.cwiseMax(0.0)) : Eigen::VectorXd::Zero(n);
  if (n > 0 && problem.M.diagonal().minCoeff() <= 0.0) {
    s.w = LcpVelocity(problem, s.z);
    s.error = LcpError(problem, s.z);
    s.message = "PGS: M has a diagonal entry <= 0; projected Gauss-Seidel cannot be applied";
    return s;
  }
  // Row i of M is column i of M^T: contiguous in Eigen's column-major storage.
  const Eigen::MatrixXd M_t = problem.M.transpose();
  const Eigen::VectorXd inverse_diagonal = problem.M.diagonal().cwiseInverse();
  s.error = LcpError(problem, s.z);
  while (s.error > options.tolerance && s.iterations < options.max_iterations) {
    for (Eigen::Index i = 0; i < n; ++i) {
      const double w_i = M_t.col(i).dot(s.z) + problem.q(i);
      s.z(i) = std::max(0.0, s.z(i) - options.relaxation * w_i * inverse_diagonal(i));
    }
    ++s.iterations;
    s.error = LcpError(problem, s.z);
  }
  s.w = LcpVelocity(problem, s.z);
  s.converged = s.error <= options.tolerance;
  s.message = s.converged ? fmt::format("PGS: converged after {} sweeps", s.iterations)
                          : fmt::format("PGS: no convergence after {} sweeps (error {:.3g} > {:.3g})",
                                        s.iterations, s.error, options.tolerance);
  return s;
}

}  // namespace flexmbs::contact
