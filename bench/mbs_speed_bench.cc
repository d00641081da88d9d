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
// what the dense Newton uses), Eigen's dense LU of I - gamma h J, ARKODE's dense Newton as it runs
// (a SUNLinSol_Dense setup and one solve), and the sparse Newton's parts (mbs/kkt_newton_solver.h):
// its evaluation, the factorisation of its augmented matrix, one solve; "modelled" rates put the
// sparse run's counts and these times together for either Newton. Then the integrators, adaptive (rtol 1e-6, atol 1e-9): explicit, implicit with
// the dense Newton and implicit with the sparse Newton, each for up to --budget seconds of wall time
// or --end-time of simulated time: steps per second, real-time factor, and the integrator's own
// overhead = wall - rhs evaluations x rhs - steps x projection. Ratios are against the first case
// (the peer in the same run, B = 1 and the smallest n by default); "sparse / dense" is the ratio of
// the two implicit runs' steps per second.
//
// Usage: bench_mbs_speed [--modes 5,10,20,50,100] [--bodies 1,2,5,10,20,50] [--budget 1.5]
//                        [--end-time 0.05] [--implicit-max-state 1200]
// (--implicit-max-state limits the dense Newton and the difference-quotient Jacobian; the sparse
// Newton runs at every size.)
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

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
#include "mbs/kkt_newton_solver.h"
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
  Index implicit_max_state = 1200;  // larger states: no dense Newton run, no dense Jacobian formed
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
  // ARKODE's dense Newton as it runs (SUNLinSol_Dense): a setup (the saved J copied back,
  // A = I - gamma J, SUNDIALS' own LU), one solve.
  double dense_setup = -1, dense_solve = -1;
  double sparse_evaluate = 0, sparse_factorize = 0, sparse_solve = 0;   // the sparse Newton's parts
};

/// gamma = h a_ii [s] of the Newton matrices timed here: the ESDIRK's a_ii (1/4) at a step of 1e-4 s.
constexpr double kBenchGamma = 0.25e-4;

/// SUNLinSol_Dense on a saved Jacobian J, as ARKODE's dense Newton holds it, and a right-hand side.
struct ArkodeDenseNewton {
  SUNContext context = nullptr;
  N_Vector x = nullptr, b = nullptr;
  SUNMatrix saved = nullptr, A = nullptr;
  SUNLinearSolver solver = nullptr;
  ArkodeDenseNewton(const Eigen::MatrixXd& J, const VectorXd& r) {
    const auto n = static_cast<sunindextype>(J.rows());
    SUNContext_Create(nullptr, &context);
    x = N_VNew_Serial(n, context);
    b = N_VNew_Serial(n, context);
    Eigen::Map<VectorXd>(N_VGetArrayPointer(b), J.rows()) = r;
    saved = SUNDenseMatrix(n, n, context);
    A = SUNDenseMatrix(n, n, context);
    Eigen::Map<Eigen::MatrixXd>(SUNDenseMatrix_Data(saved), J.rows(), J.cols()) = J;
    solver = SUNLinSol_Dense(x, A, context);
  }
  ~ArkodeDenseNewton() {
    SUNLinSolFree(solver);
    SUNMatDestroy(A);
    SUNMatDestroy(saved);
    N_VDestroy(b);
    N_VDestroy(x);
    SUNContext_Free(&context);
  }
  ArkodeDenseNewton(const ArkodeDenseNewton&) = delete;
  ArkodeDenseNewton& operator=(const ArkodeDenseNewton&) = delete;
};

/// The time per call of each MultibodySystem part at state y; the dense Jacobians and the LU only
/// for states up to implicit_max_state.
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
  flexmbs::mbs::KktNewtonSolver sparse(system);
  VectorXd r = VectorXd::Random(y.size());
  p.sparse_evaluate = SecondsPerCall([&] { sparse.Evaluate(0.0, y); });
  p.sparse_factorize = SecondsPerCall([&] { sparse.Factorize(kBenchGamma); });
  p.sparse_solve = SecondsPerCall([&] {
    VectorXd x = r;
    sparse.Solve(x);
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
  const Eigen::MatrixXd newton = Eigen::MatrixXd::Identity(y.size(), y.size()) - kBenchGamma * J;
  ArkodeDenseNewton dense(J, r);
  p.lu = SecondsPerCall([&] { Eigen::PartialPivLU<Eigen::MatrixXd> lu(newton); });
  p.dense_setup = SecondsPerCall([&] {
    SUNMatCopy(dense.saved, dense.A);
    SUNMatScaleAddI(-kBenchGamma, dense.A);
    SUNLinSolSetup(dense.solver, dense.A);
  });
  p.dense_solve = SecondsPerCall([&] { SUNLinSolSolve(dense.solver, dense.A, dense.x, dense.b, 0.0); });
  return p;
}

/// Thrown by the rhs when a run's wall-time budget is spent (ARKODE stops cleanly).
struct BudgetSpent {};

/// One integrator run within the budget.
struct Run {
  double simulated = 0, wall = 0;
  flexmbs::mbs::OdeStatistics statistics;
  flexmbs::mbs::KktNewtonTimes sparse_times;  // the sparse Newton's parts in the run
  bool failed = false;
};

/// Integrates the system from y0 with `method` (adaptive, default tolerances; the implicit one
/// with the model Jacobian and `newton`) and the projection after every step, until
/// settings.end_time or settings.budget of wall time.
Run Integrate(MultibodySystem& system, const VectorXd& y0, flexmbs::mbs::OdeMethod method,
              flexmbs::mbs::OdeNewton newton, const Settings& settings) {
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
  // The implicit method's Newton matrix from the model (Simulate's default), dense or sparse.
  problem.jacobian = [&](double t, Eigen::Ref<const VectorXd> y, Eigen::Ref<Eigen::MatrixXd> dfdy) {
    flexmbs::mbs::SystemJacobian(system, t, y, dfdy);
  };
  const auto sparse = std::make_shared<flexmbs::mbs::KktNewtonSolver>(system);
  problem.newton_solver = sparse;
  flexmbs::mbs::OdeOptions options;
  options.method = method;
  options.newton = newton;
  flexmbs::mbs::OdeIntegrator integrator(std::move(problem), options, 0.0, y0);
  Run run;
  try {
    integrator.Advance(settings.end_time);
  } catch (const BudgetSpent&) {
    // Stopped by the budget: the steps so far count.
  } catch (const std::exception& error) {
    std::fprintf(stderr, "  %s run (newton %s) failed: %s\n", std::string(flexmbs::mbs::OdeMethodName(method)).c_str(),
                 std::string(flexmbs::mbs::OdeNewtonName(newton)).c_str(), error.what());
    run.failed = true;
  }
  run.wall = Now() - start;
  run.statistics = integrator.statistics();
  run.sparse_times = sparse->times();
  run.simulated = last_step_time;
  return run;
}

/// Seconds per step of an implicit run with its counts (rhs, Newton iterations, Jacobians, setups
/// per step) and the per-call times of `parts`, for the sparse or the dense Newton: the rate a run
/// would reach in those counts, comparable where a measured run is too short (its start-up steps).
double ModelledSecondsPerStep(const flexmbs::mbs::OdeStatistics& s, const Parts& parts, bool sparse) {
  const double steps = static_cast<double>(s.steps);
  const double jacobian = sparse ? parts.sparse_evaluate : parts.model_jacobian;
  const double setup = sparse ? parts.sparse_factorize : parts.dense_setup;
  const double solve = sparse ? parts.sparse_solve : parts.dense_solve;
  return (static_cast<double>(s.rhs_evaluations) * parts.rhs + steps * parts.projection +
          static_cast<double>(s.jacobian_evaluations) * jacobian + static_cast<double>(s.newton_setups) * setup +
          static_cast<double>(s.newton_iterations) * solve) /
         steps;
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
      "  %-8s %8.0f steps/s (%.3g x peer)  RTF %.3g  h %.3g s  rhs/step %.1f  Newton/step %.2f  Jacobians %ld  "
      "setups %ld  wall: rhs %.0f %%, projection %.0f %%, integrator %.0f %%\n",
      name, steps / run.wall, steps / run.wall / peer_steps_per_second, run.simulated / run.wall,
      run.simulated / steps, static_cast<double>(run.statistics.rhs_evaluations) / steps,
      static_cast<double>(run.statistics.newton_iterations) / steps, run.statistics.jacobian_evaluations,
      run.statistics.newton_setups, 100.0 * rhs_time / run.wall,
      100.0 * projection_time / run.wall, 100.0 * overhead / run.wall);
  const flexmbs::mbs::KktNewtonTimes& t = run.sparse_times;
  if (run.statistics.sparse_newton && t.solves > 0) {
    std::printf("           sparse Newton in the run: evaluate %ld x %.3g us, factorize %ld x %.3g us, solve %ld x %.3g us: "
                "%.0f %% of the wall\n",
                t.evaluations, 1e6 * t.evaluate / static_cast<double>(std::max(t.evaluations, 1L)), t.factorizations,
                1e6 * t.factorize / static_cast<double>(std::max(t.factorizations, 1L)), t.solves,
                1e6 * t.solve / static_cast<double>(t.solves), 100.0 * (t.evaluate + t.factorize + t.solve) / run.wall);
  }
}

/// The representative state of a chain of `count` links with n modes each: y0 with small random
/// deformations and velocities, projected onto the constraints.
VectorXd RepresentativeState(MultibodySystem& system, const VectorXd& y0, int count, int n) {
  VectorXd y = y0;
  for (int b = 0; b < count; ++b) {
    VectorXd x = system.BodyPositions(y, b), u = system.BodyVelocities(y, b);
    x.tail(n) = 1e-6 * VectorXd::Random(n);
    u = 1e-2 * VectorXd::Random(6 + n);
    system.SetBodyState(b, x, u, y);
  }
  flexmbs::mbs::ProjectPositions(system, 0.0, y, {});
  flexmbs::mbs::ProjectVelocities(system, 0.0, y);
  return y;
}

/// One line per MultibodySystem part: its time per call [us] and its ratio to the peer's.
void PrintParts(const Parts& parts, const Parts& peer) {
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
}

/// The Newton systems' costs: a setup with a fresh Jacobian, a refactorisation (gamma changed),
/// one solve; dense = model Jacobian + LU, LU, LU solve.
void PrintNewtonCosts(const Parts& parts, const MultibodySystem& system) {
  std::printf("  Newton [us]: sparse evaluate %.3g, factorize %.3g, solve %.3g (augmented %ld x %ld)",
              1e6 * parts.sparse_evaluate, 1e6 * parts.sparse_factorize, 1e6 * parts.sparse_solve,
              static_cast<long>(system.num_velocities() + system.num_constraints()),
              static_cast<long>(system.num_velocities() + system.num_constraints()));
  if (parts.lu > 0) {
    std::printf("; dense (ARKODE) model Jacobian %.3g, setup %.3g, solve %.3g; dense / sparse: Jacobian + setup "
                "%.3g, setup %.3g, solve %.3g",
                1e6 * parts.model_jacobian, 1e6 * parts.dense_setup, 1e6 * parts.dense_solve,
                (parts.model_jacobian + parts.dense_setup) / (parts.sparse_evaluate + parts.sparse_factorize),
                parts.dense_setup / parts.sparse_factorize, parts.dense_solve / parts.sparse_solve);
  }
  std::printf("\n");
}

/// The first case's steps per second of each integrator run (0 until measured).
struct PeerRates {
  double explicit_run = 0, dense = 0, sparse = 0;
};

/// A run's steps per second.
double StepsPerSecond(const Run& run) { return static_cast<double>(run.statistics.steps) / run.wall; }

/// The sparse Newton's run against the dense one's steps per second (0: none), measured and
/// modelled at the sparse run's counts (where the dense parts were measured).
void PrintSparseAgainstDense(const Run& sparse_run, double dense_rate, const Parts& parts) {
  if (dense_rate > 0.0 && !sparse_run.failed && sparse_run.statistics.steps > 0) {
    std::printf("  sparse / dense Newton: %.3g x the steps per second\n", StepsPerSecond(sparse_run) / dense_rate);
  }
  if (parts.lu > 0 && !sparse_run.failed && sparse_run.statistics.steps > 0) {
    const double sparse_model = 1.0 / ModelledSecondsPerStep(sparse_run.statistics, parts, true);
    const double dense_model = 1.0 / ModelledSecondsPerStep(sparse_run.statistics, parts, false);
    std::printf("  modelled at the sparse run's counts: sparse %.3g, dense %.3g steps/s: sparse / dense %.3g\n",
                sparse_model, dense_model, sparse_model / dense_model);
  }
}

/// The integrator runs from y0 (explicit; implicit with the dense Newton where the state is small
/// enough; implicit with the sparse Newton), printed; the first case (!have_peer) sets `peer`.
void RunIntegrators(MultibodySystem& system, const VectorXd& y0, const Parts& parts,
                    const Settings& settings, bool have_peer, PeerRates* peer) {
  using flexmbs::mbs::OdeMethod;
  using flexmbs::mbs::OdeNewton;
  const Run explicit_run = Integrate(system, y0, OdeMethod::kExplicit, OdeNewton::kDense, settings);
  if (!have_peer && !explicit_run.failed) peer->explicit_run = StepsPerSecond(explicit_run);
  PrintRun("explicit", explicit_run, parts, peer->explicit_run);
  double dense_rate = 0.0;
  if (system.state_size() <= settings.implicit_max_state) {
    const Run implicit_run = Integrate(system, y0, OdeMethod::kImplicit, OdeNewton::kDense, settings);
    if (!have_peer && !implicit_run.failed) peer->dense = StepsPerSecond(implicit_run);
    PrintRun("dense", implicit_run, parts, peer->dense);
    if (!implicit_run.failed) dense_rate = StepsPerSecond(implicit_run);
  } else {
    std::printf("  dense Newton skipped (state > %ld: a dense LU of the state per setup)\n",
                static_cast<long>(settings.implicit_max_state));
  }
  const Run sparse_run = Integrate(system, y0, OdeMethod::kImplicit, OdeNewton::kSparse, settings);
  if (!have_peer && !sparse_run.failed) peer->sparse = StepsPerSecond(sparse_run);
  PrintRun("sparse", sparse_run, parts, peer->sparse);
  PrintSparseAgainstDense(sparse_run, dense_rate, parts);
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
  PeerRates peer_rates;
  bool have_peer = false;
  for (const int n : settings.modes) {
    const flexmbs::sid::ReducedBody body = flexmbs::validation::FirstModes(link.body, n);
    for (const int count : settings.bodies) {
      VectorXd y0;
      auto system = Chain(body, count, link.geometry.length, &y0);
      system->set_constraint_settings({1e3, 1e-10});
      const VectorXd y = RepresentativeState(*system, y0, count, n);
      const Parts parts = MeasureParts(*system, y, settings.implicit_max_state);
      if (!have_peer) peer = parts;
      std::printf(
          "n = %3d modes, B = %2d bodies: state %5ld, constraints %4ld, highest mode %.3g Hz\n", n,
          count, static_cast<long>(system->state_size()),
          static_cast<long>(system->num_constraints()),
          body.num_modes() > 0 ? link.basis.frequency_hz(n - 1) : 0.0);
      PrintParts(parts, peer);
      PrintNewtonCosts(parts, *system);
      RunIntegrators(*system, y0, parts, settings, have_peer, &peer_rates);
      have_peer = true;
      std::fflush(stdout);
    }
  }
  return 0;
}
