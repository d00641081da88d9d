#include "contact/complementarity/lcp_solver.h"

#include <fmt/format.h>

#include <algorithm>
#include <string>
#include <utility>

#include "contact/complementarity/friction_contact_problem.h"
#include "contact/complementarity/friction_newton.h"
#include "contact/complementarity/lemke.h"

namespace flexmbs::contact {
namespace {

/// Lemke's pivot tolerances, tried in turn: on a singular M (more contact points than the
/// directions they constrain) the entering column's entries along M's null space are round-off,
/// up to about 1e-11 of its largest on the stacked cubes of docs/contact.md, and a pivot on one
/// of them ruins the basis (error 4.5 at 1e-12; 1.3e-15 at 1e-9 after the final refinement).
constexpr double kLemkePivotTolerances[] = {1e-9, 1e-12, 1e-6};
/// Lemke's pivots per row before an attempt gives up: a solve takes O(n) (81 on those 94 rows),
/// and near-ties in the ratio test can cycle (1900 pivots without an end on 3 of their 500
/// steps; 90250 at the general limit, 0.5 s each).
constexpr int kLemkePivotsPerRow = 20;

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
  lemke.max_pivots = kLemkePivotsPerRow * (static_cast<int>(problem.q.size()) + 1);
  LcpSolution best;
  std::string stages;
  int pivots = 0;
  for (const double pivot_tolerance : kLemkePivotTolerances) {
    lemke.pivot_tolerance = pivot_tolerance;
    LcpSolution attempt = SolveLcpLemke(problem, lemke);
    pivots += attempt.iterations;
    stages += fmt::format("{}Lemke (pivot tolerance {:g}): {}", stages.empty() ? "" : "; ", pivot_tolerance,
                          attempt.message);
    if (best.z.size() == 0 || attempt.error < best.error) best = std::move(attempt);
    if (best.converged) break;
  }
  best.iterations = pivots;
  best.message = std::move(stages);
  if (best.converged) return best;
  return SolveByProximalNewton(problem, options.tolerance, std::move(best));
}

}  // namespace flexmbs::contact
