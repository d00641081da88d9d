// The ARKODE integrator (mbs/ode_integrator.h) on problems with known solutions: accuracy
// against tolerance, order with fixed steps, L-stability on a stiff system, events and Reset,
// the projection hook, statistics and errors.
#include "mbs/ode_integrator.h"

#include <arkode/arkode_butcher_dirk.h>
#include <arkode/arkode_butcher_erk.h>
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "mbs/simulation_error.h"
#include "tests/input_error.h"

namespace flexmbs::mbs {
namespace {

using Eigen::Ref;
using Eigen::VectorXd;

constexpr double kEps = std::numeric_limits<double>::epsilon();

std::string Name(OdeMethod method) { return std::string(OdeMethodName(method)); }

class BothMethods : public ::testing::TestWithParam<OdeMethod> {};

INSTANTIATE_TEST_SUITE_P(Ode, BothMethods,
                         ::testing::Values(OdeMethod::kExplicit, OdeMethod::kImplicit),
                         [](const auto& param_info) { return Name(param_info.param); });

// ---------------------------------------------------------------------------------------------
// Accuracy against the tolerance: x'' = -w^2 x.

/// x'' = -w^2 x from (1, 0): x = cos(w t), v = -w sin(w t).
OdeProblem HarmonicOscillator(double w) {
  OdeProblem problem;
  problem.size = 2;
  problem.rhs = [w](double, Ref<const VectorXd> y, Ref<VectorXd> ydot) {
    ydot(0) = y(1);
    ydot(1) = -w * w * y(0);
  };
  return problem;
}

struct OscillatorRun {
  double error = 0.0;  ///< largest error of x and v / w over the outputs
  long steps = 0;
};

/// Ten periods (w = 2 pi) with output every 0.05 s (interpolated), rtol = atol = tolerance.
OscillatorRun HarmonicOscillatorRun(OdeMethod method, double tolerance) {
  const double w = 2.0 * std::numbers::pi;
  const double dt = 0.05;
  OdeOptions options;
  options.method = method;
  options.relative_tolerance = tolerance;
  options.absolute_tolerance = tolerance;
  OdeIntegrator integrator(HarmonicOscillator(w), options, 0.0, VectorXd::Unit(2, 0));
  OscillatorRun run;
  for (int k = 1; k <= 200; ++k) {
    EXPECT_EQ(integrator.Advance(k * dt), OdeStop::kReachedTime);
    const double t = integrator.time();
    EXPECT_EQ(t, k * dt);
    run.error = std::max({run.error, std::abs(integrator.state()(0) - std::cos(w * t)),
                          std::abs(integrator.state()(1) / w + std::sin(w * t))});
  }
  run.steps = integrator.statistics().steps;
  return run;
}

TEST_P(BothMethods, HarmonicOscillatorErrorFollowsTheTolerance) {
  const OscillatorRun loose = HarmonicOscillatorRun(GetParam(), 1e-6);
  const OscillatorRun tight = HarmonicOscillatorRun(GetParam(), 1e-9);
  std::printf(
      "  %s, 10 periods: error %.2e at rtol 1e-6 (%ld steps), %.2e at rtol 1e-9 (%ld steps)\n",
      Name(GetParam()).c_str(), loose.error, loose.steps, tight.error, tight.steps);
  // On a neutrally stable problem local errors add up; the controller holds each below
  // rtol |y| (|y| <= 1 here), so the global error is below steps * rtol.
  EXPECT_LE(loose.error, loose.steps * 1e-6);
  EXPECT_LE(tight.error, tight.steps * 1e-9);
  // A thousand times tighter tolerance: at least a hundred times smaller error. At worst each
  // step errs by rtol and there are ~ rtol^(-1/(p+1)) steps, p the embedding's order: error ~
  // rtol^(1 - 1/(p+1)), 1000^0.75 = 178 for the ESDIRK (p = 3), 1000^0.8 for Dormand-Prince.
  EXPECT_LE(tight.error, loose.error / 100.0);
}

// ---------------------------------------------------------------------------------------------
// Order with fixed steps: the circular Kepler orbit, a nonlinear problem with a known solution.

/// r'' = -r / |r|^3 from (1, 0, 0, 1): the circular orbit (cos t, sin t).
OdeProblem CircularKepler() {
  OdeProblem problem;
  problem.size = 4;
  problem.rhs = [](double, Ref<const VectorXd> y, Ref<VectorXd> ydot) {
    const double r3 = std::pow(y(0) * y(0) + y(1) * y(1), 1.5);
    ydot << y(2), y(3), -y(0) / r3, -y(1) / r3;
  };
  return problem;
}

double KeplerErrorWithFixedStep(OdeMethod method, double h) {
  const double t_end = 2.0;
  OdeOptions options;
  options.method = method;
  options.fixed_step = h;
  options.relative_tolerance = 1e-12;  // the Newton iteration's: far below the truncation error
  options.absolute_tolerance = 1e-12;
  VectorXd y0(4);
  y0 << 1.0, 0.0, 0.0, 1.0;
  OdeIntegrator integrator(CircularKepler(), options, 0.0, y0);
  integrator.Advance(t_end);
  VectorXd exact(4);
  exact << std::cos(t_end), std::sin(t_end), -std::sin(t_end), std::cos(t_end);
  return (integrator.state() - exact).cwiseAbs().maxCoeff();
}

TEST_P(BothMethods, FixedStepErrorHasTheMethodsOrder) {
  const double expected_order = GetParam() == OdeMethod::kExplicit ? 5.0 : 4.0;
  // Halving h from 0.025 (80 steps): in the asymptotic range, the errors (1e-9 .. 1e-12) far
  // above round-off. 0.25 covers the higher-order terms still visible there (measured: the
  // order approaches from above for Dormand-Prince, from below for the ESDIRK).
  constexpr double kOrderTolerance = 0.25;
  std::printf("  %s, fixed steps:", Name(GetParam()).c_str());
  double order = 0.0;
  for (double h : {0.1, 0.05, 0.025}) {
    const double error = KeplerErrorWithFixedStep(GetParam(), h);
    const double error_half = KeplerErrorWithFixedStep(GetParam(), h / 2);
    order = std::log2(error / error_half);
    std::printf(" h %.3g: error %.2e, order %.2f;", h, error, order);
  }
  std::printf("\n");
  EXPECT_NEAR(order, expected_order, kOrderTolerance);
}

// ---------------------------------------------------------------------------------------------
// Stiffness: y' = -lambda (y - forcing sin t), lambda = 1, 1e3, 1e6 [1/s], at h = 1e-2 s.

const Eigen::Vector3d kStiffRates(1.0, 1e3, 1e6);
constexpr double kStiffStep = 1e-2;

OdeProblem StiffLinear(double forcing) {
  OdeProblem problem;
  problem.size = 3;
  problem.rhs = [forcing](double t, Ref<const VectorXd> y, Ref<VectorXd> ydot) {
    ydot = -kStiffRates.cwiseProduct(y - VectorXd::Constant(3, forcing * std::sin(t)));
  };
  return problem;
}

/// The exact solution with forcing 1 from y(0) = 1: the slow particular solution
/// lambda (lambda sin t - cos t) / (lambda^2 + 1) plus a transient that decays as exp(-lambda t).
VectorXd StiffLinearSolution(double t) {
  VectorXd y(3);
  for (int i = 0; i < 3; ++i) {
    const double l = kStiffRates(i);
    y(i) = l * (l * std::sin(t) - std::cos(t)) / (l * l + 1.0) +
           (1.0 + l / (l * l + 1.0)) * std::exp(-l * t);
  }
  return y;
}

/// The stability function R(z) = 1 + z b^T (I - z A)^-1 1 of a Butcher table (Hairer & Wanner
/// II, IV.3): one step of y' = lambda y multiplies y by R(h lambda).
double StabilityFunction(ARKodeButcherTable table, double z) {
  const int s = table->stages;
  Eigen::MatrixXd A(s, s);
  VectorXd b(s);
  for (int i = 0; i < s; ++i) {
    b(i) = table->b[i];
    for (int j = 0; j < s; ++j) A(i, j) = table->A[i][j];
  }
  const Eigen::MatrixXd I_minus_zA = Eigen::MatrixXd::Identity(s, s) - z * A;
  return 1.0 + z * b.dot(I_minus_zA.partialPivLu().solve(VectorXd::Ones(s)));
}

double EsdirkStabilityFunction(double z) {
  ARKodeButcherTable table = ARKodeButcherTable_LoadDIRK(ARKODE_ARK436L2SA_DIRK_6_3_4);
  const double r = StabilityFunction(table, z);
  ARKodeButcherTable_Free(table);
  return r;
}

double DormandPrinceStabilityFunction(double z) {
  ARKodeButcherTable table = ARKodeButcherTable_LoadERK(ARKODE_DORMAND_PRINCE_7_4_5);
  const double r = StabilityFunction(table, z);
  ARKodeButcherTable_Free(table);
  return r;
}

OdeOptions ImplicitFixedStep() {
  OdeOptions options;
  options.method = OdeMethod::kImplicit;
  options.fixed_step = kStiffStep;
  options.relative_tolerance = 1e-10;  // Newton's: the linear stage equations solved to ~1e-11
  options.absolute_tolerance = 1e-12;
  return options;
}

TEST(StiffLinear, ImplicitStepDampsStiffComponentsAsLStabilityPromises) {
  OdeIntegrator integrator(StiffLinear(0.0), ImplicitFixedStep(), 0.0, VectorXd::Ones(3));
  ASSERT_EQ(integrator.Advance(kStiffStep), OdeStop::kReachedTime);
  // One step multiplies each component by R(h lambda), from the method's own Butcher table.
  // The Newton tolerance (rtol 1e-10 on |y| <= 1) bounds the difference.
  constexpr double kNewtonTolerance = 1e-10;
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(integrator.state()(i), EsdirkStabilityFunction(-kStiffStep * kStiffRates(i)),
                kNewtonTolerance)
        << "component " << i;
  }
  // L-stability: R(z) -> 0 as z -> -inf, here R(-1e4) = 9.3e-4 ~ 9.3 / |z|: the 1e6 component
  // is damped to below 1e-3 in one step (an A-stable rule without it, the trapezoidal rule,
  // keeps |R(-1e4)| = 0.9996: no damping).
  EXPECT_LT(std::abs(integrator.state()(2)), 1e-3);
  std::printf("  implicit, one step h = 1e-2: y = %.4e %.4e %.4e (exp(-h lambda) = %.4e %.4e 0)\n",
              integrator.state()(0), integrator.state()(1), integrator.state()(2), std::exp(-1e-2),
              std::exp(-10.0));
}

TEST(StiffLinear, ImplicitFixedStepFollowsTheSlowSolution) {
  OdeIntegrator integrator(StiffLinear(1.0), ImplicitFixedStep(), 0.0, VectorXd::Ones(3));
  double error = 0.0;
  for (int k = 1; k <= 100; ++k) {
    ASSERT_EQ(integrator.Advance(k * kStiffStep), OdeStop::kReachedTime);
    ASSERT_TRUE(integrator.state().allFinite());
    // The transients are not resolved at h lambda = 10 and 1e4; they are damped by
    // |R(-10)| = 0.137 and |R(-1e4)| = 9.3e-4 per step: below 1e-21 after 25 steps.
    if (k >= 25) {
      const VectorXd exact = StiffLinearSolution(integrator.time());
      error = std::max(error, (integrator.state() - exact).cwiseAbs().maxCoeff());
    }
  }
  std::printf("  implicit, forced, h = 1e-2, t in [0.25, 1]: error %.2e\n", error);
  // Fourth order on a solution with unit-size derivatives: error ~ h^4 = 1e-8.
  EXPECT_LE(error, std::pow(kStiffStep, 4));
}

TEST(StiffLinear, AnalyticJacobianGivesTheSameSolutionWithoutDifferenceQuotients) {
  OdeProblem with_jacobian = StiffLinear(1.0);
  int jacobian_calls = 0;
  with_jacobian.jacobian = [&jacobian_calls](double, Ref<const VectorXd>,
                                             Ref<Eigen::MatrixXd> dfdy) {
    ++jacobian_calls;
    dfdy.diagonal() = -kStiffRates;
  };
  OdeIntegrator analytic(std::move(with_jacobian), ImplicitFixedStep(), 0.0, VectorXd::Ones(3));
  OdeIntegrator quotients(StiffLinear(1.0), ImplicitFixedStep(), 0.0, VectorXd::Ones(3));
  analytic.Advance(1.0);
  quotients.Advance(1.0);
  // Both solve the same linear stage equations to the Newton tolerance.
  EXPECT_LE((analytic.state() - quotients.state()).cwiseAbs().maxCoeff(), 1e-10);
  const OdeStatistics a = analytic.statistics();
  const OdeStatistics q = quotients.statistics();
  EXPECT_EQ(jacobian_calls, a.jacobian_evaluations);
  EXPECT_GE(a.jacobian_evaluations, 1);
  // The rhs calls differ by one per Newton iteration (a residual each; the quotients' round-off
  // changes how many the convergence test asks for) and one per column (3) per quotient Jacobian.
  EXPECT_EQ(q.rhs_evaluations - a.rhs_evaluations,
            (q.newton_iterations - a.newton_iterations) + 3 * q.jacobian_evaluations);
}

TEST(StiffLinear, ExplicitFixedStepBlowsUpAndIsRefused) {
  OdeOptions options;
  options.fixed_step = kStiffStep;
  OdeIntegrator integrator(StiffLinear(0.0), options, 0.0, VectorXd::Ones(3));
  // |R(-1e4)| = 1.7e21 per step for Dormand-Prince: the 1e6 component overflows after
  // log(DBL_MAX) / log|R| = 14.5 steps; a stage may overflow one step earlier.
  const double growth = std::abs(DormandPrinceStabilityFunction(-kStiffStep * kStiffRates(2)));
  const double overflow_time =
      std::ceil(std::log(std::numeric_limits<double>::max()) / std::log(growth)) * kStiffStep;
  try {
    integrator.Advance(1.0);
    ADD_FAILURE() << "no error; y = " << integrator.state().transpose();
  } catch (const SimulationError& e) {
    std::printf("  explicit, h = 1e-2: %s\n", e.what());
    EXPECT_NE(std::string(e.what()).find("not finite"), std::string::npos) << e.what();
    EXPECT_GE(e.time(), overflow_time - kStiffStep * (1 + 1e-9));
    EXPECT_LE(e.time(), overflow_time + kStiffStep * 1e-9);
    EXPECT_EQ(integrator.time(), 0.0);  // the last good pair: the start
    EXPECT_EQ(integrator.state(), VectorXd::Ones(3));
  }
}

TEST(StiffLinear, ExplicitAdaptiveStepIsHeldAtTheStabilityLimit) {
  OdeOptions options;
  options.max_steps_per_call = 2000;
  OdeIntegrator integrator(StiffLinear(0.0), options, 0.0, VectorXd::Ones(3));
  try {
    integrator.Advance(1.0);
    ADD_FAILURE() << "no error";
  } catch (const SimulationError& e) {
    std::printf("  explicit, adaptive: %s\n", e.what());
    EXPECT_NE(std::string(e.what()).find("ARK_TOO_MUCH_WORK"), std::string::npos) << e.what();
    // Dormand-Prince's real stability interval is about [-3.3, 0]: steps near 3.3e-6 s, so
    // 2000 of them end near 6.6e-3 s (1e-2 leaves room for the error controller's overshoot).
    EXPECT_LT(e.time(), 1e-2);
  }
}

// ---------------------------------------------------------------------------------------------
// Events: a ball falling from height h0 reaches z = 0 at sqrt(2 h0 / g).

constexpr double kGravity = 9.81;    // [m/s^2]
constexpr double kDropHeight = 1.0;  // [m]

TEST_P(BothMethods, BallHitsTheGroundAndBouncesBack) {
  OdeProblem problem;
  problem.size = 2;  // z [m], v [m/s]
  problem.rhs = [](double, Ref<const VectorXd> y, Ref<VectorXd> ydot) {
    ydot(0) = y(1);
    ydot(1) = -kGravity;
  };
  problem.num_events = 1;
  problem.events = [](double, Ref<const VectorXd> y, Ref<VectorXd> g) { g(0) = y(0); };
  OdeOptions options;
  options.method = GetParam();
  options.relative_tolerance = 1e-10;
  options.absolute_tolerance = 1e-12;
  OdeIntegrator integrator(std::move(problem), options, 0.0, VectorXd::Unit(2, 0) * kDropHeight);

  // Both methods integrate this quadratic exactly; ARKODE locates the root to ~100 eps t.
  constexpr double kTimeTolerance = 1e-10;  // relative
  const double t_impact = std::sqrt(2.0 * kDropHeight / kGravity);
  ASSERT_EQ(integrator.Advance(10.0), OdeStop::kEvent);
  EXPECT_NEAR(integrator.time(), t_impact, kTimeTolerance * t_impact);
  EXPECT_EQ(integrator.event_directions(), std::vector<int>{-1});
  EXPECT_NEAR(integrator.state()(0), 0.0, 1e-10);
  EXPECT_NEAR(integrator.state()(1), -kGravity * t_impact, 1e-9);

  // An elastic bounce: reversed velocity. The event function is zero at the restart and
  // must not fire again there.
  VectorXd bounced(2);
  bounced << 0.0, -integrator.state()(1);
  integrator.Reset(integrator.time(), bounced);
  ASSERT_EQ(integrator.Advance(2.0 * t_impact), OdeStop::kReachedTime);
  EXPECT_NEAR(integrator.state()(0), kDropHeight, 1e-9);  // the apex
  EXPECT_NEAR(integrator.state()(1), 0.0, 1e-9);
  ASSERT_EQ(integrator.Advance(10.0), OdeStop::kEvent);
  EXPECT_NEAR(integrator.time(), 3.0 * t_impact, kTimeTolerance * t_impact);
  EXPECT_EQ(integrator.event_directions(), std::vector<int>{-1});
  std::printf("  %s: impacts at %.15f s and %.15f s (exact %.15f, %.15f)\n",
              Name(GetParam()).c_str(), t_impact, integrator.time(), t_impact, 3.0 * t_impact);
}

// ---------------------------------------------------------------------------------------------
// Projection: a point rotating on the unit circle, explicit method at a loose tolerance.

struct CircleRun {
  double largest_drift = 0.0;  ///< max | |y| - 1 | over the outputs
  long projections = 0;
  long steps = 0;
};

CircleRun RotatingPoint(bool project) {
  OdeProblem problem;
  problem.size = 2;
  problem.rhs = [](double, Ref<const VectorXd> y, Ref<VectorXd> ydot) {
    ydot(0) = -y(1);
    ydot(1) = y(0);
  };
  CircleRun run;
  if (project) {
    problem.project = [&run](double, Ref<VectorXd> y) {
      ++run.projections;
      y.normalize();
    };
  }
  OdeOptions options;
  options.relative_tolerance = 1e-3;
  options.absolute_tolerance = 1e-6;
  OdeIntegrator integrator(std::move(problem), options, 0.0, VectorXd::Unit(2, 0));
  const int outputs = 100;
  for (int k = 1; k <= outputs; ++k) {
    integrator.Advance(k * 1.0);
    run.largest_drift = std::max(run.largest_drift, std::abs(integrator.state().norm() - 1.0));
  }
  run.steps = integrator.statistics().steps;
  if (project) {
    EXPECT_EQ(run.projections, run.steps + outputs) << "one per accepted step, one per output";
  }
  return run;
}

TEST(Projection, KeepsThePointOnTheCircle) {
  const CircleRun free = RotatingPoint(false);
  const CircleRun projected = RotatingPoint(true);
  std::printf("  explicit, rtol 1e-3, t = 100 s: | |y| - 1 | up to %.2e free, %.2e projected\n",
              free.largest_drift, projected.largest_drift);
  EXPECT_LE(projected.largest_drift, 4.0 * kEps);  // normalize() round-off
  EXPECT_GT(free.largest_drift, 1e-4);             // the tolerance lets the radius drift
}

// ---------------------------------------------------------------------------------------------
// Statistics and errors.

TEST(Statistics, ArePlausible) {
  const double w = 2.0 * std::numbers::pi;
  OdeOptions options;
  OdeIntegrator explicit_integrator(HarmonicOscillator(w), options, 0.0, VectorXd::Unit(2, 0));
  explicit_integrator.Advance(1.0);
  const OdeStatistics e = explicit_integrator.statistics();
  // Dormand-Prince: 7 stages, the last reused as the next step's first: 6 rhs calls per step
  // attempt, plus a few for the initial step estimate.
  const long attempts = e.steps + e.error_test_failures;
  EXPECT_GT(e.steps, 0);
  EXPECT_GE(e.rhs_evaluations, 6 * attempts);
  EXPECT_LE(e.rhs_evaluations, 7 * attempts + 10);
  EXPECT_EQ(e.newton_iterations, 0);
  EXPECT_EQ(e.jacobian_evaluations, 0);

  options.method = OdeMethod::kImplicit;
  OdeIntegrator implicit_integrator(HarmonicOscillator(w), options, 0.0, VectorXd::Unit(2, 0));
  implicit_integrator.Advance(1.0);
  const OdeStatistics i = implicit_integrator.statistics();
  std::printf(
      "  one period at rtol 1e-6: explicit %ld steps, %ld rhs; implicit %ld steps, %ld rhs, %ld "
      "Newton "
      "iterations, %ld Jacobians\n",
      e.steps, e.rhs_evaluations, i.steps, i.rhs_evaluations, i.newton_iterations,
      i.jacobian_evaluations);
  EXPECT_GT(i.steps, 0);
  EXPECT_GE(i.newton_iterations, 5 * i.steps);  // 5 implicit stages, at least one iteration each
  EXPECT_GE(i.rhs_evaluations, i.newton_iterations + i.steps);  // a residual per iteration
  EXPECT_GE(i.jacobian_evaluations, 1);
  EXPECT_LE(i.jacobian_evaluations, i.steps);
  // Reset keeps counting.
  implicit_integrator.Reset(1.0, VectorXd::Unit(2, 0));
  implicit_integrator.Advance(1.5);
  EXPECT_GT(implicit_integrator.statistics().steps, i.steps);
}

TEST(Options, BadOnesGiveOneLineErrors) {
  const auto message = [](auto change) {
    OdeOptions options;
    change(options);
    return testing::InputErrorMessage(
        [&] { OdeIntegrator(HarmonicOscillator(1.0), options, 0.0, VectorXd::Unit(2, 0)); });
  };
  EXPECT_EQ(message([](OdeOptions& o) { o.relative_tolerance = 0.0; }),
            "integrator option relative_tolerance = 0 must be finite and > 0");
  EXPECT_EQ(message([](OdeOptions& o) { o.absolute_tolerance = -1e-9; }),
            "integrator option absolute_tolerance = -1e-09 must be finite and > 0");
  EXPECT_EQ(message([](OdeOptions& o) { o.initial_step = -1.0; }),
            "integrator option initial_step = -1 must be finite and >= 0 (0: chosen by ARKODE)");
  EXPECT_EQ(message([](OdeOptions& o) { o.max_step = std::numeric_limits<double>::infinity(); }),
            "integrator option max_step = inf must be finite and >= 0 (0: unlimited)");
  EXPECT_EQ(message([](OdeOptions& o) { o.fixed_step = std::nan(""); }),
            "integrator option fixed_step = nan must be finite and >= 0 (0: adaptive)");
  EXPECT_EQ(
      message([](OdeOptions& o) {
        o.fixed_step = 1e-3;
        o.max_step = 1e-2;
      }),
      "integrator option fixed_step = 0.001 excludes initial_step and max_step (leave them 0)");
  EXPECT_EQ(message([](OdeOptions& o) { o.max_steps_per_call = 0; }),
            "integrator option max_steps_per_call = 0 must be > 0");
}

TEST(Callbacks, AnExceptionFromTheModelLeavesAdvanceUnchanged) {
  OdeProblem problem = HarmonicOscillator(1.0);
  problem.rhs = [](double t, Ref<const VectorXd> y, Ref<VectorXd> ydot) {
    if (t > 0.5) throw std::domain_error("model undefined after 0.5 s");
    ydot << y(1), -y(0);
  };
  OdeIntegrator integrator(std::move(problem), OdeOptions{}, 0.0, VectorXd::Unit(2, 0));
  ASSERT_EQ(integrator.Advance(0.25), OdeStop::kReachedTime);
  const VectorXd state_at_quarter = integrator.state();
  EXPECT_NEAR(state_at_quarter(0), std::cos(0.25), 1e-5);
  try {
    integrator.Advance(1.0);
    ADD_FAILURE() << "no error";
  } catch (const std::domain_error& e) {
    EXPECT_STREQ(e.what(), "model undefined after 0.5 s");
  }
  // The last good pair stays; ARKODE stopped cleanly, so a restart works.
  EXPECT_EQ(integrator.time(), 0.25);
  EXPECT_EQ(integrator.state(), state_at_quarter);
  integrator.Reset(0.0, VectorXd::Unit(2, 0));
  EXPECT_EQ(integrator.Advance(0.25), OdeStop::kReachedTime);
  EXPECT_LE((integrator.state() - state_at_quarter).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_THROW(integrator.Advance(0.1), InternalError);  // backwards is a caller's bug
}

}  // namespace
}  // namespace flexmbs::mbs
