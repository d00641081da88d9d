#include "tests/mbs/linear_impact_model.h"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "contact/complementarity/lcp_pgs.h"

namespace flexmbs::mbs::testing {

namespace {

/// The LCP of one step's contact impulses (the formulations of linear_impact_model.h) over the
/// contacts `active`, with the free velocity v_free from (x, v).
contact::LcpProblem StepLcp(const LinearContactModel& model, const ImpactScheme& scheme, const Eigen::MatrixXd& W,
                            double h, const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                            const Eigen::VectorXd& v_free, const std::vector<Eigen::Index>& active) {
  const Eigen::MatrixXd H = model.H(active, Eigen::all);
  const Eigen::VectorXd gap = model.g0(active) + H * x;
  switch (scheme.formulation) {
    case ContactFormulation::kVelocityLevel:
      return {W(active, active), H * v_free};
    case ContactFormulation::kPositionLevel:
      return {W(active, active), H * v_free + gap / h};
    case ContactFormulation::kPenalty: {
      const double theta = scheme.theta;
      const Eigen::Index n = static_cast<Eigen::Index>(active.size());
      const Eigen::MatrixXd M = h * theta * theta * W(active, active) +
                                Eigen::MatrixXd::Identity(n, n) / (h * scheme.penalty_stiffness);
      return {M, gap + h * theta * H * ((1.0 - theta) * v + theta * v_free)};
    }
  }
  throw std::logic_error("StepLcp: unknown formulation");
}

/// The contacts taking part in a step from (x, v) with the free velocity v_free.
std::vector<Eigen::Index> ActiveContacts(const LinearContactModel& model, const ImpactScheme& scheme, double h,
                                         const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                                         const Eigen::VectorXd& v_free) {
  Eigen::VectorXd predicted;
  switch (scheme.formulation) {
    case ContactFormulation::kVelocityLevel:
      predicted = model.g0 + model.H * (x + 0.5 * h * v);
      break;
    case ContactFormulation::kPositionLevel:
      predicted = model.g0 + model.H * (x + h * v_free);
      break;
    case ContactFormulation::kPenalty:  // every contact: its LCP row gives P = 0 while it is open
      predicted = Eigen::VectorXd::Constant(model.g0.size(), -1.0);
      break;
  }
  std::vector<Eigen::Index> active;
  for (Eigen::Index c = 0; c < predicted.size(); ++c) {
    if (predicted(c) <= 0.0) active.push_back(c);
  }
  return active;
}

}  // namespace

LinearImpactHistory IntegrateLinearImpact(const LinearContactModel& model, const Eigen::VectorXd& v0, double h,
                                          double end_time, const ImpactScheme& scheme) {
  const auto start = std::chrono::steady_clock::now();
  const double theta = scheme.theta;
  const Eigen::SparseMatrix<double> A = model.M + theta * theta * h * h * model.K;
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> factor(A);
  if (factor.info() != Eigen::Success) throw std::runtime_error("IntegrateLinearImpact: M + h^2 theta^2 K is singular");
  const Eigen::MatrixXd A_inv_Ht = factor.solve(Eigen::MatrixXd(model.H.transpose()));
  const Eigen::MatrixXd W = model.H * A_inv_Ht;

  LinearImpactHistory history;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(v0.size()), v = v0;
  for (double t = 0.0; t < end_time; t += h) {
    const Eigen::VectorXd v_free = v - factor.solve(h * (model.K * (x + theta * h * v)));
    const std::vector<Eigen::Index> active = ActiveContacts(model, scheme, h, x, v, v_free);
    Eigen::VectorXd v_next = v_free;
    double impulse = 0.0;
    if (!active.empty()) {
      contact::PgsOptions pgs;
      pgs.tolerance = 1e-13;
      const contact::LcpSolution solution = contact::SolveLcpPgs(StepLcp(model, scheme, W, h, x, v, v_free, active), pgs);
      if (!solution.converged) throw std::runtime_error("IntegrateLinearImpact: " + solution.message);
      v_next += A_inv_Ht(Eigen::all, active) * solution.z;
      impulse = solution.z.sum();
    }
    x += h * (theta * v_next + (1.0 - theta) * v);
    v = v_next;
    history.t.push_back(t + h);
    history.impulse.push_back(impulse);
  }
  history.x = x;
  history.v = v;
  history.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return history;
}

double LargestCumulativeDifference(const std::vector<double>& a, const std::vector<double>& b) {
  double sum_a = 0.0, sum_b = 0.0, largest = 0.0;
  for (std::size_t k = 0; k < std::min(a.size(), b.size()); ++k) {
    sum_a += a[k];
    sum_b += b[k];
    largest = std::max(largest, std::abs(sum_a - sum_b));
  }
  return largest;
}

}  // namespace flexmbs::mbs::testing
