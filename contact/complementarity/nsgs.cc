#include "contact/complementarity/nsgs.h"

#include <cmath>
#include <string>

#include <fmt/core.h>

#include "contact/complementarity/friction_local_solvers.h"
#include "core/error.h"

namespace flexmbs::contact {
namespace {

// One sweep over the contacts in order, updating r in place; W_t is W transposed (its column
// blocks are W's row blocks, contiguous). Returns sum_i ||change of r_i||^2.
double Sweep(const FrictionContactProblem& problem, const Eigen::MatrixXd& W_t, Eigen::VectorXd& r) {
  const int d = problem.dimension;
  double change = 0.0;
  for (int i = 0; i < problem.contacts(); ++i) {
    const Eigen::Index at = static_cast<Eigen::Index>(d) * i;
    // Row block i of W is column block i of W^T (contiguous); q_local excludes W_ii r_i.
    const auto W_ii = problem.W.block(at, at, d, d);
    if (d == 2) {
      const Eigen::Vector2d r_old = r.segment<2>(at);
      const Eigen::Vector2d q_local =
          W_t.middleCols<2>(at).transpose() * r + problem.q.segment<2>(at) - W_ii * r_old;
      const Eigen::Vector2d r_new = SolvePlanarContact(W_ii, q_local, problem.mu(i));
      change += (r_new - r_old).squaredNorm();
      r.segment<2>(at) = r_new;
    } else {
      const Eigen::Vector3d r_old = r.segment<3>(at);
      const Eigen::Vector3d q_local =
          W_t.middleCols<3>(at).transpose() * r + problem.q.segment<3>(at) - W_ii * r_old;
      Eigen::Vector3d r_new = r_old;
      SolveSpatialContact(W_ii, q_local, problem.mu(i), r_new);
      change += (r_new - r_old).squaredNorm();
      r.segment<3>(at) = r_new;
    }
  }
  return change;
}

}  // namespace

FrictionContactSolution SolveFrictionNsgs(const FrictionContactProblem& problem, const NsgsOptions& options) {
  CheckFrictionContact(problem);
  const Eigen::Index n = problem.q.size();
  FLEXMBS_CHECK(options.initial_r.size() == 0 || options.initial_r.size() == n,
                "NSGS: the initial r must have d n entries");
  FrictionContactSolution s;
  s.r = options.initial_r.size() == n ? options.initial_r : Eigen::VectorXd::Zero(n);
  const Eigen::MatrixXd W_t = problem.W.transpose();
  double light_tolerance = options.tolerance;
  s.error = FrictionContactError(problem, s.r);
  while (s.error > options.tolerance && s.iterations < options.max_iterations) {
    const double change = std::sqrt(Sweep(problem, W_t, s.r));
    ++s.iterations;
    const double norm_r = s.r.norm();
    const double light_error = norm_r > 0.0 ? change / norm_r : change;
    if (light_error <= light_tolerance || s.iterations == options.max_iterations) {
      s.error = FrictionContactError(problem, s.r);
      if (s.error > options.tolerance && s.error > 0.0) {
        light_tolerance = light_error / s.error * options.tolerance;
      }
    }
  }
  s.u = problem.W * s.r + problem.q;
  s.converged = s.error <= options.tolerance;
  s.message = s.converged ? fmt::format("NSGS: converged after {} sweeps", s.iterations)
                          : fmt::format("NSGS: no convergence after {} sweeps (error {:.3g} > {:.3g})",
                                        s.iterations, s.error, options.tolerance);
  return s;
}

}  // namespace flexmbs::contact
