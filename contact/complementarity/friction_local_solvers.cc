#include "contact/complementarity/friction_local_solvers.h"

#include <array>
#include <cmath>

#include <Eigen/LU>

#include "contact/complementarity/alart_curnier.h"
#include "contact/complementarity/friction_contact_problem.h"

namespace flexmbs::contact {
namespace {

// Round-off slack of the case tests, relative to the quantity tested.
constexpr double kSlack = 1e-14;

bool InCone(const Eigen::Ref<const Eigen::VectorXd>& r, double mu) {
  return r(0) >= 0.0 && r.tail(r.size() - 1).norm() <= mu * r(0) * (1.0 + kSlack);
}

}  // namespace

Eigen::Vector2d SolvePlanarContact(const Eigen::Matrix2d& W, const Eigen::Vector2d& q, double mu) {
  if (q(0) >= 0.0) return Eigen::Vector2d::Zero();
  std::array<Eigen::Vector2d, 3> candidates;
  int count = 0;
  const double det = W(0, 0) * W(1, 1) - W(0, 1) * W(1, 0);
  if (std::abs(det) > kSlack * W.squaredNorm()) {
    const Eigen::Vector2d stick = Eigen::Vector2d(W(0, 1) * q(1) - W(1, 1) * q(0), W(1, 0) * q(0) - W(0, 0) * q(1)) / det;
    if (InCone(stick, mu)) return stick;
    candidates[count++] = stick;
  }
  for (const double s : {1.0, -1.0}) {  // s = sign(u_T), r_T = -s mu r_N
    const double denominator = W(0, 0) - s * mu * W(0, 1);
    if (denominator <= 0.0) continue;
    const double r_n = -q(0) / denominator;
    const Eigen::Vector2d r(r_n, -s * mu * r_n);
    const double u_t = W(1, 0) * r(0) + W(1, 1) * r(1) + q(1);
    if (s * u_t >= -kSlack * (std::abs(q(1)) + W.norm() * r_n)) return r;
    candidates[count++] = r;
  }
  Eigen::Vector2d best = Eigen::Vector2d::Zero();
  double best_error = ContactNaturalMapErrorSquared(best, q, mu);
  for (int k = 0; k < count; ++k) {
    const double error = ContactNaturalMapErrorSquared(candidates[k], W * candidates[k] + q, mu);
    if (error < best_error) {
      best = candidates[k];
      best_error = error;
    }
  }
  return best;
}

bool SolveSpatialContact(const Eigen::Matrix3d& W, const Eigen::Vector3d& q, double mu, Eigen::Vector3d& r,
                         const SpatialContactOptions& options) {
  if (q(0) >= 0.0) {
    r.setZero();
    return true;
  }
  const Eigen::PartialPivLU<Eigen::Matrix3d> lu(W);
  const Eigen::Vector3d stick = lu.solve(-q);
  if (stick.allFinite() && InCone(stick, mu)) {
    r = stick;
    return true;
  }
  const double rho = AlartCurnierRho(W);
  const double scale = rho * q.norm();
  AlartCurnierContact ac = AlartCurnier(r, W * r + q, mu, rho);
  double merit = ac.phi.squaredNorm();
  for (int k = 0; k < options.max_iterations; ++k) {
    if (std::sqrt(merit) <= options.tolerance * (r.norm() + scale)) return true;
    const Eigen::Matrix3d J = Eigen::Matrix3d::Identity() - ac.D + rho * ac.D * W;
    const Eigen::Vector3d step = J.fullPivLu().solve(-Eigen::Vector3d(ac.phi));
    bool accepted = false;
    double alpha = 1.0;
    for (int halving = 0; halving < 30 && !accepted; ++halving, alpha *= 0.5) {
      const Eigen::Vector3d trial = r + alpha * step;
      AlartCurnierContact trial_ac = AlartCurnier(trial, W * trial + q, mu, rho);
      const double trial_merit = trial_ac.phi.squaredNorm();
      if (trial_merit <= (1.0 - 1e-4 * alpha) * merit) {
        r = trial;
        ac = std::move(trial_ac);
        merit = trial_merit;
        accepted = true;
      }
    }
    if (!accepted) break;  // no descent along the Newton direction: a kink Newton cannot pass
  }
  return std::sqrt(merit) <= options.tolerance * (r.norm() + scale);
}

}  // namespace flexmbs::contact
