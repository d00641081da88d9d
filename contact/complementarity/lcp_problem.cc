#include "contact/complementarity/lcp_problem.h"

#include <cfloat>

#include "core/error.h"

namespace flexmbs::contact {

void CheckLcp(const LcpProblem& problem) {
  FLEXMBS_CHECK(problem.M.rows() == problem.M.cols(), "LCP: M must be square");
  FLEXMBS_CHECK(problem.q.size() == problem.M.rows(), "LCP: q must have as many rows as M");
  FLEXMBS_CHECK(problem.M.allFinite() && problem.q.allFinite(), "LCP: M and q must be finite");
}

Eigen::VectorXd LcpVelocity(const LcpProblem& problem, const Eigen::VectorXd& z) {
  return problem.M * z + problem.q;
}

double LcpError(const LcpProblem& problem, const Eigen::VectorXd& z) {
  const Eigen::VectorXd w = LcpVelocity(problem, z);
  const double error = z.cwiseMin(w).norm();
  const double norm_q = problem.q.norm();
  return norm_q > DBL_EPSILON ? error / norm_q : error;
}

}  // namespace flexmbs::contact
