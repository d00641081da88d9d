#include "mbs/moreau_jean.h"

#include <fmt/format.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "mbs/contact_reactions.h"
#include "mbs/cpu_time.h"
#include "mbs/kkt_factor.h"
#include "mbs/planar.h"
#include "mbs/simulation_error.h"

namespace flexmbs::mbs {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

/// A pressed point with friction slides where its tangential velocity at the end of the step
/// exceeds this [m/s] (sticking points keep round-off: 1.4e-13 m/s on the incline of
/// tests/mbs/moreau_jean_friction_test.cc).
constexpr double kSlipSpeed = 1e-9;

/// The smooth part of a step: the factorised KKT matrix [A G^T; G 0] over the kept joint rows and
/// the free velocity increment with its joint impulses. In a planar scene the matrix is over the
/// kept velocity columns s (A(s, s), G(:, s)): the solves gather and scatter them.
struct SmoothStep {
  KktFactor kkt;
  std::vector<Index> kept;
  std::vector<Index> velocities;  ///< the kept velocity columns s (planar scenes); empty: all
  VectorXd dv_free;       ///< v_free - v_k
  VectorXd impulse_free;  ///< Lambda of the free step (kept rows) [N s]
};

/// Solves the KKT system for right-hand sides [rhs_v; rhs_c] (nu + m rows): the velocity parts
/// (zero in the dropped columns of a planar scene) and Lambda (the second block of the solution
/// with its sign turned: A dv = rhs_v + G^T Lambda).
void SolveKkt(const SmoothStep& step, Index nu, const MatrixXd& rhs, MatrixXd* dv, MatrixXd* impulse) {
  if (step.velocities.empty()) {
    const MatrixXd solution = step.kkt.Solve(rhs);
    *dv = solution.topRows(nu);
    *impulse = -solution.bottomRows(solution.rows() - nu);
    return;
  }
  const Index ns = static_cast<Index>(step.velocities.size()), m = rhs.rows() - nu;
  MatrixXd gathered(ns + m, rhs.cols());
  gathered.topRows(ns) = rhs(step.velocities, Eigen::all);
  gathered.bottomRows(m) = rhs.bottomRows(m);
  const MatrixXd solution = step.kkt.Solve(gathered);
  *dv = MatrixXd::Zero(nu, rhs.cols());
  dv->operator()(step.velocities, Eigen::all) = solution.topRows(ns);
  *impulse = -solution.bottomRows(m);
}

SmoothStep SolveSmoothStep(const MultibodySystem& system, double t, double h, double theta, const ConstVectorRef& y,
                           const VectorXd& u_dot_previous) {
  const Index nu = system.num_velocities();
  const auto v_k = y.tail(nu);
  MatrixXd A = MatrixXd::Zero(nu, nu), H_x = MatrixXd::Zero(nu, nu), H_u = MatrixXd::Zero(nu, nu);
  for (int b = 0; b < system.num_bodies(); ++b) {
    const auto [offset, n] = system.velocity_block(b);
    A.block(offset, offset, n, n) = system.BodyMassMatrix(b, y);
    system.body(b).AddForceJacobian(system.BodyPositions(y, b), system.BodyVelocities(y, b),
                                    u_dot_previous.segment(offset, n), system.gravity(), H_x.block(offset, offset, n, n),
                                    H_u.block(offset, offset, n, n));
  }
  for (int k = 0; k < system.num_force_elements(); ++k) system.force_element(k).AddForceJacobian(t, system, y, H_x, H_u);
  A -= h * theta * H_u + h * h * theta * theta * H_x;
  const VectorXd rhs_v = h * (system.Forces(t + theta * h, y) + h * theta * H_x * v_k);

  SmoothStep step;
  step.kept = system.KeptConstraints();
  if (system.planar()) step.velocities = system.KeptVelocities();
  const Index m = static_cast<Index>(step.kept.size());
  const SystemConstraints c = system.Constraints(t + h, y);
  VectorXd rhs(nu + m);
  rhs.head(nu) = rhs_v;
  for (Index r = 0; r < m; ++r) {
    const Index row = step.kept[static_cast<std::size_t>(r)];
    rhs(nu + r) = -c.g_t(row) - c.G.row(row).dot(v_k);
  }
  MatrixXd kkt;
  if (step.velocities.empty()) {
    kkt = MatrixXd::Zero(nu + m, nu + m);
    kkt.topLeftCorner(nu, nu) = A;
    kkt.bottomLeftCorner(m, nu) = c.G(step.kept, Eigen::all);
  } else {
    const Index ns = static_cast<Index>(step.velocities.size());
    kkt = MatrixXd::Zero(ns + m, ns + m);
    kkt.topLeftCorner(ns, ns) = A(step.velocities, step.velocities);
    kkt.bottomLeftCorner(m, ns) = c.G(step.kept, step.velocities);
  }
  const Index n = kkt.rows() - m;
  kkt.topRightCorner(n, m) = kkt.bottomLeftCorner(m, n).transpose();
  if (!step.kkt.Compute(kkt)) {
    const Eigen::Index rank = step.kkt.rank();
    throw SimulationError(t, fmt::format("t = {:.9g} s: Moreau-Jean step: the KKT matrix of the masses and the {} kept "
                                         "joint rows is singular ({} of {})",
                                         t, m, rank >= 0 ? fmt::format("rank {}", rank) : "sparse LU", n + m));
  }
  MatrixXd dv, impulse;
  SolveKkt(step, nu, rhs, &dv, &impulse);
  VectorXd h_a(nu);
  if (system.AccelerationDependentForces(y, dv / h, h_a)) {
    rhs.head(nu) += h * h_a;
    SolveKkt(step, nu, rhs, &dv, &impulse);
  }
  step.dv_free = dv;
  step.impulse_free = impulse;
  return step;
}

/// Every contact point of the system at one state: its kinematics and the contact it belongs to.
struct ContactPoints {
  std::vector<UnilateralContactKinematics> kinematics;
  std::vector<int> contact;  ///< per point: the index of its contact in the system
};

ContactPoints EvaluateContactPoints(const MultibodySystem& system, double t, const ConstVectorRef& y) {
  ContactPoints points;
  for (int k = 0; k < system.num_unilateral_contacts(); ++k) {
    for (UnilateralContactKinematics& point : system.unilateral_contact(k).Evaluate(t, system, y)) {
      points.kinematics.push_back(std::move(point));
      points.contact.push_back(k);
    }
  }
  return points;
}

/// The active points' local problem: H (d per point: W_N and the tangents' rows; d = 3, or 2 in
/// a planar scene) and the normal law's offsets.
struct ActiveContacts {
  Index d = 3;             ///< ContactDimension
  std::vector<int> index;  ///< point indices into ContactPoints
  std::vector<Eigen::Matrix3Xd> t_W;  ///< per active point its d - 1 tangents in W
  MatrixXd H;              ///< d n_a x num_velocities()
  VectorXd normal_offset;  ///< per active point: e U_N,k (velocity level) or g_N(x_k) / h (position level)
  VectorXd mu;
};

/// The index set: points whose gap predicted ahead is closed, g_N(x_k) + h/2 U_N,k <= 0 on
/// velocity level (Siconos' MoreauJeanOSI::addInteractionInIndexSet, gamma = 1/2) and
/// g_N(x_k) + h W_N v_free <= 0 on position level (the end of a step without contact impulses: a
/// point that landed on its surface stays in while a load presses it), with their rows of H, their
/// normal offsets and mu of their contact's law.
ActiveContacts FindActiveContacts(const MultibodySystem& system, const ContactPoints& points, double h,
                                  const VectorXd& v_k, const VectorXd& v_free, ImpactLevel level) {
  const bool position_level = level == ImpactLevel::kPosition;
  ActiveContacts active;
  active.d = ContactDimension(system);
  const Index d = active.d;
  for (std::size_t k = 0; k < points.kinematics.size(); ++k) {
    const UnilateralContactKinematics& c = points.kinematics[k];
    const double predicted = position_level ? c.g_N + h * c.W_N.dot(v_free) : c.g_N + 0.5 * h * c.W_N.dot(v_k);
    if (predicted <= 0.0) active.index.push_back(static_cast<int>(k));
  }
  const Index n_a = static_cast<Index>(active.index.size());
  active.H.resize(d * n_a, v_k.size());
  active.normal_offset.resize(n_a);
  active.mu.resize(n_a);
  for (Index i = 0; i < n_a; ++i) {
    const std::size_t k = static_cast<std::size_t>(active.index[static_cast<std::size_t>(i)]);
    const UnilateralContactKinematics& c = points.kinematics[k];
    const UnilateralLaw& law = system.unilateral_contact(points.contact[k]).law();
    const ContactTangents tangents = Tangents(c, d);
    active.H.row(d * i) = c.W_N;
    active.H.middleRows(d * i + 1, d - 1) = tangents.W_T;
    active.t_W.push_back(tangents.t_W);
    active.normal_offset(i) = position_level ? c.g_N / h : law.restitution * c.W_N.dot(v_k);
    active.mu(i) = law.friction;
  }
  return active;
}

/// The per-contact results of a step of length h from its points: the end-of-step gaps (at
/// y_next) with the normal velocity U_N = W_N(x_k) v_next at the smallest, and the active points'
/// impulses P (summed, and per point as the load P / h).
std::vector<ContactStepResult> SummarizeContacts(const MultibodySystem& system, double t_next, double h,
                                                 const ConstVectorRef& y_next, const ContactPoints& points,
                                                 const VectorXd& v_next, const ActiveContacts& active,
                                                 const VectorXd& P) {
  std::vector<ContactStepResult> results(static_cast<std::size_t>(system.num_unilateral_contacts()));
  std::size_t point = 0;
  for (int k = 0; k < system.num_unilateral_contacts(); ++k) {
    ContactStepResult& result = results[static_cast<std::size_t>(k)];
    result.g_N = std::numeric_limits<double>::infinity();
    for (const UnilateralContactKinematics& end : system.unilateral_contact(k).Evaluate(t_next, system, y_next)) {
      if (end.g_N < result.g_N) {
        result.g_N = end.g_N;
        result.U_N = points.kinematics[point].W_N.dot(v_next);
      }
      ++point;
    }
  }
  for (std::size_t i = 0; i < active.index.size(); ++i) {
    const std::size_t k = static_cast<std::size_t>(points.contact[static_cast<std::size_t>(active.index[i])]);
    const Index d = active.d, at = d * static_cast<Index>(i);
    const UnilateralContactKinematics& c = points.kinematics[static_cast<std::size_t>(active.index[i])];
    const Eigen::Vector3d P_T_W = active.t_W[i] * P.segment(at + 1, d - 1);
    results[k].active = true;
    ++results[k].active_points;
    results[k].P_N += P(at);
    results[k].P_T += Eigen::Vector2d(c.t1_W.dot(P_T_W), c.t2_W.dot(P_T_W));
    const double slip = (active.H.middleRows(at + 1, d - 1) * v_next).norm();
    const bool slides = active.mu(static_cast<Index>(i)) > 0.0 && P(at) > 0.0 && slip > kSlipSpeed;
    results[k].sliding = results[k].sliding || slides;
    if (P.segment(at, d).isZero(0.0)) continue;
    results[k].loads.push_back({0, c.p_WA_W, c.n_W, (P(at) * c.n_W + P_T_W) / h});
  }
  return results;
}

/// Turns a solver that did not converge into the SimulationError of step `step` at t.
[[noreturn]] void NotConverged(long step, double t, double h, int active, const contact::SolveStatus& status,
                               double tolerance) {
  throw SimulationError(t, fmt::format("t = {:.9g} s: Moreau-Jean step {} ({:.9g} -> {:.9g} s): the contact solve of "
                                       "{} active contacts did not converge: residual {:.3g} > tolerance {:.3g} after "
                                       "{} iterations ({})",
                                       t, step, t, t + h, active, status.error, tolerance, status.iterations,
                                       status.message));
}

}  // namespace

void CheckMoreauJeanOptions(const MoreauJeanOptions& options) {
  if (!(options.step > 0.0) || !std::isfinite(options.step)) {
    throw InputError(fmt::format("simulation: Moreau-Jean step {:g} s must be finite and > 0", options.step));
  }
  if (!(options.theta >= 0.5 && options.theta <= 1.0)) {
    throw InputError(fmt::format("simulation: theta {:g} must be in [0.5, 1]", options.theta));
  }
  if (options.impact_level == ImpactLevel::kPosition && options.theta != 1.0) {
    throw InputError(fmt::format("simulation: impact_level position needs theta 1 (the gap the positions reach, "
                                 "x_k+1 = x_k + h v_k+1), not {:g}",
                                 options.theta));
  }
  if (!(options.solver_tolerance > 0.0) || options.solver_max_iterations < 1) {
    throw InputError(fmt::format("simulation: contact solver tolerance {:g} must be > 0 and its iterations {} >= 1",
                                 options.solver_tolerance, options.solver_max_iterations));
  }
}

MoreauJeanStepper::MoreauJeanStepper(const MultibodySystem& system, const MoreauJeanOptions& options)
    : system_(system), options_(options), u_dot_(VectorXd::Zero(system.num_velocities())) {
  CheckMoreauJeanOptions(options_);
  if (options_.impact_level == ImpactLevel::kVelocity) return;
  for (int k = 0; k < system_.num_unilateral_contacts(); ++k) {
    const UnilateralContact& contact = system_.unilateral_contact(k);
    if (contact.law().restitution > 0.0) {
      throw InputError(fmt::format("contact '{}': restitution {:g} needs impact level velocity (on position level "
                                   "the points' impacts are inelastic, e = 0)",
                                   contact.name(), contact.law().restitution));
    }
  }
}

MoreauJeanStepReport MoreauJeanStepper::Initial(double t, const ConstVectorRef& y) const {
  MoreauJeanStepReport report;
  report.time = t;
  report.lambda = VectorXd::Zero(system_.num_constraints());
  const ContactPoints points = EvaluateContactPoints(system_, t, y);
  report.contacts =
      SummarizeContacts(system_, t, 1.0, y, points, y.tail(system_.num_velocities()), ActiveContacts{}, VectorXd());
  return report;
}

const MoreauJeanStepReport& MoreauJeanStepper::Step(double t, double h, Eigen::Ref<VectorXd> y) {
  FLEXMBS_CHECK(h > 0.0 && h <= options_.step * (1.0 + 1e-9), "MoreauJeanStepper::Step: h outside (0, step]");
  const Index nu = system_.num_velocities();
  const double theta = options_.theta;
  const long step_number = statistics_.steps + 1;
  const VectorXd v_k = y.tail(nu);
  const SmoothStep smooth = SolveSmoothStep(system_, t, h, theta, y, u_dot_);
  u_dot_ = smooth.dv_free / h;

  VectorXd v_next = v_k + smooth.dv_free;
  const ContactPoints points = EvaluateContactPoints(system_, t, y);
  const ActiveContacts active = FindActiveContacts(system_, points, h, v_k, v_next, options_.impact_level);
  const Index n_a = static_cast<Index>(active.index.size());

  VectorXd impulse = smooth.impulse_free;
  const Index d = active.d;
  VectorXd P = VectorXd::Zero(d * n_a);
  report_.solver_iterations = 0;
  report_.solver_error = 0.0;
  if (n_a > 0) {
    const ScopedCpuTime solve_time(statistics_.contact_solve_cpu_seconds);
    MatrixXd rhs = MatrixXd::Zero(nu + static_cast<Index>(smooth.kept.size()), d * n_a);
    rhs.topRows(nu) = active.H.transpose();
    MatrixXd dv_per_P, impulse_per_P;
    SolveKkt(smooth, nu, rhs, &dv_per_P, &impulse_per_P);
    const MatrixXd W = active.H * dv_per_P;
    VectorXd q = active.H * v_next;
    for (Index i = 0; i < n_a; ++i) q(d * i) += active.normal_offset(i);
    const contact::SolveStatus status =
        SolveContactReactions(W, q, active.mu, options_.solver_tolerance, options_.solver_max_iterations, &P, d);
    if (!status.converged) NotConverged(step_number, t, h, static_cast<int>(n_a), status, options_.solver_tolerance);
    report_.solver_iterations = status.iterations;
    report_.solver_error = status.error;
    v_next += dv_per_P * P;
    impulse += impulse_per_P * P;
    ++statistics_.contact_solves;
    statistics_.solver_iterations += report_.solver_iterations;
    statistics_.max_solver_error = std::max(statistics_.max_solver_error, report_.solver_error);
  }

  system_.DisplacePositions(h * (theta * v_next + (1.0 - theta) * v_k), y);
  y.tail(nu) = v_next;
  system_.NormalizeEulerParameters(y);

  report_.time = t + h;
  report_.active_contacts = static_cast<int>(n_a);
  report_.lambda = VectorXd::Zero(system_.num_constraints());
  for (std::size_t r = 0; r < smooth.kept.size(); ++r) report_.lambda(smooth.kept[r]) = impulse(static_cast<Index>(r)) / h;
  report_.contacts = SummarizeContacts(system_, t + h, h, y, points, v_next, active, P);
  ++statistics_.steps;
  statistics_.max_active_contacts = std::max(statistics_.max_active_contacts, static_cast<int>(n_a));
  return report_;
}

}  // namespace flexmbs::mbs
