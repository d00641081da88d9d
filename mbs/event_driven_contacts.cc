#include "mbs/event_driven_contacts.h"

#include <fmt/format.h>

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "contact/complementarity/friction_newton.h"
#include "contact/complementarity/lcp_problem.h"
#include "contact/complementarity/lcp_solver.h"
#include "core/error.h"
#include "mbs/constraint_solver.h"
#include "mbs/contact_reactions.h"
#include "mbs/cpu_time.h"
#include "mbs/planar.h"
#include "mbs/simulation_error.h"

namespace flexmbs::mbs {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

/// The constrained system's response to generalized forces R (n_u x k) at one state, the kept
/// joint rows holding: velocities dv = A_c^-1 R = M^-1 R - M^-1 G^T S^-1 G M^-1 R and the joints'
/// multipliers dlambda = -S^-1 G M^-1 R (M u' = h + G^T lambda + R f, G u' = gamma).
struct ConstrainedResponse {
  MatrixXd dv;       ///< n_u x k
  MatrixXd dlambda;  ///< m x k
};

ConstrainedResponse Respond(const MultibodySystem& system, double t, const ConstVectorRef& y,
                            const MatrixXd& R) {
  ConstrainedResponse response;
  if (system.num_constraints() == 0) {
    response.dv =
        ConstraintSolver(system, t, y, MatrixXd(0, system.num_velocities())).SolveMassColumns(R);
    response.dlambda = MatrixXd(0, R.cols());
    return response;
  }
  const ConstraintSolver solver(system, t, y, system.Constraints(t, y).G);
  response.dv = solver.SolveMassColumns(R);
  response.dlambda.resize(system.num_constraints(), R.cols());
  for (Index j = 0; j < R.cols(); ++j) {
    const VectorXd schur = solver.SolveSchur(solver.constraint_jacobian() * response.dv.col(j));
    response.dv.col(j) -= solver.mass_inverse_G_transpose() * schur;
    response.dlambda.col(j) = -schur;
  }
  return response;
}

/// The rows of the listed points' velocities stacked, d per point: W_N (d = 1), W_N, W_T1
/// (d = 2: a planar scene, t1 the in-plane tangent, EventDrivenContacts::Evaluate) or W_N, W_T1,
/// W_T2 (d = 3) (d k x n_u).
MatrixXd LocalRows(const std::vector<UnilateralContactKinematics>& kinematics, Index nu, Index d) {
  MatrixXd W(d * static_cast<Index>(kinematics.size()), nu);
  for (std::size_t i = 0; i < kinematics.size(); ++i) {
    const Index row = d * static_cast<Index>(i);
    W.row(row) = kinematics[i].W_N;
    if (d > 1) W.middleRows(row + 1, d - 1) = kinematics[i].W_T.topRows(d - 1);
  }
  return W;
}

/// Sweeps of NSGS before the friction-contact solver hands over to Newton.
constexpr int kNsgsSweeps = 1000;

/// The reactions r of a local problem and how the solve went.
struct Reactions {
  VectorXd r;
  contact::SolveStatus status;
};

/// The reactions of U = W r + q with d rows per point: the LCP (W, q) (d = 1; contact::SolveLcp) or
/// the friction-contact problem (d = 3, or 2 in a planar scene; contact::SolveFrictionNewton, then
/// SolveContactReactions).
/// A solve that does not converge is a SimulationError at t naming `what`.
Reactions SolveOrStop(const MatrixXd& W, const VectorXd& q, const VectorXd& mu, Index d, double tolerance, double t,
                      std::string_view what) {
  Reactions reactions;
  contact::SolveStatus& status = reactions.status;
  if (d == 1) {
    contact::LcpSolution lcp = contact::SolveLcp({W, q}, {tolerance});
    reactions.r = std::move(lcp.z);
    status = lcp;
  } else {
    // The proximal Newton solver first: its proximal centre starts at r = 0, so of statically
    // indeterminate reactions (two feet squeezing each other along a cylinder's axis) it returns
    // one near the least; NSGS drifts along W's null space to the edge of the cones, where the
    // sticking points' margins vanish and their roots chatter. NSGS and Newton behind it if not.
    contact::FrictionNewtonOptions newton;
    newton.tolerance = tolerance;
    contact::FrictionContactSolution solution = contact::SolveFrictionNewton({static_cast<int>(d), W, q, mu}, newton);
    reactions.r = std::move(solution.r);
    status = solution;
    if (!status.converged) status = SolveContactReactions(W, q, mu, tolerance, kNsgsSweeps, &reactions.r, d);
  }
  if (!status.converged) {
    throw SimulationError(
        t, fmt::format("t = {:.9g} s: event-driven {} problem of {} contact points did not converge: "
                       "residual {:.3g} > tolerance {:.3g} after {} iterations ({})",
                       t, what, mu.size(), status.error, tolerance, status.iterations, status.message));
  }
  return reactions;
}

/// Of a local vector (d entries per point, the normal first), the normal entries.
VectorXd NormalEntries(const VectorXd& local, Index d) {
  return Eigen::Map<const VectorXd, 0, Eigen::InnerStride<>>(local.data(), local.size() / d, Eigen::InnerStride<>(d));
}

/// Of a local vector with d entries per point (d = 2 or 3), the tangential pairs (2 x k; the
/// second 0 for d = 2, the out-of-plane tangent of a planar scene).
Eigen::Matrix2Xd TangentialEntries(const VectorXd& local, Index d) {
  Eigen::Matrix2Xd pairs = Eigen::Matrix2Xd::Zero(2, local.size() / d);
  for (Index i = 0; i < pairs.cols(); ++i) pairs.col(i).head(d - 1) = local.segment(d * i + 1, d - 1);
  return pairs;
}

/// The direction a sliding point's friction opposes: its tangential velocity's, U_T / |U_T| with
/// U_T = W_T u, while U_T points ahead of the slide's direction s (U_T . s > 0) and |U_T| > 1e-12
/// m/s; s itself at the start of a slide and once U_T has turned through 90 degrees from it, so
/// that the motion stays smooth up to the root U_T . s = 0 where the point sticks or turns.
Eigen::Vector2d SlideDirection(const UnilateralContactKinematics& k, const ConstVectorRef& u, const Eigen::Vector2d& s) {
  const Eigen::Vector2d U_T = k.W_T * u;
  constexpr double kDirectionSpeed = 1e-12;  // [m/s]
  return U_T.dot(s) > 0.0 && U_T.norm() > kDirectionSpeed ? Eigen::Vector2d(U_T.normalized()) : s;
}

}  // namespace

EventDrivenContacts::EventDrivenContacts(const MultibodySystem& system,
                                         const EventDrivenOptions& options)
    : system_(system), options_(options) {
  for (int k = 0; k < system.num_unilateral_contacts(); ++k) {
    for (int p = 0; p < system.unilateral_contact(k).num_points(); ++p) points_.push_back({k, p});
  }
}

std::vector<UnilateralContactKinematics> EventDrivenContacts::Evaluate(
    double t, const ConstVectorRef& y, const std::vector<int>& indices) const {
  std::vector<UnilateralContactKinematics> out(indices.size());
  int evaluated_contact = -1;
  std::vector<UnilateralContactKinematics> contact_points;
  // Sorted by contact, so that each contact is evaluated once.
  std::vector<std::size_t> order(indices.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return indices[a] < indices[b]; });
  for (const std::size_t i : order) {
    const ContactPointRef& ref = points_.at(static_cast<std::size_t>(indices[i]));
    if (ref.contact != evaluated_contact) {
      contact_points = system_.unilateral_contact(ref.contact).Evaluate(t, system_, y);
      evaluated_contact = ref.contact;
    }
    out[i] = contact_points.at(static_cast<std::size_t>(ref.point));
    if (system_.planar()) UsePlanarTangents(out[i]);
  }
  return out;
}

std::vector<UnilateralContactKinematics> EventDrivenContacts::EvaluateAll(
    double t, const ConstVectorRef& y) const {
  std::vector<UnilateralContactKinematics> out;
  out.reserve(points_.size());
  for (int k = 0; k < system_.num_unilateral_contacts(); ++k) {
    for (UnilateralContactKinematics& point :
         system_.unilateral_contact(k).Evaluate(t, system_, y)) {
      if (system_.planar()) UsePlanarTangents(point);
      out.push_back(std::move(point));
    }
  }
  return out;
}

bool EventDrivenContacts::HasFriction(int contact) const {
  return system_.unilateral_contact(contact).law().friction > 0.0;
}

Eigen::Matrix3Xd EventDrivenContacts::AccelerationBias(double t, const ConstVectorRef& y,
                                                       const std::vector<int>& indices) const {
  const Index nu = system_.num_velocities();
  const VectorXd u = y.tail(nu);
  const double eps = std::cbrt(std::numeric_limits<double>::epsilon()) / std::max(1.0, u.lpNorm<Eigen::Infinity>());
  VectorXd y_plus = y, y_minus = y;
  system_.DisplacePositions(eps * u, y_plus);
  system_.DisplacePositions(-eps * u, y_minus);
  const auto plus = Evaluate(t, y_plus, indices), minus = Evaluate(t, y_minus, indices);
  Eigen::Matrix3Xd bias(3, static_cast<Index>(indices.size()));
  for (std::size_t i = 0; i < indices.size(); ++i) {
    const Index c = static_cast<Index>(i);
    bias(0, c) = (plus[i].W_N - minus[i].W_N).dot(u) / (2.0 * eps);
    bias.col(c).tail<2>() = (plus[i].W_T - minus[i].W_T) * u / (2.0 * eps);
  }
  return bias;
}

ClosedContactForces EventDrivenContacts::Derivative(double t, const ConstVectorRef& y,
                                                    const std::vector<ClosedPoint>& closed,
                                                    Eigen::Ref<VectorXd> y_dot) const {
  const Index nu = system_.num_velocities();
  for (int b = 0; b < system_.num_bodies(); ++b) {
    PositionDerivative(system_.BodyPositions(y, b), system_.BodyVelocities(y, b),
                       y_dot.segment(system_.position_offset(b), system_.body(b).num_positions()));
  }
  const Index k = static_cast<Index>(closed.size());
  ClosedContactForces forces;
  forces.joint_lambda.resize(system_.num_constraints());
  forces.lambda_T.setZero(2, k);
  forces.tangential_acceleration.setZero(2, k);
  forces.tangential_delassus.setZero(k);
  auto u_dot = y_dot.tail(nu);
  system_.Accelerations(t, y, u_dot, forces.joint_lambda);
  if (closed.empty()) return forces;
  std::vector<int> indices;
  for (const ClosedPoint& point : closed) indices.push_back(point.index);
  const auto kinematics = Evaluate(t, y, indices);
  const bool friction = std::any_of(closed.begin(), closed.end(),
                                    [](const ClosedPoint& p) { return p.tangential != Tangential::kFree; });
  const Index d = friction ? ContactDimension(system_) : 1;
  const MatrixXd rows = LocalRows(kinematics, nu, d);
  MatrixXd columns = rows.transpose();
  // The sticking points' cones in the friction-contact problem; a sliding point's friction
  // -mu lambda_N s rides on its normal column (the problem sees it frictionless).
  VectorXd mu = VectorXd::Zero(k);
  Eigen::Matrix2Xd slide_friction = Eigen::Matrix2Xd::Zero(2, k);  // -mu s per sliding point
  for (Index i = 0; i < k; ++i) {
    const ClosedPoint& point = closed[static_cast<std::size_t>(i)];
    const double mu_i = system_.unilateral_contact(points_[static_cast<std::size_t>(point.index)].contact).law().friction;
    if (point.tangential == Tangential::kStick) mu(i) = mu_i;
    if (point.tangential != Tangential::kSlide) continue;
    const UnilateralContactKinematics& ki = kinematics[static_cast<std::size_t>(i)];
    slide_friction.col(i) = -mu_i * SlideDirection(ki, y.tail(nu), point.slide_direction);
    columns.col(d * i) += ki.W_T.transpose() * slide_friction.col(i);
  }
  const Eigen::Matrix3Xd bias = AccelerationBias(t, y, indices);
  const double solve_start = ProcessCpuSeconds();
  const ConstrainedResponse response = Respond(system_, t, y, columns);
  const MatrixXd W = rows * response.dv;
  VectorXd q = rows * u_dot;
  for (Index i = 0; i < k; ++i) q.segment(d * i, d) += bias.col(i).head(d);
  const Reactions reactions = SolveOrStop(W, q, mu, d, options_.lcp_tolerance, t, "acceleration-level");
  solve_cpu_seconds_ += ProcessCpuSeconds() - solve_start;
  const VectorXd& r = reactions.r;
  const VectorXd a = W * r + q;
  u_dot += response.dv * r;
  forces.joint_lambda += response.dlambda * r;
  forces.lambda_N = NormalEntries(r, d);
  forces.gap_acceleration = NormalEntries(a, d);
  forces.delassus_diagonal = NormalEntries(W.diagonal(), d);
  forces.lcp_iterations = reactions.status.iterations;
  forces.lcp_error = reactions.status.error;
  if (!friction) return forces;
  forces.lambda_T = TangentialEntries(r, d);
  forces.tangential_acceleration = TangentialEntries(a, d);
  for (Index i = 0; i < k; ++i) {
    forces.tangential_delassus(i) = W.diagonal().segment(d * i + 1, d - 1).mean();
    if (closed[static_cast<std::size_t>(i)].tangential == Tangential::kSlide)
      forces.lambda_T.col(i) = r(d * i) * slide_friction.col(i);
  }
  return forces;
}

ImpactResult EventDrivenContacts::Impact(double t, Eigen::Ref<VectorXd> y, const std::vector<int>& points) const {
  const Index nu = system_.num_velocities(), k = static_cast<Index>(points.size());
  VectorXd mu(k), e(k);
  for (Index i = 0; i < k; ++i) {
    const UnilateralLaw& law =
        system_.unilateral_contact(points_[static_cast<std::size_t>(points[static_cast<std::size_t>(i)])].contact).law();
    mu(i) = law.friction;
    e(i) = law.restitution;
  }
  const Index d = k > 0 && mu.maxCoeff() > 0.0 ? ContactDimension(system_) : 1;
  const MatrixXd rows = LocalRows(Evaluate(t, y, points), nu, d);
  const double solve_start = ProcessCpuSeconds();
  const ConstrainedResponse response = Respond(system_, t, y, rows.transpose());
  const MatrixXd W = rows * response.dv;
  const VectorXd U_before = rows * y.tail(nu);
  Reactions reactions;
  if (options_.impact_law == ImpactLaw::kPoisson) {
    FLEXMBS_CHECK(d == 1, "event-driven: Poisson's impact law takes frictionless contacts only");
    const Reactions compression = SolveOrStop(W, U_before, mu, d, options_.lcp_tolerance, t, "compression");
    const VectorXd P_E = e.cwiseProduct(compression.r);  // the expansion's impulse before Lambda
    const VectorXd U_C = U_before + W * compression.r;
    reactions = SolveOrStop(W, U_C + W * P_E, mu, d, options_.lcp_tolerance, t, "expansion");
    reactions.r += compression.r + P_E;
    reactions.status.error = std::max(reactions.status.error, compression.status.error);
  } else {
    VectorXd q = U_before;
    // Newton's law acts on approaching points; a touching point already separating (U_N- > 0)
    // only must not be pushed into the surface: U_N+ >= 0.
    for (Index i = 0; i < k; ++i) q(d * i) += e(i) * std::min(0.0, q(d * i));
    reactions = SolveOrStop(W, q, mu, d, options_.lcp_tolerance, t, "impact");
  }
  solve_cpu_seconds_ += ProcessCpuSeconds() - solve_start;
  y.tail(nu) += response.dv * reactions.r;
  const VectorXd U_after = rows * y.tail(nu);
  ImpactResult result;
  result.U_N_before = NormalEntries(U_before, d);
  result.U_N_after = NormalEntries(U_after, d);
  result.P_N = NormalEntries(reactions.r, d);
  result.U_T_after = d > 1 ? TangentialEntries(U_after, d) : Eigen::Matrix2Xd::Zero(2, k);
  result.P_T = d > 1 ? TangentialEntries(reactions.r, d) : Eigen::Matrix2Xd::Zero(2, k);
  result.lcp_error = reactions.status.error;
  return result;
}

void EventDrivenContacts::ProjectClosed(double t, Eigen::Ref<VectorXd> y, const std::vector<ClosedPoint>& closed,
                                        const ProjectionOptions& projection) const {
  const Index nu = system_.num_velocities();
  const bool joints = system_.num_constraints() > 0;
  std::vector<int> indices;
  for (const ClosedPoint& point : closed) indices.push_back(point.index);
  if (joints) ProjectPositions(system_, t, y, projection);
  if (!closed.empty()) {
    constexpr int kMaxIterations = 10;
    double residual = 0.0;
    for (int iteration = 0;; ++iteration) {
      const auto kinematics = Evaluate(t, y, indices);
      VectorXd g(static_cast<Index>(closed.size()));
      for (std::size_t i = 0; i < closed.size(); ++i) g(static_cast<Index>(i)) = kinematics[i].g_N;
      residual = g.lpNorm<Eigen::Infinity>();
      if (residual <= options_.gap_projection_tolerance) break;
      if (iteration == kMaxIterations) {
        throw SimulationError(
            t, fmt::format("t = {:.9g} s: event-driven: the {} closed contact gaps do not project "
                           "to 0: max |g_N| {:.3g} m after {} steps",
                           t, closed.size(), residual, kMaxIterations));
      }
      const MatrixXd W = LocalRows(kinematics, nu, 1);
      const ConstrainedResponse response = Respond(system_, t, y, W.transpose());
      const Eigen::CompleteOrthogonalDecomposition<MatrixXd> delassus(W * response.dv);
      system_.DisplacePositions(-response.dv * delassus.solve(g), y);
      system_.NormalizeEulerParameters(y);
      if (joints) ProjectPositions(system_, t, y, projection);
    }
  }
  if (joints) ProjectVelocities(system_, t, y);
  if (closed.empty()) return;
  // The rows held at zero velocity: every closed point's W_N, and W_T of the sticking ones.
  const auto kinematics = Evaluate(t, y, indices);
  std::vector<Eigen::RowVectorXd> held;
  for (std::size_t i = 0; i < closed.size(); ++i) {
    held.push_back(kinematics[i].W_N);
    if (closed[i].tangential != Tangential::kStick) continue;
    held.push_back(kinematics[i].W_T.row(0));
    if (!system_.planar()) held.push_back(kinematics[i].W_T.row(1));  // planar: t2 = z, idle
  }
  MatrixXd W(static_cast<Index>(held.size()), nu);
  for (std::size_t i = 0; i < held.size(); ++i) W.row(static_cast<Index>(i)) = held[i];
  const ConstrainedResponse response = Respond(system_, t, y, W.transpose());
  const Eigen::CompleteOrthogonalDecomposition<MatrixXd> delassus(W * response.dv);
  y.tail(nu) -= response.dv * delassus.solve(VectorXd(W * y.tail(nu)));
}

}  // namespace flexmbs::mbs
