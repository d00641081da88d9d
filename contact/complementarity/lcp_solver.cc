#include "contact/complementarity/lcp_solver.h"

#include <algorithm>
#include <utility>

#include "contact/complementarity/friction_contact_problem.h"
#include "contact/complementarity/friction_newton.h"
#include "contact/complementarity/lemke.h"

namespace flexmbs::contact {
namespace {

/// The LCP as the planar friction problem with mu = 0 and an identity tangential block, solved
/// by proximal Newton; the better of its solution and Lemke's.
LcpSolution SolveByProximalNewton(const LcpProblem& problem, double tolerance, LcpSolution lemke) {
  const Eigen::Index n = problem.q.size();
  FrictionContactProblem planar{2, Eigen::MatrixXd::Identity(2 * n, 2 * n), Eigen::VectorXd::Zero(2 * n),
                                Eigen::VectorXd::Zero(n)};
  for (Eigen::Index i = 0; i < n; ++i) {
    planar.q(2 * i) = problem.q(i);
    for (Eigen::Index j = 0; j < n; ++j) planar.W(2 * i, 2 * j) = problem.M(i, j);
  }
  FrictionNewtonOptions options;
  options.tolerance = tolerance;
  const FrictionContactSolution newton = SolveFrictionNewton(planar, options);
  LcpSolution solution;
  solution.z.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) solution.z(i) = std::max(0.0, newton.r(2 * i));
  solution.w = problem.M * solution.z + problem.q;
  solution.error = LcpError(problem, solution.z);
  if (!(solution.error < lemke.error)) return lemke;
  solution.iterations = lemke.iterations + newton.iterations;
  solution.converged = solution.error <= tolerance;
  solution.message = lemke.message + "; then proximal Newton: " + newton.message;
  return solution;
}

}  // namespace

LcpSolution SolveLcp(const LcpProblem& problem, const LcpSolveOptions& options) {
  LemkeOptions lemke;
  lemke.tolerance = options.tolerance;
  LcpSolution solution = SolveLcpLemke(problem, lemke);
  solution.message = "Lemke: " + solution.message;
  if (solution.converged || problem.q.size() == 0) return solution;
  return SolveByProximalNewton(problem, options.tolerance, std::move(solution));
}

}  // namespace flexmbs::contact
