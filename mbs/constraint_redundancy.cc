#include "mbs/constraint_redundancy.h"

#include <fmt/format.h>

#include <cmath>

#include "mbs/constraint_solver.h"
#include "mbs/simulation_error.h"

namespace flexmbs::mbs {

std::string ConstraintRedundancy::Describe(const MultibodySystem& system) const {
  if (dropped_rows.empty()) return "none";
  std::string rows;
  for (const Eigen::Index row : dropped_rows) {
    rows += fmt::format("{}{}", rows.empty() ? "" : ", ", system.DescribeConstraintRow(row));
  }
  return fmt::format("{} row{} dropped: {}", dropped_rows.size(), dropped_rows.size() == 1 ? "" : "s", rows);
}

ConstraintRedundancy FindRedundantConstraints(const MultibodySystem& system, double t, const ConstVectorRef& y,
                                              double pivot_limit) {
  ConstraintRedundancy redundancy;
  redundancy.pivot_limit = pivot_limit;
  const Eigen::Index m = system.num_constraints();
  if (m == 0) return redundancy;
  const ConstraintSolver solver(system, t, y, system.Constraints(t, y).G, SolverRows::kAll);
  const Eigen::MatrixXd& S = solver.scaled_schur();
  // L L^T = S(kept, kept), grown one kept row at a time.
  Eigen::MatrixXd L = Eigen::MatrixXd::Zero(m, m);
  std::vector<Eigen::Index> kept;
  for (Eigen::Index row = 0; row < m; ++row) {
    const Eigen::Index n = static_cast<Eigen::Index>(kept.size());
    const Eigen::VectorXd l =
        L.topLeftCorner(n, n).triangularView<Eigen::Lower>().solve(S(kept, row));
    const double pivot = S(row, row) - l.squaredNorm();
    if (!(pivot >= pivot_limit)) {
      redundancy.dropped_rows.push_back(row);
      continue;
    }
    L.row(n).head(n) = l.transpose();
    L(n, n) = std::sqrt(pivot);
    kept.push_back(row);
  }
  return redundancy;
}

void CheckDroppedConstraints(const MultibodySystem& system, double t, const Eigen::VectorXd& g, double limit) {
  const std::vector<Eigen::Index>& dropped = system.dropped_constraints();
  if (dropped.empty()) return;
  Eigen::Index worst = 0;
  const double violation = g(dropped).cwiseAbs().maxCoeff(&worst);
  if (violation <= limit) return;
  throw SimulationError(t, fmt::format("t = {:.9g} s: the redundancy of the constraints changed: the dropped "
                                       "redundant {} is violated by {:.3g} (limit {:.3g}) while the kept rows hold",
                                       t, system.DescribeConstraintRow(dropped[static_cast<std::size_t>(worst)]),
                                       violation, limit));
}

}  // namespace flexmbs::mbs
