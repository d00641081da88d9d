#include "contact/complementarity/friction_solver.h"

#include "contact/complementarity/friction_newton.h"
#include "contact/complementarity/nsgs.h"

namespace flexmbs::contact {

FrictionContactSolution SolveFrictionContact(const FrictionContactProblem& problem,
                                             const FrictionContactOptions& options) {
  NsgsOptions nsgs;
  nsgs.tolerance = options.tolerance;
  nsgs.max_iterations = options.nsgs_sweeps;
  FrictionContactSolution first = SolveFrictionNsgs(problem, nsgs);
  if (first.converged || problem.q.size() > options.newton_max_unknowns) return first;
  FrictionNewtonOptions newton;
  newton.tolerance = options.tolerance;
  newton.max_iterations = options.newton_steps;
  newton.initial_r = first.r;
  // NSGS's reactions lie far from the solution along W's null space: sigma from the error
  // (docs/contact.md, "What the second family of problems showed").
  newton.proximal_per_error = kHandoverProximalPerError;
  FrictionContactSolution second = SolveFrictionNewton(problem, newton);
  second.iterations += first.iterations;
  second.message = first.message + "; then " + second.message;
  return second;
}

}  // namespace flexmbs::contact
