#pragma once
// Integration of y' = f(t, y) by SUNDIALS ARKODE (docs/mbs.md, "Integrators"): an explicit
// adaptive Runge-Kutta method and an L-stable implicit one, with root functions for events and
// a projection after every accepted step. The multibody step loop drives it; it never owns the
// model.

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <string_view>
#include <vector>

namespace flexmbs::mbs {

/// The methods.
enum class OdeMethod {
  kExplicit,  ///< Dormand-Prince 5(4), ERKStep (ARKODE_DORMAND_PRINCE_7_4_5)
  kImplicit,  ///< L-stable ESDIRK order 4 (ARKODE_ARK436L2SA_DIRK_6_3_4), Newton, dense LU
};

/// "explicit" / "implicit".
std::string_view OdeMethodName(OdeMethod method);

/// The problem: y' = f(t, y), optional events g_k(t, y) (a root is an event), optional
/// projection of y after each accepted step (constraint manifolds).
struct OdeProblem {
  Eigen::Index size = 0;
  std::function<void(double t, const Eigen::VectorXd& y, Eigen::VectorXd& ydot)> rhs;
  /// Number of event functions and their values g(t, y) (size num_events).
  int num_events = 0;
  std::function<void(double t, const Eigen::VectorXd& y, Eigen::VectorXd& g)> events;
  /// Moves y onto the constraint manifold after an accepted step (may be empty).
  std::function<void(double t, Eigen::VectorXd& y)> project;
};

/// Settings.
struct OdeOptions {
  OdeMethod method = OdeMethod::kExplicit;
  double relative_tolerance = 1e-6;
  double absolute_tolerance = 1e-9;
  double initial_step = 0.0;  ///< 0: chosen by ARKODE
  double max_step = 0.0;      ///< 0: unlimited
  double fixed_step = 0.0;    ///< > 0: no adaptivity, this step (the implicit method still iterates)
  long max_steps_per_call = 100000;
};

/// Counters since the last Reset.
struct OdeStatistics {
  long steps = 0;
  long rhs_evaluations = 0;
  long error_test_failures = 0;
  long newton_iterations = 0;     ///< implicit only
  long jacobian_evaluations = 0;  ///< implicit only
};

/// Why Advance returned.
enum class OdeStop { kReachedTime, kEvent };

/// An ARKODE integrator for one OdeProblem (pimpl: no SUNDIALS header reaches users).
class OdeIntegrator {
 public:
  /// Starts at (t0, y0). Throws InputError for bad options (non-positive tolerances, ...).
  OdeIntegrator(OdeProblem problem, const OdeOptions& options, double t0, const Eigen::VectorXd& y0);
  ~OdeIntegrator();
  OdeIntegrator(const OdeIntegrator&) = delete;
  OdeIntegrator& operator=(const OdeIntegrator&) = delete;

  /// Integrates to t_out, or to the first event before it. Afterwards time() and state() give
  /// where it stopped (interpolated at t_out: steps may overshoot it). Throws InternalError
  /// naming the time and ARKODE's reason (step size too small, Newton failure, ...).
  OdeStop Advance(double t_out);
  /// After kEvent: which event functions have a root (+1 rising, -1 falling, 0 none).
  const std::vector<int>& event_directions() const;
  /// Restarts from (t, y), e.g. after an impact changed velocities; keeps the options.
  void Reset(double t, const Eigen::VectorXd& y);

  double time() const;
  const Eigen::VectorXd& state() const;
  OdeStatistics statistics() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace flexmbs::mbs
