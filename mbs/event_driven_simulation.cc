#include "mbs/event_driven_simulation.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
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
        closed_(static_cast<std::size_t>(contacts_.num_points()), false),
        interval_impulse_(VectorXd::Zero(system.num_unilateral_contacts())),
        interval_impact_(static_cast<std::size_t>(system.num_unilateral_contacts()), false) {}

  Index y_size() const { return system_.state_size(); }
  /// [y; I] for the integrator (I = 0 at the start).
  VectorXd InitialState(double t, const VectorXd& y0) {
    VectorXd z = VectorXd::Zero(y_size() + contacts_.num_points());
    z.head(y_size()) = y0;
    StartContacts(t, z);
    last_impulse_ = z.tail(contacts_.num_points());
    return z;
  }
  OdeProblem Problem();
  /// Handles the roots the integrator stopped at: impacts, separations, or no event (counted).
  void HandleRoots(double t, VectorXd& z, const std::vector<int>& directions);
  /// The contact report and the joint multipliers of the output interval that ends at (t, z).
  MoreauJeanStepReport Report(double t, const VectorXd& z, VectorXd* joint_lambda);

 private:
  std::vector<int> Closed() const {
    std::vector<int> closed;
    for (int i = 0; i < contacts_.num_points(); ++i) {
      if (closed_[static_cast<std::size_t>(i)]) closed.push_back(i);
    }
    return closed;
  }
  void StartContacts(double t, VectorXd& z);
  void ImpactAt(double t, VectorXd& z, const std::vector<UnilateralContactKinematics>& kinematics,
                std::vector<ContactEvent>* events);
  void OpenUnloaded(double t, VectorXd& z, std::vector<ContactEvent>* events);
  void Emit(std::vector<ContactEvent>& events, double t, const VectorXd& z);

  MultibodySystem& system_;
  const SimulationOptions& options_;
  EventDrivenOptions ed_;
  EventDrivenContacts contacts_;
  const EventOutputCallback& event_output_;
  DroppedRowWatch& watch_;
  SimulationStatistics& statistics_;
  std::vector<bool> closed_;
  VectorXd interval_impulse_;          ///< impact impulses per contact since the last output [N s]
  std::vector<bool> interval_impact_;  ///< per contact: an impact since the last output
  VectorXd last_impulse_;              ///< I at the last output
};

OdeProblem EventDrivenRun::Problem() {
  OdeProblem problem;
  problem.size = y_size() + contacts_.num_points();
  problem.rhs = [this](double t, Eigen::Ref<const VectorXd> z, Eigen::Ref<VectorXd> z_dot) {
    const std::vector<int> closed = Closed();
    const ClosedContactForces forces =
        contacts_.Derivative(t, z.head(y_size()), closed, z_dot.head(y_size()));
    z_dot.tail(contacts_.num_points()).setZero();
    for (std::size_t i = 0; i < closed.size(); ++i)
      z_dot(y_size() + closed[i]) = forces.lambda_N(static_cast<Index>(i));
  };
  problem.num_events = contacts_.num_points();
  problem.events = [this](double t, Eigen::Ref<const VectorXd> z, Eigen::Ref<VectorXd> g) {
    const auto y = z.head(y_size());
    const std::vector<int> closed = Closed();
    const auto kinematics = contacts_.EvaluateAll(t, y);
    for (int i = 0; i < contacts_.num_points(); ++i)
      g(i) = kinematics[static_cast<std::size_t>(i)].g_N;
    if (closed.empty()) return;
    VectorXd y_dot(y_size());
    const ClosedContactForces forces = contacts_.Derivative(t, y, closed, y_dot);
    for (std::size_t i = 0; i < closed.size(); ++i) {
      const Index c = static_cast<Index>(i);
      g(closed[i]) = forces.delassus_diagonal(c) * forces.lambda_N(c) - forces.gap_acceleration(c);
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

void EventDrivenRun::StartContacts(double t, VectorXd& z) {
  auto y = z.head(y_size());
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
    const double U_N = k.W_N.dot(y.tail(system_.num_velocities()));
    if (U_N < 0.0) approaching = true;
    closed_[static_cast<std::size_t>(i)] = U_N <= ed_.rest_velocity;
  }
  std::vector<ContactEvent> events;
  if (approaching) ImpactAt(t, z, kinematics, &events);
  OpenUnloaded(t, z, &events);
  contacts_.ProjectClosed(t, y, Closed(), options_.projection);
  Emit(events, t, z);
}

void EventDrivenRun::ImpactAt(double t, VectorXd& z,
                              const std::vector<UnilateralContactKinematics>& kinematics,
                              std::vector<ContactEvent>* events) {
  auto y = z.head(y_size());
  std::vector<int> touching;
  for (int i = 0; i < contacts_.num_points(); ++i) {
    if (closed_[static_cast<std::size_t>(i)] ||
        kinematics[static_cast<std::size_t>(i)].g_N <= ed_.gap_tolerance) {
      touching.push_back(i);
    }
  }
  const double energy_before = system_.KineticEnergy(y);
  const ImpactResult impact = contacts_.Impact(t, y, touching);
  ++statistics_.event_driven.impacts;
  statistics_.event_driven.max_impact_points =
      std::max(statistics_.event_driven.max_impact_points, static_cast<int>(touching.size()));
  statistics_.event_driven.max_lcp_error =
      std::max(statistics_.event_driven.max_lcp_error, impact.lcp_error);
  for (std::size_t j = 0; j < touching.size(); ++j) {
    const Index c = static_cast<Index>(j);
    const int i = touching[j];
    const ContactPointRef& ref = contacts_.points()[static_cast<std::size_t>(i)];
    const bool close = impact.U_N_after(c) <= ed_.rest_velocity;
    if (close && !closed_[static_cast<std::size_t>(i)]) ++statistics_.event_driven.closings;
    closed_[static_cast<std::size_t>(i)] = close;
    interval_impulse_(ref.contact) += impact.P_N(c);
    interval_impact_[static_cast<std::size_t>(ref.contact)] = true;
    events->push_back({t, ContactEventKind::kImpact, ref.contact, ref.point, impact.U_N_before(c),
                       close ? 0.0 : impact.U_N_after(c), impact.P_N(c), energy_before, 0.0,
                       close});
  }
}

void EventDrivenRun::OpenUnloaded(double t, VectorXd& z, std::vector<ContactEvent>* events) {
  auto y = z.head(y_size());
  for (int round = 0; round < contacts_.num_points(); ++round) {
    const std::vector<int> closed = Closed();
    if (closed.empty()) return;
    VectorXd y_dot(y_size());
    const ClosedContactForces forces = contacts_.Derivative(t, y, closed, y_dot);
    bool opened = false;
    for (std::size_t j = 0; j < closed.size(); ++j) {
      const Index c = static_cast<Index>(j);
      if (!(forces.lambda_N(c) <= 0.0 && forces.gap_acceleration(c) > 0.0)) continue;
      const ContactPointRef& ref = contacts_.points()[static_cast<std::size_t>(closed[j])];
      closed_[static_cast<std::size_t>(closed[j])] = false;
      opened = true;
      ++statistics_.event_driven.separations;
      const double energy = system_.KineticEnergy(y);
      events->push_back({t, ContactEventKind::kSeparation, ref.contact, ref.point, 0.0, 0.0, 0.0,
                         energy, energy, false});
    }
    if (!opened) return;
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
    if (!closed_[s] && kinematics[s].W_N.dot(u) < 0.0) impact = true;
    if (closed_[s]) {
      closed_[s] = false;
      separation = true;
      ++statistics_.event_driven.separations;
      const ContactPointRef& ref = contacts_.points()[s];
      const double energy = system_.KineticEnergy(y);
      events.push_back({t, ContactEventKind::kSeparation, ref.contact, ref.point, 0.0, 0.0, 0.0,
                        energy, energy, false});
    }
  }
  if (!impact && !separation) {
    ++statistics_.event_driven.ignored_roots;
    return;
  }
  if (impact) ImpactAt(t, z, kinematics, &events);
  OpenUnloaded(t, z, &events);
  contacts_.ProjectClosed(t, y, Closed(), options_.projection);
  Emit(events, t, z);
}

MoreauJeanStepReport EventDrivenRun::Report(double t, const VectorXd& z, VectorXd* joint_lambda) {
  const auto y = z.head(y_size());
  const std::vector<int> closed = Closed();
  VectorXd y_dot(y_size());
  const ClosedContactForces forces = contacts_.Derivative(t, y, closed, y_dot);
  *joint_lambda = forces.joint_lambda;
  const auto kinematics = contacts_.EvaluateAll(t, y);
  const VectorXd impulse = z.tail(contacts_.num_points());
  MoreauJeanStepReport report;
  report.time = t;
  report.active_contacts = static_cast<int>(closed.size());
  report.solver_iterations = forces.lcp_iterations;
  report.solver_error = forces.lcp_error;
  report.lambda = forces.joint_lambda;
  report.contacts.assign(static_cast<std::size_t>(system_.num_unilateral_contacts()),
                         ContactStepResult{});
  for (auto& result : report.contacts) result.g_N = std::numeric_limits<double>::infinity();
  for (int i = 0; i < contacts_.num_points(); ++i) {
    const std::size_t s = static_cast<std::size_t>(i);
    const int k = contacts_.points()[s].contact;
    ContactStepResult& result = report.contacts[static_cast<std::size_t>(k)];
    if (closed_[s]) ++result.active_points;
    result.P_N += impulse(i) - last_impulse_(i);
    if (kinematics[s].g_N < result.g_N) {
      result.g_N = kinematics[s].g_N;
      result.U_N = kinematics[s].W_N.dot(y.tail(system_.num_velocities()));
    }
  }
  for (std::size_t c = 0; c < closed.size(); ++c) {
    const UnilateralContactKinematics& point = kinematics[static_cast<std::size_t>(closed[c])];
    const double lambda_N = forces.lambda_N(static_cast<Eigen::Index>(c));
    if (lambda_N == 0.0) continue;
    report.contacts[static_cast<std::size_t>(contacts_.points()[static_cast<std::size_t>(closed[c])].contact)]
        .loads.push_back({0, point.p_WA_W, point.n_W, lambda_N * point.n_W});
  }
  for (int k = 0; k < system_.num_unilateral_contacts(); ++k) {
    ContactStepResult& result = report.contacts[static_cast<std::size_t>(k)];
    result.P_N += interval_impulse_(k);
    result.active = result.active_points > 0 || interval_impact_[static_cast<std::size_t>(k)];
  }
  last_impulse_ = impulse;
  interval_impulse_.setZero();
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
  statistics.dropped_row_violation = watch.largest_violation();
  statistics.dropped_row_limit_share = watch.largest_share();
  statistics.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return statistics;
}

}  // namespace flexmbs::mbs
