#include "mbs/constraint_redundancy.h"

#include <fmt/format.h>

#include <algorithm>
#include <Eigen/Cholesky>
#include <cmath>
#include <utility>

#include "mbs/constraint_solver.h"
#include "mbs/simulation_error.h"

namespace flexmbs::mbs {

std::string ConstraintRedundancy::Describe(const MultibodySystem& system) const {
  if (dropped_rows.empty()) return "none";
  std::string rows;
  for (std::size_t k = 0; k < dropped_rows.size(); ++k) {
    rows += fmt::format("{}{}", rows.empty() ? "" : ", ", DescribeRow(system, k));
  }
  return fmt::format("{} row{} dropped: {}", dropped_rows.size(), dropped_rows.size() == 1 ? "" : "s", rows);
}

std::string ConstraintRedundancy::DescribeRow(const MultibodySystem& system, std::size_t index) const {
  const std::string row = system.DescribeConstraintRow(dropped_rows.at(index));
  const double pivot = pivots.at(index);
  if (pivot < system.constraint_settings().singular_pivot) return row;
  return fmt::format("{} (nearly redundant: pivot {:.2g})", row, pivot);
}

namespace {

/// Per row k of G: in a planar scene the share of its mobility G_k M^-1 G_k^T (the full mass
/// matrix) that its in-plane part G_k S M~^-1 S^T G_k^T keeps (the solver's), 0 for a row that
/// constrains only out-of-plane motion (a revolute's z translation and x, y alignments; on a
/// reduced body also a row whose in-plane part is its mesh's round-off); 1 for every row of a
/// spatial scene.
Eigen::VectorXd InPlaneShares(const MultibodySystem& system, const ConstVectorRef& y, const Eigen::MatrixXd& G,
                              const ConstraintSolver& solver) {
  Eigen::VectorXd share = Eigen::VectorXd::Ones(G.rows());
  if (!system.planar()) return share;
  Eigen::VectorXd full = Eigen::VectorXd::Zero(G.rows());
  for (int b = 0; b < system.num_bodies(); ++b) {
    const VelocityBlock& block = system.velocity_block(b);
    const Eigen::MatrixXd G_b = G.middleCols(block.start, block.size);
    const Eigen::MatrixXd Minv_G_b_T = system.BodyMassMatrix(b, y).llt().solve(G_b.transpose());
    full += G_b.cwiseProduct(Minv_G_b_T.transpose()).rowwise().sum();
  }
  for (Eigen::Index k = 0; k < G.rows(); ++k) {
    const Eigen::VectorXd G_k = G.row(k).transpose();
    share(k) = full(k) > 0.0 ? G_k.dot(solver.SolveMass(G_k)) / full(k) : 0.0;
  }
  return share;
}

}  // namespace

ConstraintRedundancy FindRedundantConstraints(const MultibodySystem& system, double t, const ConstVectorRef& y,
                                              double pivot_limit) {
  ConstraintRedundancy redundancy;
  redundancy.pivot_limit = pivot_limit;
  const Eigen::Index m = system.num_constraints();
  if (m == 0) return redundancy;
  const Eigen::MatrixXd G = system.Constraints(t, y).G;
  const ConstraintSolver solver(system, t, y, G, SolverRows::kAll);
  const Eigen::MatrixXd& S = solver.scaled_schur();
  const Eigen::VectorXd in_plane = InPlaneShares(system, y, G, solver);
  // L L^T = S(kept, kept), grown one kept row at a time.
  Eigen::MatrixXd L = Eigen::MatrixXd::Zero(m, m);
  std::vector<Eigen::Index> kept;
  for (Eigen::Index row = 0; row < m; ++row) {
    const Eigen::Index n = static_cast<Eigen::Index>(kept.size());
    if (in_plane(row) < pivot_limit) {  // an out-of-plane row of a planar scene
      redundancy.dropped_rows.push_back(row);
      redundancy.pivots.push_back(in_plane(row));
      redundancy.drift_rates.push_back(0.0);
      continue;
    }
    const Eigen::VectorXd l =
        L.topLeftCorner(n, n).triangularView<Eigen::Lower>().solve(S(kept, row));
    const double pivot = S(row, row) - l.squaredNorm();
    if (!(pivot >= pivot_limit)) {
      redundancy.dropped_rows.push_back(row);
      redundancy.pivots.push_back(pivot);
      const Eigen::VectorXd G_row = G.row(row).transpose();
      const double schur_diagonal = G_row.dot(solver.SolveMass(G_row));
      redundancy.drift_rates.push_back(std::sqrt(std::max(pivot, 0.0) * schur_diagonal));
      continue;
    }
    L.row(n).head(n) = l.transpose();
    L(n, n) = std::sqrt(pivot);
    kept.push_back(row);
  }
  return redundancy;
}

DroppedRowWatch::DroppedRowWatch(ConstraintRedundancy redundancy, double base_limit)
    : redundancy_(std::move(redundancy)), base_limit_(base_limit) {}

void DroppedRowWatch::Check(const MultibodySystem& system, double t, const ConstVectorRef& y) {
  const std::vector<Eigen::Index>& dropped = redundancy_.dropped_rows;
  if (dropped.empty()) return;
  const double speed = std::sqrt(2.0 * system.KineticEnergy(y));  // |u|_M
  if (started_) path_ += std::abs(t - last_time_) * std::max(speed, speed_);
  started_ = true;
  speed_ = speed;
  last_time_ = t;
  const Eigen::VectorXd g = system.Constraints(t, y).g;
  for (std::size_t k = 0; k < dropped.size(); ++k) {
    const double violation = std::abs(g(dropped[k]));
    const double limit = base_limit_ + redundancy_.drift_rates[k] * path_;
    largest_violation_ = std::max(largest_violation_, violation);
    largest_share_ = std::max(largest_share_, violation / limit);
    if (violation > limit) {
      throw SimulationError(t, fmt::format("t = {:.9g} s: the redundancy of the constraints changed: the dropped "
                                           "redundant {} is violated by {:.3g} (limit {:.3g}) while the kept rows hold",
                                           t, redundancy_.DescribeRow(system, k), violation, limit));
    }
  }
}

}  // namespace flexmbs::mbs
