// Event-driven integration against Moreau-Jean time stepping on many bouncing balls (issue 16;
// docs/contact.md, "Event-driven integration"): N balls (1 kg, r = 0.1 m, e = 0.9) dropped from
// heights spread over [0.5, 1] m onto the ground, one unilateral sphere_plane contact each, so
// their impacts fall at N different times. Both runs are timed (CPU seconds of this process, the
// steadier measure on a shared machine; one run each) and
// measured against the closed form of every ball: impacts at t_1 = sqrt(2 h0 / g),
// t_k+1 = t_k + 2 e^k v_1 / g, and the total energy at the end, m g (r + e^(2k) h0) after k
// impacts. Printed: times, errors and their ratios (Moreau-Jean / event-driven).
//
//   bench_event_driven [--balls 100] [--end 2.0] [--mj-step 1e-3] [--rtol 1e-10] [--atol 1e-12]
//                      [--event-driven-only 1]
#include <fmt/format.h>

#include <Eigen/Core>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "mbs/event_driven.h"
#include "mbs/rigid_body.h"
#include "mbs/simulation.h"
#include "mbs/unilateral_contact.h"

namespace flexmbs::bench {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Eigen::VectorXd;

constexpr double kMass = 1.0, kRadius = 0.1, kG = 9.81, kRestitution = 0.9;

struct Settings {
  int balls = 100;
  double end_time = 2.0;  // [s]
  double mj_step = 1e-3;  // [s]
  double rtol = 1e-10, atol = 1e-12;
  bool event_driven_only = false;  // skip Moreau-Jean (to profile event-driven alone)
};

/// prefix + k.
std::string Numbered(const char* prefix, int k) {
  std::string name = prefix;
  name += std::to_string(k);
  return name;
}

double DropHeight(int ball, int balls) { return 0.5 + 0.5 * ball / std::max(1, balls - 1); }

/// The balls, each above the ground plane with its own contact "floor<k>".
std::unique_ptr<mbs::MultibodySystem> Balls(int balls, VectorXd* y0) {
  auto system = std::make_unique<mbs::MultibodySystem>(Vector3d(0.0, 0.0, -kG));
  const Matrix3d inertia = Matrix3d::Identity() * (0.4 * kMass * kRadius * kRadius);
  for (int k = 0; k < balls; ++k) {
    system->AddBody(std::make_unique<mbs::RigidBody>(
        Numbered("ball", k), kMass, Vector3d::Zero(), inertia,
        std::vector<mbs::RigidBodyMarker>{{"centre", Vector3d::Zero(), Matrix3d::Identity()}}));
    system->AddUnilateralContact(std::make_unique<mbs::SpherePlaneUnilateral>(
        Numbered("floor", k), system->Marker(Numbered("ball", k), "centre"),
        mbs::MarkerRef::Ground(Vector3d::Zero()), kRadius, mbs::UnilateralLaw{kRestitution, 0.0}));
  }
  *y0 = system->NeutralState();
  for (int k = 0; k < balls; ++k) {
    VectorXd x(7);
    x << 2.0 * kRadius * k, 0.0, kRadius + DropHeight(k, balls), 1.0, 0.0, 0.0, 0.0;
    system->SetBodyState(k, x, VectorXd::Zero(6), *y0);
  }
  return system;
}

/// The closed-form impact times of a ball dropped from h0, up to `end`.
std::vector<double> ExactImpacts(double h0, double end) {
  std::vector<double> times;
  const double v1 = std::sqrt(2.0 * kG * h0);
  double t = std::sqrt(2.0 * h0 / kG), speed = v1;
  while (t < end) {
    times.push_back(t);
    speed *= kRestitution;
    t += 2.0 * speed / kG;
  }
  return times;
}

/// One run's CPU time, impact times per ball and energy at the end.
struct Run {
  double cpu_seconds = 0.0;
  std::vector<std::vector<double>> impacts;
  VectorXd y_end;
  long steps = 0;
};

Run Simulate(const Settings& settings, bool event_driven) {
  VectorXd y0;
  std::unique_ptr<mbs::MultibodySystem> system = Balls(settings.balls, &y0);
  mbs::SimulationOptions options;
  options.end_time = settings.end_time;
  Run run;
  run.impacts.resize(static_cast<std::size_t>(settings.balls));
  std::vector<bool> in_contact(static_cast<std::size_t>(settings.balls), false);
  mbs::ContactOutputCallback contacts;
  mbs::EventOutputCallback events;
  if (event_driven) {
    options.output_interval = settings.end_time;
    options.integrator.relative_tolerance = settings.rtol;
    options.integrator.absolute_tolerance = settings.atol;
    options.event_driven = mbs::EventDrivenOptions{};
    options.event_driven->rest_velocity = 1e-4;
    events = [&](const mbs::ContactEvent& event) {
      if (event.normal_velocity_before < 0.0)
        run.impacts[static_cast<std::size_t>(event.contact)].push_back(event.time);
    };
  } else {
    // Outputs at every step: an impact is the middle of the first step with an impulse.
    options.output_interval = settings.mj_step;
    options.moreau_jean = mbs::MoreauJeanOptions{settings.mj_step};
    contacts = [&](double t, const mbs::MoreauJeanStepReport& step) {
      for (std::size_t k = 0; k < step.contacts.size(); ++k) {
        const bool impulse = step.contacts[k].P_N > 0.0;
        if (impulse && !in_contact[k]) run.impacts[k].push_back(t - 0.5 * settings.mj_step);
        in_contact[k] = impulse;
      }
    };
  }
  const std::clock_t start = std::clock();
  const mbs::SimulationStatistics statistics = mbs::Simulate(
      *system, options, y0, [&](double, const VectorXd& y, const VectorXd&) { run.y_end = y; },
      contacts, events);
  run.cpu_seconds = static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
  run.steps = statistics.integrator.steps;
  return run;
}

/// The largest impact-time error over all balls (impacts up to end - 0.05 s) [s], and the total
/// energy's error at the end relative to the initial energy.
struct Errors {
  double impact_time = 0.0;
  double energy = 0.0;
  long impacts = 0;
};

Errors Measure(const Settings& settings, const Run& run) {
  Errors errors;
  double energy_error = 0.0, energy0 = 0.0;
  for (int k = 0; k < settings.balls; ++k) {
    const double h0 = DropHeight(k, settings.balls);
    const std::vector<double> exact = ExactImpacts(h0, settings.end_time);
    const std::vector<double>& found = run.impacts[static_cast<std::size_t>(k)];
    for (std::size_t i = 0; i < exact.size() && exact[i] < settings.end_time - 0.05; ++i) {
      errors.impact_time =
          std::max(errors.impact_time, i < found.size() ? std::abs(found[i] - exact[i]) : 1.0);
      ++errors.impacts;
    }
    const double e2k = std::pow(kRestitution, 2.0 * static_cast<double>(exact.size()));
    const Eigen::Index offset = 7 * settings.balls + 6 * k;
    const double z = run.y_end(7 * k + 2), v = run.y_end.segment<3>(offset).norm();
    energy_error +=
        std::abs(kMass * kG * z + 0.5 * kMass * v * v - kMass * kG * (kRadius + e2k * h0));
    energy0 += kMass * kG * (kRadius + h0);
  }
  errors.energy = energy_error / energy0;
  return errors;
}

Settings Parse(int argc, char** argv) {
  Settings settings;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string_view key = argv[i];
    const char* value = argv[i + 1];
    if (key == "--balls") {
      settings.balls = std::atoi(value);
    } else if (key == "--end") {
      settings.end_time = std::atof(value);
    } else if (key == "--mj-step") {
      settings.mj_step = std::atof(value);
    } else if (key == "--rtol") {
      settings.rtol = std::atof(value);
    } else if (key == "--atol") {
      settings.atol = std::atof(value);
    } else if (key == "--event-driven-only") {
      settings.event_driven_only = std::atoi(value) != 0;
    } else {
      fmt::print(stderr, "unknown option {}\n", key);
      std::exit(2);
    }
  }
  return settings;
}

}  // namespace
}  // namespace flexmbs::bench

int main(int argc, char** argv) {
  using namespace flexmbs::bench;
  const Settings settings = Parse(argc, argv);
  fmt::print("{} balls, e = {}, {} s; event-driven rtol {:g}, atol {:g}; Moreau-Jean h = {:g} s\n",
             settings.balls, kRestitution, settings.end_time, settings.rtol, settings.atol,
             settings.mj_step);
  const Run ed = Simulate(settings, true);
  const Errors ed_errors = Measure(settings, ed);
  if (settings.event_driven_only) {
    fmt::print(
        "event-driven: {:.3f} s CPU, {} steps, {} impacts, impact-time error {:.3e} s, energy "
        "error {:.3e}\n",
        ed.cpu_seconds, ed.steps, ed_errors.impacts, ed_errors.impact_time, ed_errors.energy);
    return 0;
  }
  const Run mj = Simulate(settings, false);
  const Errors mj_errors = Measure(settings, mj);
  fmt::print("{:<14} {:>10} {:>10} {:>10} {:>16} {:>14}\n", "method", "CPU [s]", "steps", "impacts",
             "impact-time err", "energy err");
  fmt::print("{:<14} {:>10.3f} {:>10} {:>10} {:>16.3e} {:>14.3e}\n", "event-driven", ed.cpu_seconds,
             ed.steps, ed_errors.impacts, ed_errors.impact_time, ed_errors.energy);
  fmt::print("{:<14} {:>10.3f} {:>10} {:>10} {:>16.3e} {:>14.3e}\n", "Moreau-Jean", mj.cpu_seconds,
             mj.steps, mj_errors.impacts, mj_errors.impact_time, mj_errors.energy);
  fmt::print("ratio MJ / ED: time {:.3g}, impact-time error {:.3g}, energy error {:.3g}\n",
             mj.cpu_seconds / ed.cpu_seconds, mj_errors.impact_time / ed_errors.impact_time,
             mj_errors.energy / ed_errors.energy);
  return 0;
}
