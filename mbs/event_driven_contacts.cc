#include "mbs/event_driven_contacts.h"

#include <fmt/format.h>

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "contact/complementarity/lcp_problem.h"
#include "contact/complementarity/lcp_solver.h"
#include "core/error.h"
#include "mbs/constraint_solver.h"
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

/// W_N of the given kinematics stacked (k x n_u).
MatrixXd NormalRows(const std::vector<UnilateralContactKinematics>& kinematics, Index nu) {
  MatrixXd W(static_cast<Index>(kinematics.size()), nu);
  for (std::size_t i = 0; i < kinematics.size(); ++i)
    W.row(static_cast<Index>(i)) = kinematics[i].W_N;
  return W;
}

/// (M, q) by contact::SolveLcp (Lemke, then proximal Newton on a singular M); a solve that does
/// not converge is a SimulationError at t naming `what`.
contact::LcpSolution SolveLcpOrStop(const MatrixXd& M, const VectorXd& q, double tolerance, double t,
                                    std::string_view what) {
  const contact::LcpSolution solution = contact::SolveLcp({M, q}, {tolerance});
  if (!solution.converged) {
    throw SimulationError(
        t, fmt::format("t = {:.9g} s: event-driven {} LCP of {} contact points did not converge: "
                       "residual {:.3g} > tolerance {:.3g} after {} iterations ({})",
                       t, what, q.size(), solution.error, tolerance, solution.iterations,
                       solution.message));
  }
  return solution;
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
      out.push_back(std::move(point));
    }
  }
  return out;
}

VectorXd EventDrivenContacts::GapAccelerationBias(double t, const ConstVectorRef& y,
                                                  const std::vector<int>& closed) const {
  const Index nu = system_.num_velocities();
  const VectorXd u = y.tail(nu);
  const double eps = std::cbrt(std::numeric_limits<double>::epsilon()) /
                     std::max(1.0, u.lpNorm<Eigen::Infinity>());
  VectorXd y_plus = y, y_minus = y;
  system_.DisplacePositions(eps * u, y_plus);
  system_.DisplacePositions(-eps * u, y_minus);
  const auto plus = Evaluate(t, y_plus, closed), minus = Evaluate(t, y_minus, closed);
  VectorXd bias(static_cast<Index>(closed.size()));
  for (std::size_t i = 0; i < closed.size(); ++i) {
    bias(static_cast<Index>(i)) = (plus[i].W_N - minus[i].W_N).dot(u) / (2.0 * eps);
  }
  return bias;
}

ClosedContactForces EventDrivenContacts::Derivative(double t, const ConstVectorRef& y,
                                                    const std::vector<int>& closed,
                                                    Eigen::Ref<VectorXd> y_dot) const {
  const Index nu = system_.num_velocities();
  for (int b = 0; b < system_.num_bodies(); ++b) {
    PositionDerivative(system_.BodyPositions(y, b), system_.BodyVelocities(y, b),
                       y_dot.segment(system_.position_offset(b), system_.body(b).num_positions()));
  }
  ClosedContactForces forces;
  forces.joint_lambda.resize(system_.num_constraints());
  auto u_dot = y_dot.tail(nu);
  system_.Accelerations(t, y, u_dot, forces.joint_lambda);
  if (closed.empty()) return forces;
  const MatrixXd W = NormalRows(Evaluate(t, y, closed), nu);
  const ConstrainedResponse response = Respond(system_, t, y, W.transpose());
  const MatrixXd delassus = W * response.dv;
  const VectorXd w = W * u_dot + GapAccelerationBias(t, y, closed);
  const contact::LcpSolution lcp =
      SolveLcpOrStop(delassus, w, options_.lcp_tolerance, t, "acceleration-level");
  u_dot += response.dv * lcp.z;
  forces.joint_lambda += response.dlambda * lcp.z;
  forces.lambda_N = lcp.z;
  forces.gap_acceleration = lcp.w;
  forces.delassus_diagonal = delassus.diagonal();
  forces.lcp_iterations = lcp.iterations;
  forces.lcp_error = lcp.error;
  return forces;
}

ImpactResult EventDrivenContacts::Impact(double t, Eigen::Ref<VectorXd> y,
                                         const std::vector<int>& points) const {
  const Index nu = system_.num_velocities();
  const MatrixXd W = NormalRows(Evaluate(t, y, points), nu);
  const ConstrainedResponse response = Respond(system_, t, y, W.transpose());
  ImpactResult result;
  result.U_N_before = W * y.tail(nu);
  VectorXd q = result.U_N_before;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double e =
        system_.unilateral_contact(points_[static_cast<std::size_t>(points[i])].contact)
            .law()
            .restitution;
    // Newton's law acts on approaching points; a touching point already separating (U_N- > 0)
    // only must not be pushed into the surface: U_N+ >= 0.
    q(static_cast<Index>(i)) += e * std::min(0.0, q(static_cast<Index>(i)));
  }
  const contact::LcpSolution lcp =
      SolveLcpOrStop(W * response.dv, q, options_.lcp_tolerance, t, "impact");
  result.P_N = lcp.z;
  result.lcp_error = lcp.error;
  y.tail(nu) += response.dv * lcp.z;
  result.U_N_after = W * y.tail(nu);
  return result;
}

void EventDrivenContacts::ProjectClosed(double t, Eigen::Ref<VectorXd> y,
                                        const std::vector<int>& closed,
                                        const ProjectionOptions& projection) const {
  const Index nu = system_.num_velocities();
  const bool joints = system_.num_constraints() > 0;
  if (joints) ProjectPositions(system_, t, y, projection);
  if (!closed.empty()) {
    constexpr int kMaxIterations = 10;
    double residual = 0.0;
    for (int iteration = 0;; ++iteration) {
      const auto kinematics = Evaluate(t, y, closed);
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
      const MatrixXd W = NormalRows(kinematics, nu);
      const ConstrainedResponse response = Respond(system_, t, y, W.transpose());
      const Eigen::CompleteOrthogonalDecomposition<MatrixXd> delassus(W * response.dv);
      system_.DisplacePositions(-response.dv * delassus.solve(g), y);
      system_.NormalizeEulerParameters(y);
      if (joints) ProjectPositions(system_, t, y, projection);
    }
  }
  if (joints) ProjectVelocities(system_, t, y);
  if (closed.empty()) return;
  const MatrixXd W = NormalRows(Evaluate(t, y, closed), nu);
  const ConstrainedResponse response = Respond(system_, t, y, W.transpose());
  const Eigen::CompleteOrthogonalDecomposition<MatrixXd> delassus(W * response.dv);
  y.tail(nu) -= response.dv * delassus.solve(VectorXd(W * y.tail(nu)));
}

}  // namespace flexmbs::mbs
