// The multibody solver's speed against the size of the scene: a chain of B flexible links (the
// slender steel link of tests/validation/flexible_pendulum_model.h with its first n clamped
// modes) joined by revolute joints (link 0 to the ground, link k's root to link k-1's tip), all
// horizontal and at rest at t = 0, swinging down under gravity.
//
// Per (n, B): the time of each MultibodySystem call at a representative state (the start with
// small random deformations and velocities, projected), measured from outside over repeated
// calls: the bodies' mass matrices, the forces h, the constraints, the accelerations (the whole
// constrained solve), the derivative (one rhs), the projection after a step, a difference-quotient
// Jacobian (state size x rhs, formed here as ARKODE does), the model Jacobian (mbs/system_jacobian.h,
// what the implicit runs use) and the dense LU of I - gamma h J. Then both integrators, adaptive (rtol 1e-6, atol 1e-9), run for up to --budget seconds of wall time
// or --end-time of simulated time: steps per second, real-time factor, and the integrator's own
// overhead = wall - rhs evaluations x rhs - steps x projection. Ratios are against the first case
// (the peer in the same run, B = 1 and the smallest n by default).
//
// Usage: bench_mbs_speed [--modes 5,10,20,50,100] [--bodies 1,2,5,10,20,50] [--budget 1.5]
//                        [--end-time 0.05] [--implicit-max-state 1200]
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <numbers>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "bench/command_line.h"
#include "mbs/constraint_projection.h"
#include "mbs/flexible_body.h"
#include "mbs/joint.h"
#include "mbs/multibody_system.h"
#include "mbs/ode_integrator.h"
#include "mbs/system_jacobian.h"
#include "tests/validation/flexible_pendulum_model.h"

namespace {

using Eigen::Index;
using Eigen::Matrix3d;
using Eigen::Vector3d;
using Eigen::VectorXd;
using flexmbs::mbs::MultibodySystem;

struct Settings {
  std::vector<int> modes{5, 10, 20, 50, 100};
  std::vector<int> bodies{1, 2, 5, 10, 20, 50};
  double budget = 1.5;              // [s] of wall time per integrator run
  double end_time = 0.05;           // [s] simulated
  Index implicit_max_state = 1200;  // larger states: no implicit run, no Jacobian formed
};

/// "5,10,20" -> {5, 10, 20}.
/// The command line's settings (file comment); exits with 2 on an unknown option.
Settings ParseArguments(int argc, char** argv) {
  Settings settings;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string_view key = argv[i], value = argv[i + 1];
    if (key == "--modes") {
      settings.modes = flexmbs::bench::ParseIntList(value);
    } else if (key == "--bodies") {
      settings.bodies = flexmbs::bench::ParseIntList(value);
    } else if (key == "--budget") {
      settings.budget = std::stod(std::string(value));
    } else if (key == "--end-time") {
      settings.end_time = std::stod(std::string(value));
    } else if (key == "--implicit-max-state") {
      settings.implicit_max_state = std::stol(std::string(value));
    } else {
      std::fprintf(stderr, "unknown option %s\n", argv[i]);
      std::exit(2);
    }
  }
  return settings;
}

/// Wall time [s].
double Now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// Seconds per call of `call`: the first call if it takes over 0.05 s, else the mean of the
/// calls after it over at least 0.05 s (and 3 calls).
double SecondsPerCall(const std::function<void()>& call) {
  const double first = Now();
  call();
  if (Now() - first > 0.05) return Now() - first;
  long count = 0;
  const double start = Now();
  double elapsed = 0.0;
  while (count < 3 || elapsed < 0.05) {
    call();
    ++count;
    elapsed = Now() - start;
  }
  return elapsed / static_cast<double>(count);
}

/// The chain of `count` links, each with `body`'s modes; its start state (at rest, undeformed).
std::unique_ptr<MultibodySystem> Chain(const flexmbs::sid::ReducedBody& body, int count,
                                       double length, VectorXd* y0) {
  auto system = std::make_unique<MultibodySystem>(Vector3d(0.0, 0.0, -9.81));
  const Matrix3d R_WI = Eigen::AngleAxisd(-0.5 * std::numbers::pi, Vector3d::UnitX())
                            .toRotationMatrix();  // z_I = W y
  const std::string origin(flexmbs::mbs::FlexibleBody::kOriginMarker);
  for (int k = 0; k < count; ++k) {
    const std::string name = "link" + std::to_string(k);
    system->AddBody(std::make_unique<flexmbs::mbs::FlexibleBody>(name, body, false));
    const flexmbs::mbs::MarkerRef parent =
        k == 0 ? flexmbs::mbs::MarkerRef::Ground(Vector3d::Zero(), R_WI)
               : system->Marker("link" + std::to_string(k - 1), "tip");
    system->AddJoint(flexmbs::mbs::Joint("hinge" + std::to_string(k),
                                         flexmbs::mbs::JointType::kRevolute, parent,
                                         system->Marker(name, origin)));
  }
  *y0 = system->NeutralState();
  const Eigen::Quaterniond e(R_WI);
  for (int k = 0; k < count; ++k) {
    VectorXd x = VectorXd::Zero(7 + body.num_modes());
    x.head<3>() = Vector3d(k * length, 0.0, 0.0);
    x.segment<4>(3) << e.w(), e.x(), e.y(), e.z();
    system->SetBodyState(k, x, VectorXd::Zero(6 + body.num_modes()), *y0);
  }
  return system;
}

/// The time split of one scene's calls [s per call].
struct Parts {
  double mass_matrices = 0, forces = 0, constraints = 0, accelerations = 0, rhs = 0, projection = 0;
  double jacobian = -1, model_jacobian = -1, lu = -1;  // -1: not measured (state too large)
};

/// The time per call of each MultibodySystem part at state y; the Jacobian and its LU only for
/// states up to implicit_max_state.
Parts MeasureParts(const MultibodySystem& system, const VectorXd& y, Index implicit_max_state) {
  Parts p;
  VectorXd u_dot(system.num_velocities()), lambda(system.num_constraints()), y_dot(y.size());
  p.mass_matrices = SecondsPerCall([&] {
    for (int b = 0; b < system.num_bodies(); ++b) (void)system.BodyMassMatrix(b, y);
  });
  p.forces = SecondsPerCall([&] { (void)system.Forces(0.0, y); });
  p.constraints = SecondsPerCall([&] { (void)system.Constraints(0.0, y); });
  p.accelerations = SecondsPerCall([&] { system.Accelerations(0.0, y, u_dot, lambda); });
  p.rhs = SecondsPerCall([&] { system.Derivative(0.0, y, y_dot); });
  p.projection = SecondsPerCall([&] {
    VectorXd moved = y;
    flexmbs::mbs::ProjectPositions(system, 0.0, moved, {});
    flexmbs::mbs::ProjectVelocities(system, 0.0, moved);
  });
  if (y.size() > implicit_max_state) return p;
  Eigen::MatrixXd J(y.size(), y.size());
  const auto form_jacobian = [&] {
    VectorXd f0(y.size()), f1(y.size()), moved = y;
    system.Derivative(0.0, y, f0);
    for (Index j = 0; j < y.size(); ++j) {
      const double step = 1e-8 * std::max(1.0, std::abs(y(j)));
      moved(j) = y(j) + step;
      system.Derivative(0.0, moved, f1);
      J.col(j) = (f1 - f0) / step;
      moved(j) = y(j);
    }
  };
  p.jacobian = SecondsPerCall(form_jacobian);
  Eigen::MatrixXd model(y.size(), y.size());
  p.model_jacobian = SecondsPerCall([&] { flexmbs::mbs::SystemJacobian(system, 0.0, y, model); });
  const Eigen::MatrixXd newton = Eigen::MatrixXd::Identity(y.size(), y.size()) - 0.25e-4 * J;
  p.lu = SecondsPerCall([&] { Eigen::PartialPivLU<Eigen::MatrixXd> lu(newton); });
  return p;
}

/// Thrown by the rhs when a run's wall-time budget is spent (ARKODE stops cleanly).
struct BudgetSpent {};

/// One integrator run within the budget.
struct Run {
  double simulated = 0, wall = 0;
  flexmbs::mbs::OdeStatistics statistics;
  bool failed = false;
};

/// Integrates the system from y0 with `method` (adaptive, default tolerances) and the projection
/// after every step, until settings.end_time or settings.budget of wall time.
Run Integrate(MultibodySystem& system, const VectorXd& y0, flexmbs::mbs::OdeMethod method,
              const Settings& settings) {
  const double start = Now();
  flexmbs::mbs::OdeProblem problem;
  problem.size = system.state_size();
  problem.rhs = [&](double t, Eigen::Ref<const VectorXd> y, Eigen::Ref<VectorXd> y_dot) {
    if (Now() - start > settings.budget) throw BudgetSpent{};
    system.Derivative(t, y, y_dot);
  };
  double last_step_time = 0.0;  // the last accepted step's end [s]
  problem.project = [&](double t, Eigen::Ref<VectorXd> y) {
    flexmbs::mbs::ProjectPositions(system, t, y, {});
    flexmbs::mbs::ProjectVelocities(system, t, y);
    last_step_time = t;
  };
  // The implicit method's Newton matrix from the model (Simulate's default).
  problem.jacobian = [&](double t, Eigen::Ref<const VectorXd> y, Eigen::Ref<Eigen::MatrixXd> dfdy) {
    flexmbs::mbs::SystemJacobian(system, t, y, dfdy);
  };
  flexmbs::mbs::OdeOptions options;
  options.method = method;
  flexmbs::mbs::OdeIntegrator integrator(std::move(problem), options, 0.0, y0);
  Run run;
  try {
    integrator.Advance(settings.end_time);
  } catch (const BudgetSpent&) {
    // Stopped by the budget: the steps so far count.
  } catch (const std::exception& error) {
    std::fprintf(stderr, "  %s run failed: %s\n",
                 std::string(flexmbs::mbs::OdeMethodName(method)).c_str(), error.what());
    run.failed = true;
  }
  run.wall = Now() - start;
  run.statistics = integrator.statistics();
  run.simulated = last_step_time;
  return run;
}

/// One line per run: steps/s (and its ratio to the peer's), RTF, mean step, rhs per step, and the
/// wall time split into rhs, projection and the integrator's rest.
void PrintRun(const char* name, const Run& run, const Parts& parts, double peer_steps_per_second) {
  if (run.failed || run.statistics.steps == 0) {
    std::printf("  %-8s failed or no step\n", name);
    return;
  }
  const double steps = static_cast<double>(run.statistics.steps);
  const double rhs_time = static_cast<double>(run.statistics.rhs_evaluations) * parts.rhs;
  const double projection_time = steps * parts.projection;
  const double overhead = run.wall - rhs_time - projection_time;
  std::printf(
      "  %-8s %8.0f steps/s (%.3g x peer)  RTF %.3g  h %.3g s  rhs/step %.1f  Jacobians %ld  "
      "wall: rhs %.0f %%, projection %.0f %%, integrator %.0f %%\n",
      name, steps / run.wall, steps / run.wall / peer_steps_per_second, run.simulated / run.wall,
      run.simulated / steps, static_cast<double>(run.statistics.rhs_evaluations) / steps,
      run.statistics.jacobian_evaluations, 100.0 * rhs_time / run.wall,
      100.0 * projection_time / run.wall, 100.0 * overhead / run.wall);
}

}  // namespace

int main(int argc, char** argv) {
  const Settings settings = ParseArguments(argc, argv);
  const flexmbs::validation::FeLink link =
      flexmbs::validation::BuildLink(flexmbs::validation::LinkGeometry{});
  std::printf("link: %ld clamped modes, %.3g Hz to %.3g Hz\n",
              static_cast<long>(link.basis.frequency_hz.size()), link.basis.frequency_hz(0),
              link.basis.frequency_hz(link.basis.frequency_hz.size() - 1));
  Parts peer;
  double peer_explicit = 0, peer_implicit = 0;
  bool have_peer = false;
  for (const int n : settings.modes) {
    const flexmbs::sid::ReducedBody body = flexmbs::validation::FirstModes(link.body, n);
    for (const int count : settings.bodies) {
      VectorXd y0;
      auto system = Chain(body, count, link.geometry.length, &y0);
      // The representative state: small random deformations and velocities, projected.
      VectorXd y = y0;
      for (int b = 0; b < count; ++b) {
        VectorXd x = system->BodyPositions(y, b), u = system->BodyVelocities(y, b);
        x.tail(n) = 1e-6 * VectorXd::Random(n);
        u = 1e-2 * VectorXd::Random(6 + n);
        system->SetBodyState(b, x, u, y);
      }
      system->set_constraint_settings({1e3, 1e-10});
      flexmbs::mbs::ProjectPositions(*system, 0.0, y, {});
      flexmbs::mbs::ProjectVelocities(*system, 0.0, y);
      const Parts parts = MeasureParts(*system, y, settings.implicit_max_state);
      if (!have_peer) peer = parts;
      std::printf(
          "n = %3d modes, B = %2d bodies: state %5ld, constraints %4ld, highest mode %.3g Hz\n", n,
          count, static_cast<long>(system->state_size()),
          static_cast<long>(system->num_constraints()),
          body.num_modes() > 0 ? link.basis.frequency_hz(n - 1) : 0.0);
      std::printf(
          "  per call [us] (x peer): mass matrices %.3g (%.3g), forces %.3g (%.3g), constraints "
          "%.3g (%.3g), "
          "accelerations %.3g (%.3g), rhs %.3g (%.3g), projection %.3g (%.3g)",
          1e6 * parts.mass_matrices, parts.mass_matrices / peer.mass_matrices, 1e6 * parts.forces,
          parts.forces / peer.forces, 1e6 * parts.constraints, parts.constraints / peer.constraints,
          1e6 * parts.accelerations, parts.accelerations / peer.accelerations, 1e6 * parts.rhs,
          parts.rhs / peer.rhs, 1e6 * parts.projection, parts.projection / peer.projection);
      if (parts.jacobian > 0) {
        std::printf(", DQ Jacobian %.3g (%.3g), model Jacobian %.3g (%.3g), LU %.3g (%.3g)", 1e6 * parts.jacobian,
                    parts.jacobian / peer.jacobian, 1e6 * parts.model_jacobian,
                    parts.model_jacobian / peer.model_jacobian, 1e6 * parts.lu, parts.lu / peer.lu);
      }
      std::printf("\n");
      const Run explicit_run = Integrate(*system, y0, flexmbs::mbs::OdeMethod::kExplicit, settings);
      if (!have_peer && !explicit_run.failed)
        peer_explicit = static_cast<double>(explicit_run.statistics.steps) / explicit_run.wall;
      PrintRun("explicit", explicit_run, parts, peer_explicit);
      if (system->state_size() <= settings.implicit_max_state) {
        const Run implicit_run =
            Integrate(*system, y0, flexmbs::mbs::OdeMethod::kImplicit, settings);
        if (!have_peer && !implicit_run.failed)
          peer_implicit = static_cast<double>(implicit_run.statistics.steps) / implicit_run.wall;
        PrintRun("implicit", implicit_run, parts, peer_implicit);
      } else {
        std::printf(
            "  implicit skipped (state > %ld: a DQ Jacobian of %ld rhs and a dense LU per "
            "refresh)\n",
            static_cast<long>(settings.implicit_max_state),
            static_cast<long>(system->state_size()));
      }
      have_peer = true;
      std::fflush(stdout);
    }
  }
  return 0;
}
