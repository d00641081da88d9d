#include "tests/mbs/hertz_rod_model.h"

#include <Eigen/SparseCholesky>
#include <chrono>
#include <cmath>
#include <stdexcept>

namespace flexmbs::mbs::testing {
namespace {

/// F >= 0 with F = k max(delta0 - c F, 0)^1.5 (c > 0): 0 if delta0 <= 0, else by Newton's method on
/// g(F) = F - k (delta0 - c F)^1.5, increasing and convex-free on [0, delta0 / c], from the
/// bracket's midpoint kept inside it.
double SolveHertzForce(double k, double delta0, double c) {
  if (delta0 <= 0.0) return 0.0;
  double low = 0.0, high = delta0 / c, F = 0.5 * high;
  for (int iteration = 0; iteration < 200; ++iteration) {
    const double d = delta0 - c * F;
    const double g = F - k * std::pow(d, 1.5), dg = 1.0 + 1.5 * k * c * std::sqrt(d);
    (g > 0.0 ? high : low) = F;
    double next = F - g / dg;
    if (!(next > low && next < high)) next = 0.5 * (low + high);
    if (std::abs(next - F) <= 1e-15 * high) return next;
    F = next;
  }
  throw std::runtime_error("SolveHertzForce: no convergence");
}

}  // namespace

HertzImpactHistory IntegrateHertzImpact(const HertzImpactModel& model, double v0, double h, double end_time) {
  const auto start = std::chrono::steady_clock::now();
  const double four_over_h2 = 4.0 / (h * h);
  const Eigen::SparseMatrix<double> K_eff = model.K + four_over_h2 * model.M;
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> factor(K_eff);
  if (factor.info() != Eigen::Success) throw std::runtime_error("IntegrateHertzImpact: K + 4/h^2 M is singular");
  const Eigen::VectorXd K_eff_inv_b = factor.solve(model.b);
  // delta_k+1 = delta_0 - c F_k+1: the sphere's and the face's compliance over one step.
  const double c = h * h / (4.0 * model.sphere_mass) + model.b.dot(K_eff_inv_b);

  const Eigen::Index n = model.K.rows();
  Eigen::VectorXd u = Eigen::VectorXd::Zero(n), v = Eigen::VectorXd::Zero(n), a = Eigen::VectorXd::Zero(n);
  double x = 0.0, x_dot = v0, x_ddot = 0.0;
  HertzImpactHistory history;
  for (double t = 0.0; t < end_time; t += h) {
    const Eigen::VectorXd u_free = factor.solve(model.M * (four_over_h2 * (u + h * v) + a));
    const double x_free = x + h * x_dot + 0.25 * h * h * x_ddot;
    const double F = SolveHertzForce(model.hertz_stiffness, x_free - model.b.dot(u_free) - model.gap0, c);
    const Eigen::VectorXd u_next = u_free + F * K_eff_inv_b;
    const double x_next = x_free - 0.25 * h * h * F / model.sphere_mass;
    const Eigen::VectorXd a_next = four_over_h2 * (u_next - u - h * v) - a;
    const double x_ddot_next = -F / model.sphere_mass;
    v += 0.5 * h * (a + a_next);
    x_dot += 0.5 * h * (x_ddot + x_ddot_next);
    u = u_next;
    a = a_next;
    x = x_next;
    x_ddot = x_ddot_next;
    history.t.push_back(t + h);
    history.force.push_back(F);
  }
  history.sphere_velocity = x_dot;
  history.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return history;
}

}  // namespace flexmbs::mbs::testing
