#include "contact/complementarity/friction_newton.h"

#include <vector>

#include <Eigen/LU>
#include <fmt/core.h>

#include "contact/complementarity/alart_curnier.h"
#include "core/error.h"

namespace flexmbs::contact {
namespace {

// Alart-Curnier's function of every contact at r, with its Jacobian blocks D_i.
struct GlobalFunction {
  Eigen::VectorXd phi;
  std::vector<LocalMatrix> D;
  double merit = 0.0;  // ||phi||^2
};

GlobalFunction Evaluate(const FrictionContactProblem& problem, const Eigen::VectorXd& rho, const Eigen::VectorXd& r) {
  const int d = problem.dimension;
  const Eigen::VectorXd u = problem.W * r + problem.q;
  GlobalFunction f{Eigen::VectorXd(r.size()), std::vector<LocalMatrix>(problem.contacts()), 0.0};
  for (int i = 0; i < problem.contacts(); ++i) {
    AlartCurnierContact c = AlartCurnier(r.segment(d * i, d), u.segment(d * i, d), problem.mu(i), rho(i));
    f.phi.segment(d * i, d) = c.phi;
    f.D[i] = std::move(c.D);
  }
  f.merit = f.phi.squaredNorm();
  return f;
}

// J = I - D + rho D (W + sigma I), D block diagonal.
Eigen::MatrixXd Jacobian(const FrictionContactProblem& problem, const Eigen::VectorXd& rho, const GlobalFunction& f,
                         double sigma) {
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
  FLEXMBS_CHECK(options.proximal > 0.0, "Newton: the proximal weight must be > 0");
  Eigen::VectorXd rho(problem.contacts());
  for (int i = 0; i < problem.contacts(); ++i) rho(i) = AlartCurnierRho(problem.W.block(d * i, d * i, d, d));
  const double w_scale = n > 0 && problem.W.diagonal().mean() > 0.0 ? problem.W.diagonal().mean() : 1.0;
  double sigma = options.proximal * w_scale;

  FrictionContactSolution s;
  s.r = options.initial_r.size() == n ? options.initial_r : Eigen::VectorXd::Zero(n);
  GlobalFunction f = Evaluate(problem, rho, s.r);
  s.error = FrictionContactError(problem, s.r);
  while (s.error > options.tolerance && s.iterations < options.max_iterations) {
    ++s.iterations;
    const Eigen::VectorXd step = Jacobian(problem, rho, f, sigma).partialPivLu().solve(-f.phi);
    bool accepted = false;
    double alpha = 1.0;
    for (int halving = 0; halving < 20 && !accepted && step.allFinite(); ++halving, alpha *= 0.5) {
      const Eigen::VectorXd trial = s.r + alpha * step;
      GlobalFunction trial_f = Evaluate(problem, rho, trial);
      if (trial_f.merit <= (1.0 - 1e-4 * alpha) * f.merit) {
        s.r = trial;
        f = std::move(trial_f);
        accepted = true;
      }
    }
    sigma = accepted ? std::max(0.1 * sigma, 1e-12 * w_scale) : 10.0 * sigma;
    if (accepted) s.error = FrictionContactError(problem, s.r);
  }
  s.u = problem.W * s.r + problem.q;
  s.converged = s.error <= options.tolerance;
  s.message = s.converged ? fmt::format("Newton: converged after {} steps", s.iterations)
                          : fmt::format("Newton: no convergence after {} steps (error {:.3g} > {:.3g})",
                                        s.iterations, s.error, options.tolerance);
  return s;
}

}  // namespace flexmbs::contact
