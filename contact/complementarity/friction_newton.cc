#include "contact/complementarity/friction_newton.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/LU>
#include <fmt/core.h>

#include "contact/complementarity/alart_curnier.h"
#include "core/error.h"

namespace flexmbs::contact {
namespace {

// The shortest Armijo step that still counts as progress on a subproblem (1/32 measured best
// among 1/32 and 1/512 on the stacks of tests/contact: 14 and 135 Newton steps against 19 and 161
// on the two problems the old rule failed on).
constexpr double kShortStep = 1.0 / 32.0;

// Alart-Curnier's function of the proximal subproblem (W + sigma I, q - sigma c) at r: its
// velocities are u + sigma (r - c) with u = W r + q. D holds the Jacobian blocks D_i.
struct ProximalFunction {
  Eigen::VectorXd phi;
  std::vector<LocalMatrix> D;
  double merit = 0.0;  // ||phi||^2
};

ProximalFunction Evaluate(const FrictionContactProblem& problem, const Eigen::VectorXd& rho, double sigma,
                          const Eigen::VectorXd& centre, const Eigen::VectorXd& r) {
  const int d = problem.dimension;
  const Eigen::VectorXd u = problem.W * r + problem.q + sigma * (r - centre);
  ProximalFunction f{Eigen::VectorXd(r.size()), std::vector<LocalMatrix>(problem.contacts()), 0.0};
  for (int i = 0; i < problem.contacts(); ++i) {
    AlartCurnierContact c = AlartCurnier(r.segment(d * i, d), u.segment(d * i, d), problem.mu(i), rho(i));
    f.phi.segment(d * i, d) = c.phi;
    f.D[i] = std::move(c.D);
  }
  f.merit = f.phi.squaredNorm();
  return f;
}

// J = I - D + rho D (W + sigma I), D block diagonal.
Eigen::MatrixXd Jacobian(const FrictionContactProblem& problem, const Eigen::VectorXd& rho, double sigma,
                         const ProximalFunction& f) {
  const int d = problem.dimension;
  const Eigen::Index n = problem.q.size();
  Eigen::MatrixXd J(n, n);
  for (int i = 0; i < problem.contacts(); ++i) {
    const Eigen::Index at = static_cast<Eigen::Index>(d) * i;
    J.middleRows(at, d).noalias() = rho(i) * f.D[i] * problem.W.middleRows(at, d);
    J.block(at, at, d, d) += LocalMatrix::Identity(d, d) - (1.0 - rho(i) * sigma) * f.D[i];
  }
  return J;
}

}  // namespace

FrictionContactSolution SolveFrictionNewton(const FrictionContactProblem& problem,
                                            const FrictionNewtonOptions& options) {
  CheckFrictionContact(problem);
  const int d = problem.dimension;
  const Eigen::Index n = problem.q.size();
  FLEXMBS_CHECK(options.initial_r.size() == 0 || options.initial_r.size() == n,
                "Newton: the initial r must have d n entries");
  FLEXMBS_CHECK(options.proximal > 0.0 && options.min_proximal > 0.0, "Newton: the proximal weights must be > 0");
  Eigen::VectorXd rho(problem.contacts());
  for (int i = 0; i < problem.contacts(); ++i) rho(i) = AlartCurnierRho(problem.W.block(d * i, d * i, d, d));
  const double w_scale = n > 0 && problem.W.diagonal().mean() > 0.0 ? problem.W.diagonal().mean() : 1.0;
  double sigma = options.proximal * w_scale;
  double sigma_floor = options.min_proximal * w_scale;

  FrictionContactSolution s;
  s.r = options.initial_r.size() == n ? options.initial_r : Eigen::VectorXd::Zero(n);
  Eigen::VectorXd centre = s.r;
  ProximalFunction f = Evaluate(problem, rho, sigma, centre, s.r);
  double merit_at_centre = f.merit;
  s.error = FrictionContactError(problem, s.r);
  while (s.error > options.tolerance && s.iterations < options.max_iterations) {
    ++s.iterations;
    const Eigen::VectorXd step = Jacobian(problem, rho, sigma, f).partialPivLu().solve(-f.phi);
    bool accepted = false;
    double alpha = 1.0;
    for (int halving = 0; halving < 20 && !accepted && step.allFinite(); ++halving) {
      const Eigen::VectorXd trial = s.r + alpha * step;
      ProximalFunction trial_f = Evaluate(problem, rho, sigma, centre, trial);
      if (trial_f.merit <= (1.0 - 1e-4 * alpha) * f.merit) {
        s.r = trial;
        f = std::move(trial_f);
        accepted = true;
      } else {
        alpha *= 0.5;
      }
    }
    s.error = FrictionContactError(problem, s.r);
    // Subproblem solved well enough (or Newton stuck on it): move the centre, adapt sigma. A step
    // cut below kShortStep counts as stuck: at a kink of ||Phi||^2 the Armijo steps shrink to
    // nothing one after another (measured: 1e-5 for ten steps) instead of failing at once.
    const bool stuck = !accepted || alpha < kShortStep;
    const bool solved = !stuck && f.merit <= options.subproblem_reduction * merit_at_centre;
    if ((solved || stuck) && options.proximal_per_error > 0.0) {
      sigma = stuck ? 10.0 * sigma
                    : std::max(std::min(0.1 * sigma, options.proximal_per_error * s.error * w_scale),
                               options.min_proximal * w_scale);
    } else if (solved || stuck) {
      // Newton stalls at this sigma: stay above it for a while; each solved subproblem lowers
      // that floor tenfold again, so a stall far from the solution does not hold sigma (and the
      // proximal point method's linear rate) for good.
      sigma_floor = stuck ? 10.0 * sigma : std::max(0.1 * sigma_floor, options.min_proximal * w_scale);
      sigma = solved ? std::max(0.1 * sigma, sigma_floor) : sigma_floor;
    }
    if (solved || stuck) {
      centre = s.r;
      f = Evaluate(problem, rho, sigma, centre, s.r);
      merit_at_centre = f.merit;
    }
  }
  s.u = problem.W * s.r + problem.q;
  s.converged = s.error <= options.tolerance;
  s.message = s.converged ? fmt::format("Newton: converged after {} steps", s.iterations)
                          : fmt::format("Newton: no convergence after {} steps (error {:.3g} > {:.3g})",
                                        s.iterations, s.error, options.tolerance);
  return s;
}

}  // namespace flexmbs::contact
