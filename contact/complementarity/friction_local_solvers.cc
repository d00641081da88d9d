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

// The sliding reaction of direction angle theta, r = r_N (1, -mu cos theta, -mu sin theta), with
// r_N set by u_N = 0; r_N <= 0 (no sliding this way) when W's normal row does not push back.
struct Slide {
  Eigen::Vector3d r;
  double cross = 0.0;  // u_T x t: zero when u_T is parallel to t = (cos, sin)
  double along = 0.0;  // u_T . t: must be >= 0 (r_T opposes u_T)
};

Slide SlideAt(const Eigen::Matrix3d& W, const Eigen::Vector3d& q, double mu, double theta) {
  const double c = std::cos(theta), s = std::sin(theta);
  const Eigen::Vector3d a(1.0, -mu * c, -mu * s);
  const double push = W.row(0).dot(a);
  Slide slide{push > 0.0 ? Eigen::Vector3d(-q(0) / push * a) : Eigen::Vector3d::Zero(), 0.0, -1.0};
  if (push <= 0.0) return slide;
  const Eigen::Vector2d u_t = (W * slide.r + q).tail<2>();
  slide.cross = u_t(0) * s - u_t(1) * c;
  slide.along = u_t(0) * c + u_t(1) * s;
  return slide;
}

// Every sliding solution found on a scan of the direction angle: where u_T x t changes sign
// between samples (with r_N > 0 at both), bisection to round-off; returns the candidate with the
// least natural-map error, or r unchanged if it is better than all.
void SolveSpatialSliding(const Eigen::Matrix3d& W, const Eigen::Vector3d& q, double mu, Eigen::Vector3d& r) {
  constexpr int kSamples = 64;
  constexpr double kTwoPi = 6.283185307179586;
  double best_error = ContactNaturalMapErrorSquared(r, W * r + q, mu);
  double theta_a = 0.0;
  Slide a = SlideAt(W, q, mu, theta_a);
  for (int k = 1; k <= kSamples; ++k) {
    double theta_b = kTwoPi * k / kSamples;
    const Slide b = SlideAt(W, q, mu, theta_b);
    if (a.r(0) > 0.0 && b.r(0) > 0.0 && (a.cross <= 0.0) != (b.cross <= 0.0)) {
      double low = theta_a, high = theta_b;
      const bool low_negative = a.cross <= 0.0;
      for (int halving = 0; halving < 60 && low < high; ++halving) {
        const double middle = 0.5 * (low + high);
        if (middle <= low || middle >= high) break;
        ((SlideAt(W, q, mu, middle).cross <= 0.0) == low_negative ? low : high) = middle;
      }
      const Slide root = SlideAt(W, q, mu, 0.5 * (low + high));
      const double error = ContactNaturalMapErrorSquared(root.r, W * root.r + q, mu);
      if (root.along >= 0.0 && error < best_error) {
        best_error = error;
        r = root.r;
      }
    }
    theta_a = theta_b;
    a = b;
  }
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
  if (std::sqrt(merit) <= options.tolerance * (r.norm() + scale)) return true;
  // Newton stalled (a kink of ||Phi||^2 or a poor rho): the sliding solutions by enumeration.
  SolveSpatialSliding(W, q, mu, r);
  merit = AlartCurnier(r, W * r + q, mu, rho).phi.squaredNorm();
  return std::sqrt(merit) <= options.tolerance * (r.norm() + scale);
}

}  // namespace flexmbs::contact
