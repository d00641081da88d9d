#include "mbs/constraint_solver.h"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "mbs/simulation_error.h"

namespace flexmbs::mbs {
namespace {

// A constraint row takes part in a near-null vector of the scaled S when its component is at
// least this share of the vector's largest one (rows of one loop have comparable components
// after the unit-diagonal scaling; unrelated rows are at round-off).
constexpr double kInvolvedShare = 0.05;

}  // namespace

ConstraintSolver::ConstraintSolver(const MultibodySystem& system, double t, const ConstVectorRef& y,
                                   const Eigen::MatrixXd& G, SolverRows rows)
    : system_(system) {
  mass_factors_.reserve(static_cast<std::size_t>(system.num_bodies()));
  for (int b = 0; b < system.num_bodies(); ++b) {
    mass_factors_.emplace_back(system.BodyMassMatrix(b, y));
    if (mass_factors_.back().info() != Eigen::Success) {
      throw SimulationError(t, fmt::format("t = {:.9g} s: body '{}': mass matrix is not positive definite", t,
                                           system.body(b).name()));
    }
  }
  const Eigen::Index m = G.rows();
  Minv_GT_.resize(system.num_velocities(), m);
  for (Eigen::Index k = 0; k < m; ++k) Minv_GT_.col(k) = SolveMass(G.row(k).transpose());
  if (rows == SolverRows::kKept) {
    rows_ = system.KeptConstraints();
  } else {
    for (Eigen::Index k = 0; k < m; ++k) rows_.push_back(k);
  }
  if (rows_.empty()) return;
  const Eigen::MatrixXd S = G(rows_, Eigen::all) * Minv_GT_(Eigen::all, rows_);
  scale_ = S.diagonal().cwiseMax(0.0).cwiseSqrt();
  if (scale_.minCoeff() == 0.0) smallest_pivot_ = 0.0;  // a row of G that moves nothing
  scale_ = (scale_.array() > 0.0).select(scale_, 1.0);
  const Eigen::VectorXd inverse_scale = scale_.cwiseInverse();
  S_scaled_ = inverse_scale.asDiagonal() * (0.5 * (S + S.transpose())) * inverse_scale.asDiagonal();
  schur_factor_.compute(S_scaled_);
  smallest_pivot_ = std::min(smallest_pivot_, schur_factor_.vectorD().minCoeff());
}

Eigen::VectorXd ConstraintSolver::SolveMass(const ConstVectorRef& r) const {
  Eigen::VectorXd out(r.size());
  for (int b = 0; b < system_.num_bodies(); ++b) {
    const Eigen::Index offset = system_.velocity_offset(b), n = system_.body(b).num_velocities();
    out.segment(offset, n) = mass_factors_[static_cast<std::size_t>(b)].solve(r.segment(offset, n));
  }
  return out;
}

Eigen::VectorXd ConstraintSolver::SolveSchur(const ConstVectorRef& r) const {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(r.size());
  if (rows_.empty()) return out;
  const Eigen::VectorXd inverse_scale = scale_.cwiseInverse();
  out(rows_) = inverse_scale.cwiseProduct(schur_factor_.solve(inverse_scale.cwiseProduct(r(rows_))));
  return out;
}

std::vector<int> ConstraintSolver::DependentJoints(double pivot) const {
  std::vector<int> joints;
  if (S_scaled_.rows() == 0) return joints;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(S_scaled_);
  for (Eigen::Index i = 0; i < S_scaled_.rows() && (i == 0 || eigen.eigenvalues()(i) < pivot); ++i) {
    const Eigen::VectorXd v = eigen.eigenvectors().col(i).cwiseAbs();
    for (Eigen::Index row = 0; row < v.size(); ++row) {
      if (v(row) >= kInvolvedShare * v.maxCoeff()) {
        joints.push_back(system_.JointOfConstraint(rows_[static_cast<std::size_t>(row)]));
      }
    }
  }
  std::sort(joints.begin(), joints.end());
  joints.erase(std::unique(joints.begin(), joints.end()), joints.end());
  return joints;
}

std::string ConstraintSolver::DescribeRankDeficiency(double t, double pivot) const {
  std::string names;
  for (const int joint : DependentJoints(pivot)) {
    names += fmt::format("{}'{}'", names.empty() ? "" : ", ", system_.joint(joint).name());
  }
  return fmt::format("t = {:.9g} s: the constraint Jacobian is rank deficient (smallest relative pivot {:.3g}, "
                     "limit {:.3g}) in joints {}: redundant joints, or a closed loop in a singular configuration",
                     t, smallest_pivot_, pivot, names);
}

void ConstraintSolver::RequireFullRank(double t, double pivot) const {
  if (!(smallest_pivot_ >= pivot)) throw SimulationError(t, DescribeRankDeficiency(t, pivot));
}

}  // namespace flexmbs::mbs
