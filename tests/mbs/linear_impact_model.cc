#include "tests/mbs/linear_impact_model.h"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "contact/complementarity/lcp_pgs.h"

namespace flexmbs::mbs::testing {

LinearImpactHistory IntegrateLinearImpact(const LinearContactModel& model, const Eigen::VectorXd& v0, double h,
                                          double end_time) {
  const auto start = std::chrono::steady_clock::now();
  const Eigen::SparseMatrix<double> A = model.M + 0.25 * h * h * model.K;
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> factor(A);
  if (factor.info() != Eigen::Success) throw std::runtime_error("IntegrateLinearImpact: M + h^2/4 K is singular");
  const Eigen::MatrixXd A_inv_Ht = factor.solve(Eigen::MatrixXd(model.H.transpose()));
  const Eigen::MatrixXd W = model.H * A_inv_Ht;

  LinearImpactHistory history;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(v0.size()), v = v0;
  for (double t = 0.0; t < end_time; t += h) {
    const Eigen::VectorXd v_free = v - factor.solve(h * (model.K * (x + 0.5 * h * v)));
    std::vector<Eigen::Index> active;
    const Eigen::VectorXd predicted = model.g0 + model.H * x + 0.5 * h * model.H * v;
    for (Eigen::Index c = 0; c < predicted.size(); ++c) {
      if (predicted(c) <= 0.0) active.push_back(c);
    }
    Eigen::VectorXd v_next = v_free;
    double impulse = 0.0;
    if (!active.empty()) {
      contact::LcpProblem lcp{W(active, active), model.H(active, Eigen::all) * v_free};
      contact::PgsOptions pgs;
      pgs.tolerance = 1e-13;
      const contact::LcpSolution solution = contact::SolveLcpPgs(lcp, pgs);
      if (!solution.converged) throw std::runtime_error("IntegrateLinearImpact: " + solution.message);
      v_next += A_inv_Ht(Eigen::all, active) * solution.z;
      impulse = solution.z.sum();
    }
    x += 0.5 * h * (v + v_next);
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
