#include "mbs/event_driven_simulation.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "core/error.h"
#include "mbs/constraint_projection.h"
#include "mbs/constraint_redundancy.h"
#include "mbs/event_driven_contacts.h"
#include "mbs/ode_integrator.h"
#include "mbs/simulation_error.h"

namespace flexmbs::mbs {
namespace {

using Eigen::Index;
using Eigen::VectorXd;

/// One event-driven run: the closed points, the ODE problem on [y; I] and the event handling.
class EventDrivenRun {
 public:
  EventDrivenRun(MultibodySystem& system, const SimulationOptions& options,
                 const EventOutputCallback& event_output, DroppedRowWatch& watch,
                 SimulationStatistics& statistics)
      : system_(system),
        options_(options),
        ed_(*options.event_driven),
        contacts_(system, ed_),
        event_output_(event_output),
        watch_(watch),
        statistics_(statistics),
        state_(static_cast<std::size_t>(contacts_.num_points())),
        interval_impulse_(VectorXd::Zero(system.num_unilateral_contacts())),
        interval_tangential_(Eigen::Matrix2Xd::Zero(2, system.num_unilateral_contacts())),
        interval_impact_(static_cast<std::size_t>(system.num_unilateral_contacts()), false) {}

  Index y_size() const { return system_.state_size(); }
  /// The integrated impulses' entries: 3 per point (normal, t1, t2).
  Index impulse_size() const { return 3 * contacts_.num_points(); }
  /// [y; I] for the integrator (I = 0 at the start).
  VectorXd InitialState(double t, const VectorXd& y0) {
    VectorXd z = VectorXd::Zero(y_size() + impulse_size());
    z.head(y_size()) = y0;
    StartContacts(t, z);
    last_impulse_ = z.tail(impulse_size());
    return z;
  }
  OdeProblem Problem();
  /// Handles the roots the integrator stopped at: impacts, separations, sticks, slips, or no event
  /// (counted).
  void HandleRoots(double t, VectorXd& z, const std::vector<int>& directions);
  /// The contact report and the joint multipliers of the output interval that ends at (t, z).
  MoreauJeanStepReport Report(double t, const VectorXd& z, VectorXd* joint_lambda);
  /// CPU time of the contact solves so far [s] (EventDrivenContacts::solve_cpu_seconds).
  double solve_cpu_seconds() const { return contacts_.solve_cpu_seconds(); }

 private:
  /// A contact point's state between events.
  struct PointState {
    bool closed = false;
    Tangential tangential = Tangential::kFree;  ///< while closed
    Eigen::Vector2d slide_direction = Eigen::Vector2d::UnitX();
  };
  std::vector<ClosedPoint> Closed() const {
    std::vector<ClosedPoint> closed;
    for (int i = 0; i < contacts_.num_points(); ++i) {
      const PointState& point = state_[static_cast<std::size_t>(i)];
      if (point.closed) closed.push_back({i, point.tangential, point.slide_direction});
    }
    return closed;
  }
  /// Closes point i with its tangential state from its tangential velocity U_T [m/s]: frictionless,
  /// sticking (|U_T| <= stick_velocity) or sliding along U_T.
  void Close(int i, const Eigen::Vector2d& U_T);
  void StartContacts(double t, VectorXd& z);
  void ImpactAt(double t, VectorXd& z, const std::vector<UnilateralContactKinematics>& kinematics,
                std::vector<ContactEvent>* events);
  /// The tangential roots: a sliding point whose velocity turned through 0 sticks (or turns), a
  /// sticking point whose friction margin fell through 0 begins to slide. Whether any was an event.
  bool TangentialRoots(double t, const VectorXd& z, const std::vector<int>& directions,
                       std::vector<ContactEvent>* events);
  /// Repeats the acceleration-level problem until the closed points agree with it: a point with
  /// lambda_N = 0 and g_N'' > 0 opens, a sticking point the problem lets slip begins to slide.
  void Settle(double t, VectorXd& z, std::vector<ContactEvent>* events);
  /// The event record of a point's change of state without an impulse at t.
  ContactEvent StateChange(double t, int i, ContactEventKind kind, const VectorXd& z) const;
  void Emit(std::vector<ContactEvent>& events, double t, const VectorXd& z);

  MultibodySystem& system_;
  const SimulationOptions& options_;
  EventDrivenOptions ed_;
  EventDrivenContacts contacts_;
  const EventOutputCallback& event_output_;
  DroppedRowWatch& watch_;
  SimulationStatistics& statistics_;
  std::vector<PointState> state_;
  VectorXd interval_impulse_;          ///< impact impulses per contact since the last output [N s]
  Eigen::Matrix2Xd interval_tangential_;  ///< impacts' tangential impulses per contact [N s]
  std::vector<bool> interval_impact_;  ///< per contact: an impact since the last output
  VectorXd last_impulse_;              ///< I at the last output
};

OdeProblem EventDrivenRun::Problem() {
  OdeProblem problem;
  const int n = contacts_.num_points();
  problem.size = y_size() + impulse_size();
  problem.rhs = [this](double t, Eigen::Ref<const VectorXd> z, Eigen::Ref<VectorXd> z_dot) {
    const std::vector<ClosedPoint> closed = Closed();
    const ClosedContactForces forces = contacts_.Derivative(t, z.head(y_size()), closed, z_dot.head(y_size()));
    auto impulse_rate = z_dot.tail(impulse_size());
    impulse_rate.setZero();
    for (std::size_t i = 0; i < closed.size(); ++i) {
      const Index c = static_cast<Index>(i), at = 3 * closed[i].index;
      impulse_rate(at) = forces.lambda_N(c);
      impulse_rate.segment<2>(at + 1) = forces.lambda_T.col(c);
    }
  };
  // Per point a normal root (an open gap, a closed point's force) and a tangential one (a sliding
  // point's velocity along its direction, a sticking point's friction margin; 1 otherwise).
  problem.num_events = 2 * n;
  problem.events = [this, n](double t, Eigen::Ref<const VectorXd> z, Eigen::Ref<VectorXd> g) {
    const auto y = z.head(y_size());
    const auto u = y.tail(system_.num_velocities());
    const auto kinematics = contacts_.EvaluateAll(t, y);
    g.tail(n).setOnes();
    for (int i = 0; i < n; ++i) {
      const PointState& point = state_[static_cast<std::size_t>(i)];
      g(i) = kinematics[static_cast<std::size_t>(i)].g_N;
      if (point.closed && point.tangential == Tangential::kSlide)
        g(n + i) = (kinematics[static_cast<std::size_t>(i)].W_T * u).dot(point.slide_direction);
    }
    const std::vector<ClosedPoint> closed = Closed();
    if (closed.empty()) return;
    VectorXd y_dot(y_size());
    const ClosedContactForces forces = contacts_.Derivative(t, y, closed, y_dot);
    for (std::size_t i = 0; i < closed.size(); ++i) {
      const Index c = static_cast<Index>(i);
      const int at = closed[i].index;
      g(at) = forces.delassus_diagonal(c) * forces.lambda_N(c) - forces.gap_acceleration(c);
      if (closed[i].tangential != Tangential::kStick) continue;
      // [N]: mu lambda_N - |lambda_T| while sticking, -|U_T'| / (W_TT)_ii once the problem lets
      // the point slip; continuous through the switch, where both are 0.
      const double mu = system_.unilateral_contact(contacts_.points()[static_cast<std::size_t>(at)].contact).law().friction;
      g(n + at) = mu * forces.lambda_N(c) - forces.lambda_T.col(c).norm() -
                  forces.tangential_acceleration.col(c).norm() / forces.tangential_delassus(c);
    }
  };
  problem.project = [this](double t, Eigen::Ref<VectorXd> z) {
    auto y = z.head(y_size());
    contacts_.ProjectClosed(t, y, Closed(), options_.projection);
    watch_.Check(system_, t, y);
    ++statistics_.projections;
  };
  return problem;
}

void EventDrivenRun::Close(int i, const Eigen::Vector2d& U_T) {
  PointState& point = state_[static_cast<std::size_t>(i)];
  point.closed = true;
  if (!contacts_.HasFriction(contacts_.points()[static_cast<std::size_t>(i)].contact)) {
    point.tangential = Tangential::kFree;
  } else if (U_T.norm() <= ed_.stick_velocity) {
    point.tangential = Tangential::kStick;
  } else {
    point.tangential = Tangential::kSlide;
    point.slide_direction = U_T.normalized();
  }
}

void EventDrivenRun::StartContacts(double t, VectorXd& z) {
  auto y = z.head(y_size());
  const auto u = y.tail(system_.num_velocities());
  const auto kinematics = contacts_.EvaluateAll(t, y);
  bool approaching = false;
  for (int i = 0; i < contacts_.num_points(); ++i) {
    const UnilateralContactKinematics& k = kinematics[static_cast<std::size_t>(i)];
    const ContactPointRef& ref = contacts_.points()[static_cast<std::size_t>(i)];
    if (k.g_N < -ed_.gap_tolerance) {
      throw InputError(fmt::format(
          "contact '{}' point {}: the initial gap {:.6g} m is a penetration deeper than "
          "gap_tolerance {:g} m",
          system_.unilateral_contact(ref.contact).name(), ref.point, k.g_N, ed_.gap_tolerance));
    }
    if (k.g_N > ed_.gap_tolerance) continue;
    const double U_N = k.W_N.dot(u);
    if (U_N < 0.0) approaching = true;
    if (U_N <= ed_.rest_velocity) Close(i, k.W_T * u);
  }
  std::vector<ContactEvent> events;
  if (approaching) ImpactAt(t, z, kinematics, &events);
  Settle(t, z, &events);
  contacts_.ProjectClosed(t, y, Closed(), options_.projection);
  Emit(events, t, z);
}

void EventDrivenRun::ImpactAt(double t, VectorXd& z, const std::vector<UnilateralContactKinematics>& kinematics,
                              std::vector<ContactEvent>* events) {
  auto y = z.head(y_size());
  std::vector<int> touching;
  for (int i = 0; i < contacts_.num_points(); ++i) {
    if (state_[static_cast<std::size_t>(i)].closed || kinematics[static_cast<std::size_t>(i)].g_N <= ed_.gap_tolerance) {
      touching.push_back(i);
    }
  }
  const double energy_before = system_.KineticEnergy(y);
  const ImpactResult impact = contacts_.Impact(t, y, touching);
  ++statistics_.event_driven.impacts;
  statistics_.event_driven.max_impact_points =
      std::max(statistics_.event_driven.max_impact_points, static_cast<int>(touching.size()));
  statistics_.event_driven.max_lcp_error = std::max(statistics_.event_driven.max_lcp_error, impact.lcp_error);
  for (std::size_t j = 0; j < touching.size(); ++j) {
    const Index c = static_cast<Index>(j);
    const int i = touching[j];
    const ContactPointRef& ref = contacts_.points()[static_cast<std::size_t>(i)];
    PointState& point = state_[static_cast<std::size_t>(i)];
    const bool close = impact.U_N_after(c) <= ed_.rest_velocity;
    if (close && !point.closed) ++statistics_.event_driven.closings;
    if (close) {
      Close(i, impact.U_T_after.col(c));
    } else {
      point.closed = false;
    }
    interval_impulse_(ref.contact) += impact.P_N(c);
    interval_tangential_.col(ref.contact) += impact.P_T.col(c);
    interval_impact_[static_cast<std::size_t>(ref.contact)] = true;
    events->push_back({t, ContactEventKind::kImpact, ref.contact, ref.point, impact.U_N_before(c),
                       close ? 0.0 : impact.U_N_after(c), impact.P_N(c), energy_before, 0.0, close});
  }
}

ContactEvent EventDrivenRun::StateChange(double t, int i, ContactEventKind kind, const VectorXd& z) const {
  const ContactPointRef& ref = contacts_.points()[static_cast<std::size_t>(i)];
  const double energy = system_.KineticEnergy(z.head(y_size()));
  return {t, kind, ref.contact, ref.point, 0.0, 0.0, 0.0, energy, energy, state_[static_cast<std::size_t>(i)].closed};
}

bool EventDrivenRun::TangentialRoots(double t, const VectorXd& z, const std::vector<int>& directions,
                                     std::vector<ContactEvent>* events) {
  const int n = contacts_.num_points();
  const auto y = z.head(y_size());
  const auto u = y.tail(system_.num_velocities());
  const std::vector<ClosedPoint> closed = Closed();
  std::optional<ClosedContactForces> forces;  // the problem at t, for the sticking points' slips
  bool changed = false;
  for (std::size_t j = 0; j < closed.size(); ++j) {
    const int i = closed[j].index;
    PointState& point = state_[static_cast<std::size_t>(i)];
    if (directions[static_cast<std::size_t>(n + i)] >= 0 || point.tangential == Tangential::kFree) continue;
    if (point.tangential == Tangential::kSlide) {
      const Eigen::Vector2d U_T = contacts_.Evaluate(t, y, {i})[0].W_T * u;
      if (U_T.norm() > ed_.stick_velocity) {
        point.slide_direction = U_T.normalized();  // turned, not stopped: no event
        continue;
      }
      point.tangential = Tangential::kStick;
      ++statistics_.event_driven.sticks;
      events->push_back(StateChange(t, i, ContactEventKind::kStick, z));
    } else {
      if (!forces) {
        VectorXd y_dot(y_size());
        forces = contacts_.Derivative(t, y, closed, y_dot);
      }
      // The direction the point begins to slide in: its acceleration's, or (at the switch itself,
      // where U_T' is still 0) against its friction force.
      const Index c = static_cast<Index>(j);
      const Eigen::Vector2d a_T = forces->tangential_acceleration.col(c), lambda_T = forces->lambda_T.col(c);
      point.tangential = Tangential::kSlide;
      point.slide_direction = a_T.norm() > 0.0 ? a_T.normalized() : Eigen::Vector2d(-lambda_T.normalized());
      ++statistics_.event_driven.slips;
      events->push_back(StateChange(t, i, ContactEventKind::kSlip, z));
    }
    changed = true;
  }
  return changed;
}

void EventDrivenRun::Settle(double t, VectorXd& z, std::vector<ContactEvent>* events) {
  auto y = z.head(y_size());
  for (int round = 0; round <= 2 * contacts_.num_points(); ++round) {
    const std::vector<ClosedPoint> closed = Closed();
    if (closed.empty()) return;
    VectorXd y_dot(y_size());
    const ClosedContactForces forces = contacts_.Derivative(t, y, closed, y_dot);
    // A point opens when the problem leaves it no force and a gap acceleration > 0; a sticking
    // point slips when it leaves it a tangential acceleration above the solve's round-off [m/s^2]
    // (the roots open and slip points at their switches; this settles the state after an event).
    const double acceleration_floor = 1e-8 * std::max(1.0, forces.gap_acceleration.lpNorm<Eigen::Infinity>() +
                                                                forces.tangential_acceleration.lpNorm<Eigen::Infinity>());
    bool changed = false;
    for (std::size_t j = 0; j < closed.size(); ++j) {
      const Index c = static_cast<Index>(j);
      PointState& point = state_[static_cast<std::size_t>(closed[j].index)];
      if (forces.lambda_N(c) <= 0.0 && forces.gap_acceleration(c) > 0.0) {
        point.closed = false;
        ++statistics_.event_driven.separations;
        events->push_back(StateChange(t, closed[j].index, ContactEventKind::kSeparation, z));
        changed = true;
        continue;
      }
      const Eigen::Vector2d a_T = forces.tangential_acceleration.col(c);
      if (point.tangential != Tangential::kStick || a_T.norm() <= acceleration_floor) continue;
      point.tangential = Tangential::kSlide;
      point.slide_direction = a_T.normalized();
      ++statistics_.event_driven.slips;
      events->push_back(StateChange(t, closed[j].index, ContactEventKind::kSlip, z));
      changed = true;
    }
    if (!changed) return;
  }
}

void EventDrivenRun::Emit(std::vector<ContactEvent>& events, double t, const VectorXd& z) {
  if (events.empty()) return;
  const double energy_after = system_.KineticEnergy(z.head(y_size()));
  for (ContactEvent& event : events) {
    if (event.kind == ContactEventKind::kImpact) event.kinetic_energy_after = energy_after;
    if (event_output_) event_output_(event);
  }
  ++statistics_.event_driven.events;
  if (statistics_.event_driven.events > ed_.max_events) {
    throw SimulationError(
        t,
        fmt::format("t = {:.9g} s: event-driven: more than {} events (an accumulation of impacts "
                    "that rest_velocity {:g} m/s does not end: raise it)",
                    t, ed_.max_events, ed_.rest_velocity));
  }
}

void EventDrivenRun::HandleRoots(double t, VectorXd& z, const std::vector<int>& directions) {
  auto y = z.head(y_size());
  const auto kinematics = contacts_.EvaluateAll(t, y);
  const auto u = y.tail(system_.num_velocities());
  bool impact = false, separation = false;
  std::vector<ContactEvent> events;
  for (int i = 0; i < contacts_.num_points(); ++i) {
    const std::size_t s = static_cast<std::size_t>(i);
    if (directions[s] >= 0) continue;
    if (!state_[s].closed && kinematics[s].W_N.dot(u) < 0.0) impact = true;
    if (state_[s].closed) {
      state_[s].closed = false;
      separation = true;
      ++statistics_.event_driven.separations;
      events.push_back(StateChange(t, i, ContactEventKind::kSeparation, z));
    }
  }
  const bool tangential = TangentialRoots(t, z, directions, &events);
  if (!impact && !separation && !tangential) {
    ++statistics_.event_driven.ignored_roots;
    return;
  }
  if (impact) ImpactAt(t, z, kinematics, &events);
  Settle(t, z, &events);
  contacts_.ProjectClosed(t, y, Closed(), options_.projection);
  Emit(events, t, z);
}

MoreauJeanStepReport EventDrivenRun::Report(double t, const VectorXd& z, VectorXd* joint_lambda) {
  const auto y = z.head(y_size());
  const std::vector<ClosedPoint> closed = Closed();
  VectorXd y_dot(y_size());
  const ClosedContactForces forces = contacts_.Derivative(t, y, closed, y_dot);
  *joint_lambda = forces.joint_lambda;
  const auto kinematics = contacts_.EvaluateAll(t, y);
  const VectorXd impulse = z.tail(impulse_size());
  MoreauJeanStepReport report;
  report.time = t;
  report.active_contacts = static_cast<int>(closed.size());
  report.solver_iterations = forces.lcp_iterations;
  report.solver_error = forces.lcp_error;
  report.lambda = forces.joint_lambda;
  report.contacts.assign(static_cast<std::size_t>(system_.num_unilateral_contacts()), ContactStepResult{});
  for (auto& result : report.contacts) result.g_N = std::numeric_limits<double>::infinity();
  for (int i = 0; i < contacts_.num_points(); ++i) {
    const std::size_t s = static_cast<std::size_t>(i);
    ContactStepResult& result = report.contacts[static_cast<std::size_t>(contacts_.points()[s].contact)];
    if (state_[s].closed) ++result.active_points;
    if (state_[s].closed && state_[s].tangential == Tangential::kSlide) result.sliding = true;
    const VectorXd interval = impulse.segment<3>(3 * i) - last_impulse_.segment<3>(3 * i);
    result.P_N += interval(0);
    result.P_T += interval.tail<2>();
    if (kinematics[s].g_N < result.g_N) {
      result.g_N = kinematics[s].g_N;
      result.U_N = kinematics[s].W_N.dot(y.tail(system_.num_velocities()));
    }
  }
  for (std::size_t c = 0; c < closed.size(); ++c) {
    const UnilateralContactKinematics& point = kinematics[static_cast<std::size_t>(closed[c].index)];
    const Index j = static_cast<Index>(c);
    if (forces.lambda_N(j) == 0.0) continue;
    const Eigen::Vector3d force_W =
        forces.lambda_N(j) * point.n_W + forces.lambda_T(0, j) * point.t1_W + forces.lambda_T(1, j) * point.t2_W;
    report.contacts[static_cast<std::size_t>(contacts_.points()[static_cast<std::size_t>(closed[c].index)].contact)]
        .loads.push_back({0, point.p_WA_W, point.n_W, force_W});
  }
  for (int k = 0; k < system_.num_unilateral_contacts(); ++k) {
    ContactStepResult& result = report.contacts[static_cast<std::size_t>(k)];
    result.P_N += interval_impulse_(k);
    result.P_T += interval_tangential_.col(k);
    result.active = result.active_points > 0 || interval_impact_[static_cast<std::size_t>(k)];
  }
  last_impulse_ = impulse;
  interval_impulse_.setZero();
  interval_tangential_.setZero();
  std::fill(interval_impact_.begin(), interval_impact_.end(), false);
  return report;
}

}  // namespace

SimulationStatistics SimulateEventDriven(MultibodySystem& system, const SimulationOptions& options,
                                         Eigen::VectorXd y0, const OutputCallback& output,
                                         const ContactOutputCallback& contact_output,
                                         const EventOutputCallback& event_output) {
  const auto wall_start = std::chrono::steady_clock::now();
  FLEXMBS_CHECK(options.event_driven.has_value(), "SimulateEventDriven: no event-driven options");
  CheckEventDrivenOptions(*options.event_driven);
  if (options.event_driven->impact_law == ImpactLaw::kPoisson) {
    for (int k = 0; k < system.num_unilateral_contacts(); ++k) {
      if (system.unilateral_contact(k).law().friction > 0.0) {
        throw InputError(fmt::format("contact '{}': friction {:g}: impact_law poisson takes frictionless contacts",
                                     system.unilateral_contact(k).name(), system.unilateral_contact(k).law().friction));
      }
    }
  }
  SimulationStatistics statistics;
  statistics.baumgarte_frequency = BaumgarteFrequency(options);
  system.set_constraint_settings({statistics.baumgarte_frequency, options.singular_pivot});
  statistics.initial_conditions =
      MakeConsistent(system, options.start_time, y0, options.initial_conditions);
  DroppedRowWatch watch(statistics.initial_conditions.redundancy,
                        kDroppedRowSlack * options.projection.position_tolerance);
  watch.Check(system, options.start_time, y0);

  EventDrivenRun run(system, options, event_output, watch, statistics);
  VectorXd z = run.InitialState(options.start_time, y0);
  const auto emit = [&](double t, const VectorXd& state) {
    VectorXd lambda;
    const MoreauJeanStepReport report = run.Report(t, state, &lambda);
    if (contact_output) contact_output(t, report);
    output(t, state.head(run.y_size()), lambda);
    ++statistics.outputs;
  };
  emit(options.start_time, z);
  OdeIntegrator integrator(run.Problem(), options.integrator, options.start_time, z);
  for (const double t_out : OutputTimes(options)) {
    while (integrator.time() < t_out) {
      if (integrator.Advance(t_out) == OdeStop::kReachedTime) break;
      z = integrator.state();
      // Reset after every root, even one that is no event: continuing from a root where a root
      // function is exactly 0 at and near it is refused by ARKODE ("root found at and very near
      // t"), while a reset deactivates such a function until it moves off 0.
      run.HandleRoots(integrator.time(), z, integrator.event_directions());
      integrator.Reset(integrator.time(), z);
    }
    emit(integrator.time(), integrator.state());
  }
  statistics.integrator = integrator.statistics();
  statistics.event_driven.contact_solve_cpu_seconds = run.solve_cpu_seconds();
  statistics.dropped_row_violation = watch.largest_violation();
  statistics.dropped_row_limit_share = watch.largest_share();
  statistics.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return statistics;
}

}  // namespace flexmbs::mbs
