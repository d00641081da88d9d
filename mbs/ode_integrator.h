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
  kImplicit,  ///< L-stable ESDIRK order 4 (ARKODE_ARK436L2SA_DIRK_6_3_4), Newton (OdeNewton)
};

/// "explicit" / "implicit".
std::string_view OdeMethodName(OdeMethod method);

/// A solver of the implicit method's Newton systems (I - gamma df/dy) d = r that forms and
/// factorises that matrix itself, from structure the problem knows (the multibody system's sparse
/// augmented system, mbs/kkt_newton_solver.h), instead of the dense LU of a dense df/dy. ARKODE
/// drives it as its dense direct solver: Evaluate where it would evaluate the Jacobian (the first
/// step, every 51 steps, after a Newton convergence failure), Factorize at each setup (here: every
/// change of gamma), Solve at every Newton iteration. Each may throw (as OdeProblem's callbacks).
class OdeNewtonSolver {
 public:
  virtual ~OdeNewtonSolver() = default;
  /// Evaluates and keeps df/dy (or the pieces it is made of) at (t, y).
  virtual void Evaluate(double t, Eigen::Ref<const Eigen::VectorXd> y) = 0;
  /// Factorises I - gamma df/dy with the kept Jacobian; gamma = h a_ii [s] > 0.
  virtual void Factorize(double gamma) = 0;
  /// Overwrites r (size of the state) with (I - gamma df/dy)^-1 r of the last Factorize.
  virtual void Solve(Eigen::Ref<Eigen::VectorXd> r) = 0;
};

/// The problem: y' = f(t, y), optional events g_k(t, y) (a root is an event), optional
/// projection of y after each accepted step (constraint manifolds), optional Jacobian df/dy.
/// The vectors are views of ARKODE's own storage (no copies); a callback may throw (the
/// exception propagates out of Advance unchanged, after ARKODE has stopped cleanly).
struct OdeProblem {
  Eigen::Index size = 0;
  /// ydot = f(t, y).
  std::function<void(double t, Eigen::Ref<const Eigen::VectorXd> y,
                     Eigen::Ref<Eigen::VectorXd> ydot)>
      rhs;
  /// Number of event functions and their values g(t, y) (size num_events).
  int num_events = 0;
  std::function<void(double t, Eigen::Ref<const Eigen::VectorXd> y, Eigen::Ref<Eigen::VectorXd> g)>
      events;
  /// Moves y onto the constraint manifold after an accepted step (may be empty).
  std::function<void(double t, Eigen::Ref<Eigen::VectorXd> y)> project;
  /// Implicit method only, may be empty: fills df/dy (size x size, arrives zeroed) at (t, y).
  /// Empty: ARKODE's difference quotients (one rhs call per column of df/dy).
  std::function<void(double t, Eigen::Ref<const Eigen::VectorXd> y,
                     Eigen::Ref<Eigen::MatrixXd> dfdy)>
      jacobian;
  /// Implicit method only, may be null: the problem's own Newton solver (OdeNewton::kSparse).
  std::shared_ptr<OdeNewtonSolver> newton_solver;
};

/// Where the implicit method's df/dy comes from.
enum class OdeJacobian {
  kModel,                ///< OdeProblem::jacobian (difference quotients if the problem has none)
  kDifferenceQuotients,  ///< ARKODE's difference quotients: one rhs call per column
};

/// "model" or "difference_quotients" (the scene's `simulation.jacobian` values).
std::string_view OdeJacobianName(OdeJacobian jacobian);

/// How the implicit method solves its Newton systems.
enum class OdeNewton {
  kAuto,    ///< kSparse where it is faster: a problem with a newton_solver, the model Jacobian and
            ///< size >= kSparseNewtonFromSize; kDense otherwise
  kDense,   ///< dense LU of I - gamma df/dy (SUNLinSol_Dense), df/dy per OdeJacobian
  kSparse,  ///< OdeProblem::newton_solver (as a SUNDIALS direct linear solver)
};

/// "auto", "dense" or "sparse" (the scene's `simulation.newton` values).
std::string_view OdeNewtonName(OdeNewton newton);

/// The state size from which OdeNewton::kAuto takes the problem's newton_solver: measured on the
/// flexible chain of bench_mbs_speed (bench/README.md, "Sparse Newton"), where the sparse
/// augmented solve of mbs/kkt_newton_solver.h overtakes the dense LU.
inline constexpr Eigen::Index kSparseNewtonFromSize = 40;

/// Settings.
struct OdeOptions {
  OdeMethod method = OdeMethod::kExplicit;
  OdeJacobian jacobian = OdeJacobian::kModel;  ///< implicit only
  OdeNewton newton = OdeNewton::kAuto;         ///< implicit only
  double relative_tolerance = 1e-6;
  double absolute_tolerance = 1e-9;
  double initial_step = 0.0;  ///< [s], 0: chosen by ARKODE (also after Reset)
  double max_step = 0.0;      ///< [s], 0: unlimited
  /// [s], > 0: no adaptivity, this step (excludes initial_step and max_step). The implicit
  /// method still iterates (up to 10 Newton iterations per stage: a fixed step cannot be cut).
  double fixed_step = 0.0;
  long max_steps_per_call = 100000;
};

/// Counters since construction (Reset keeps counting).
struct OdeStatistics {
  long steps = 0;
  long rhs_evaluations = 0;  ///< including the difference quotients of the Jacobian
  long error_test_failures = 0;
  long newton_iterations = 0;     ///< implicit only
  long jacobian_evaluations = 0;  ///< implicit only
  long newton_setups = 0;         ///< implicit only: factorisations of I - gamma df/dy
  bool sparse_newton = false;     ///< implicit only: the Newton systems went to OdeProblem::newton_solver
};

/// Why Advance returned.
enum class OdeStop { kReachedTime, kEvent };

/// An ARKODE integrator for one OdeProblem (pimpl: no SUNDIALS header reaches users).
class OdeIntegrator {
 public:
  /// Starts at (t0, y0). Throws InputError (one line) for bad options (non-positive
  /// tolerances, negative steps, OdeNewton::kSparse without a newton_solver or with difference
  /// quotients, ...).
  OdeIntegrator(OdeProblem problem, const OdeOptions& options, double t0,
                const Eigen::VectorXd& y0);
  ~OdeIntegrator();
  OdeIntegrator(const OdeIntegrator&) = delete;
  OdeIntegrator& operator=(const OdeIntegrator&) = delete;

  /// Integrates to t_out >= time(), or to the first event before it, and returns which.
  /// ARKODE steps on (ARK_NORMAL: steps end where the error control puts them, so f is also
  /// evaluated up to one step beyond t_out) and interpolates back: afterwards time() is t_out
  /// or the root, state() the interpolated state there. With problem.project, ARKODE's dense
  /// output interpolates between projected step states, so the interpolated state is off the
  /// manifold by the interpolation error: state() is projected once more (the integration
  /// continues from ARKODE's own step, unaffected). Throws SimulationError naming the time and
  /// ARKODE's reason (too many steps, step size too small, Newton failure, a state that is not
  /// finite, ...); time() and state() then stay those of the last successful Advance, and only
  /// Reset makes sense.
  OdeStop Advance(double t_out);
  /// After kEvent: which event functions have a root (+1 rising, -1 falling, 0 none).
  const std::vector<int>& event_directions() const;
  /// Restarts from (t, y), e.g. after an impact changed velocities; keeps the options, and
  /// the next step size is chosen anew (or is the fixed step).
  void Reset(double t, const Eigen::VectorXd& y);

  /// Where the last Advance stopped (or the start / Reset) [s], and the state there.
  double time() const;
  const Eigen::VectorXd& state() const;
  OdeStatistics statistics() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace flexmbs::mbs
