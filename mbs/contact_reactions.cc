#include "mbs/contact_reactions.h"

#include <string>

#include "contact/complementarity/friction_contact_problem.h"
#include "contact/complementarity/friction_solver.h"
#include "contact/complementarity/lcp_problem.h"
#include "contact/complementarity/lcp_solver.h"

namespace flexmbs::mbs {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

contact::SolveStatus SolveContactReactions(const MatrixXd& W, const VectorXd& q, const VectorXd& mu,
                                           double tolerance, int nsgs_sweeps, VectorXd* r, Index d) {
  const Index n = mu.size();
  r->setZero(d * n);
  if (n == 0 || mu.maxCoeff() == 0.0) {
    contact::LcpProblem lcp{MatrixXd(n, n), VectorXd(n)};
    for (Index i = 0; i < n; ++i) {
      lcp.q(i) = q(d * i);
      for (Index j = 0; j < n; ++j) lcp.M(i, j) = W(d * i, d * j);
    }
    contact::LcpSolution solution = contact::SolveLcp(lcp, {tolerance});
    for (Index i = 0; i < n; ++i) (*r)(d * i) = solution.z(i);
    solution.message = "LCP by " + solution.message;
    return solution;
  }
  contact::FrictionContactOptions friction;
  friction.tolerance = tolerance;
  friction.nsgs_sweeps = nsgs_sweeps;
  contact::FrictionContactSolution solution = contact::SolveFrictionContact({static_cast<int>(d), W, q, mu}, friction);
  *r = solution.r;
  solution.message = "friction contact: " + solution.message;
  return solution;
}

}  // namespace flexmbs::mbs
