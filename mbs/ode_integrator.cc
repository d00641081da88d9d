#include "mbs/ode_integrator.h"

#include <arkode/arkode_arkstep.h>
#include <arkode/arkode_erkstep.h>
#include <fmt/format.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <limits>
#include <new>
#include <string>
#include <utility>

#include "core/error.h"
#include "mbs/simulation_error.h"

namespace flexmbs::mbs {
namespace {

/// The calls that ERKStep and ARKStep both have, under their two names.
struct StepperApi {
  int (*set_user_data)(void*, void*);
  int (*set_err_handler)(void*, ARKErrHandlerFn, void*);
  int (*set_tolerances)(void*, realtype, realtype);
  int (*set_max_num_steps)(void*, long);
  int (*set_init_step)(void*, realtype);
  int (*set_max_step)(void*, realtype);
  int (*set_fixed_step)(void*, realtype);
  int (*set_postprocess_step)(void*, ARKPostProcessFn);
  int (*root_init)(void*, int, ARKRootFn);
  int (*set_no_inactive_root_warn)(void*);
  int (*evolve)(void*, realtype, N_Vector, realtype*, int);
  int (*get_root_info)(void*, int*);
  int (*reset)(void*, realtype, N_Vector);
  int (*get_num_steps)(void*, long*);
  int (*get_num_err_test_fails)(void*, long*);
  char* (*flag_name)(long);
  void (*free)(void**);
};

constexpr StepperApi kErkStep{&ERKStepSetUserData,
                              &ERKStepSetErrHandlerFn,
                              &ERKStepSStolerances,
                              &ERKStepSetMaxNumSteps,
                              &ERKStepSetInitStep,
                              &ERKStepSetMaxStep,
                              &ERKStepSetFixedStep,
                              &ERKStepSetPostprocessStepFn,
                              &ERKStepRootInit,
                              &ERKStepSetNoInactiveRootWarn,
                              &ERKStepEvolve,
                              &ERKStepGetRootInfo,
                              &ERKStepReset,
                              &ERKStepGetNumSteps,
                              &ERKStepGetNumErrTestFails,
                              &ERKStepGetReturnFlagName,
                              &ERKStepFree};

constexpr StepperApi kArkStep{&ARKStepSetUserData,
                              &ARKStepSetErrHandlerFn,
                              &ARKStepSStolerances,
                              &ARKStepSetMaxNumSteps,
                              &ARKStepSetInitStep,
                              &ARKStepSetMaxStep,
                              &ARKStepSetFixedStep,
                              &ARKStepSetPostprocessStepFn,
                              &ARKStepRootInit,
                              &ARKStepSetNoInactiveRootWarn,
                              &ARKStepEvolve,
                              &ARKStepGetRootInfo,
                              &ARKStepReset,
                              &ARKStepGetNumSteps,
                              &ARKStepGetNumErrTestFails,
                              &ARKStepGetReturnFlagName,
                              &ARKStepFree};

/// ARKODE's name of the return `flag` (its GetReturnFlagName mallocs the string: the caller
/// frees it).
std::string FlagName(const StepperApi& api, long flag) {
  char* name = api.flag_name(flag);
  std::string out = name != nullptr ? name : "unknown flag";
  std::free(name);
  return out;
}

/// Relative change of ARKODE's gamma = h a_ii beyond which the Newton matrix is refactored:
/// any change but round-off (ARKODE refuses 0).
constexpr double kDeltaGammaMax = 1e-12;

/// Newton iterations per stage with a fixed step (ARKODE's default, 3, suits adaptive steps,
/// which are cut when Newton fails; its modified Newton converges linearly).
constexpr int kFixedStepNewtonIterations = 10;

/// A view of a serial N_Vector's storage.
Eigen::Map<Eigen::VectorXd> View(N_Vector v) {
  return {N_VGetArrayPointer(v), static_cast<Eigen::Index>(N_VGetLength(v))};
}

/// Throws InputError unless `ok`: "integrator option <name> = <value> <requirement>".
void RequireOption(bool ok, std::string_view name, double value, std::string_view requirement) {
  if (!ok) throw InputError(fmt::format("integrator option {} = {} {}", name, value, requirement));
}

void ValidateOptions(const OdeOptions& options) {
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  const auto non_negative = [](double v) { return std::isfinite(v) && v >= 0.0; };
  RequireOption(positive(options.relative_tolerance), "relative_tolerance",
                options.relative_tolerance, "must be finite and > 0");
  RequireOption(positive(options.absolute_tolerance), "absolute_tolerance",
                options.absolute_tolerance, "must be finite and > 0");
  RequireOption(non_negative(options.initial_step), "initial_step", options.initial_step,
                "must be finite and >= 0 (0: chosen by ARKODE)");
  RequireOption(non_negative(options.max_step), "max_step", options.max_step,
                "must be finite and >= 0 (0: unlimited)");
  RequireOption(non_negative(options.fixed_step), "fixed_step", options.fixed_step,
                "must be finite and >= 0 (0: adaptive)");
  RequireOption(
      options.fixed_step == 0.0 || (options.initial_step == 0.0 && options.max_step == 0.0),
      "fixed_step", options.fixed_step, "excludes initial_step and max_step (leave them 0)");
  RequireOption(options.max_steps_per_call > 0, "max_steps_per_call",
                static_cast<double>(options.max_steps_per_call), "must be > 0");
}

/// The SUNMatrix of the Newton matrix when an OdeNewtonSolver holds it (OdeNewton::kSparse): it
/// stands for jacobian J + identity I, J the solver's last evaluated Jacobian, the only one there
/// is (ARKODE's saved copy of J, from which it restores A before scaling it, is that J too).
/// ARKODE's operations on it: zero, copy, J from the Jacobian function (1, 0), and
/// SUNMatScaleAddI(-gamma) before its linear solver's setup (-gamma, 1): A = I - gamma J.
struct NewtonMatrix {
  double jacobian = 0.0, identity = 0.0;
};

NewtonMatrix& NewtonMatrixOf(SUNMatrix A) { return *static_cast<NewtonMatrix*>(A->content); }

SUNMatrix NewNewtonMatrix(SUNContext context);

SUNMatrix_ID NewtonMatrixId(SUNMatrix /*A*/) { return SUNMATRIX_CUSTOM; }
SUNMatrix NewtonMatrixClone(SUNMatrix A) { return NewNewtonMatrix(A->sunctx); }
void NewtonMatrixDestroy(SUNMatrix A) {
  delete static_cast<NewtonMatrix*>(A->content);
  A->content = nullptr;
  SUNMatFreeEmpty(A);
}
int NewtonMatrixZero(SUNMatrix A) {
  NewtonMatrixOf(A) = {};
  return SUNMAT_SUCCESS;
}
int NewtonMatrixCopy(SUNMatrix from, SUNMatrix to) {
  NewtonMatrixOf(to) = NewtonMatrixOf(from);
  return SUNMAT_SUCCESS;
}
/// A = c A + I.
int NewtonMatrixScaleAddI(realtype c, SUNMatrix A) {
  NewtonMatrix& newton = NewtonMatrixOf(A);
  newton = {c * newton.jacobian, c * newton.identity + 1.0};
  return SUNMAT_SUCCESS;
}

/// A NewtonMatrix (0 J + 0 I), or null if out of memory.
SUNMatrix NewNewtonMatrix(SUNContext context) {
  SUNMatrix A = SUNMatNewEmpty(context);
  if (A == nullptr) return nullptr;
  A->content = new (std::nothrow) NewtonMatrix;
  if (A->content == nullptr) {
    SUNMatFreeEmpty(A);
    return nullptr;
  }
  A->ops->getid = &NewtonMatrixId;
  A->ops->clone = &NewtonMatrixClone;
  A->ops->destroy = &NewtonMatrixDestroy;
  A->ops->zero = &NewtonMatrixZero;
  A->ops->copy = &NewtonMatrixCopy;
  A->ops->scaleaddi = &NewtonMatrixScaleAddI;
  return A;
}

/// Whether the implicit method hands its Newton systems to problem.newton_solver (OdeNewton);
/// throws InputError for kSparse without one or with difference quotients.
bool UsesSparseNewton(const OdeProblem& problem, const OdeOptions& options) {
  if (options.method != OdeMethod::kImplicit) return false;
  const bool model = options.jacobian == OdeJacobian::kModel;
  switch (options.newton) {
    case OdeNewton::kDense:
      return false;
    case OdeNewton::kSparse:
      if (!model) {
        throw InputError(
            "integrator option newton = sparse solves with the model Jacobian: set jacobian to model, or newton "
            "to dense for difference quotients");
      }
      if (!problem.newton_solver) {
        throw InputError("integrator option newton = sparse needs a problem with its own Newton solver");
      }
      return true;
    case OdeNewton::kAuto:
      return problem.newton_solver && model && problem.size >= kSparseNewtonFromSize;
  }
  return false;
}

}  // namespace

std::string_view OdeNewtonName(OdeNewton newton) {
  switch (newton) {
    case OdeNewton::kAuto:
      return "auto";
    case OdeNewton::kDense:
      return "dense";
    case OdeNewton::kSparse:
      return "sparse";
  }
  return "unknown";
}

std::string_view OdeJacobianName(OdeJacobian jacobian) {
  switch (jacobian) {
    case OdeJacobian::kModel:
      return "model";
    case OdeJacobian::kDifferenceQuotients:
      return "difference_quotients";
  }
  return "unknown";
}

std::string_view OdeMethodName(OdeMethod method) {
  switch (method) {
    case OdeMethod::kExplicit:
      return "explicit";
    case OdeMethod::kImplicit:
      return "implicit";
  }
  return "unknown";
}

struct OdeIntegrator::Impl {
  OdeProblem problem;
  OdeOptions options;
  const StepperApi* api = nullptr;
  SUNContext context = nullptr;
  N_Vector y = nullptr;  // wraps `state`: ARKODE writes its output there
  SUNMatrix matrix = nullptr;
  SUNLinearSolver linear_solver = nullptr;
  void* arkode = nullptr;
  double t = 0.0;
  Eigen::VectorXd state;
  std::vector<int> event_directions;
  std::exception_ptr callback_error;  // an exception from a callback, rethrown by Advance
  std::string arkode_error;           // ARKODE's last error message
  bool sparse_newton = false;         // the Newton systems go to problem.newton_solver

  ~Impl() {
    if (arkode != nullptr) api->free(&arkode);
    if (linear_solver != nullptr) SUNLinSolFree(linear_solver);
    if (matrix != nullptr) SUNMatDestroy(matrix);
    if (y != nullptr) N_VDestroy(y);
    if (context != nullptr) SUNContext_Free(&context);
  }

  /// Setup calls cannot fail on valid input: a failure is a bug here.
  void Check(int flag, std::string_view call) const {
    FLEXMBS_CHECK(flag == ARK_SUCCESS, fmt::format("{} returned {}", call, FlagName(*api, flag)));
  }

  /// Runs a user callback for ARKODE: an exception must not unwind through C, so it is kept
  /// and ARKODE is told to stop (a negative return is unrecoverable).
  template <typename Call>
  int Guard(Call&& call) {
    try {
      call();
      return 0;
    } catch (...) {
      callback_error = std::current_exception();
      return -1;
    }
  }

  /// The first step after construction or Reset: fixed, given, or estimated by ARKODE
  /// (Reset alone would keep the last step size; SetInitStep alone would end a fixed step).
  void SetFirstStep() {
    if (options.fixed_step > 0.0) {
      Check(api->set_fixed_step(arkode, options.fixed_step), "SetFixedStep");
    } else {
      Check(api->set_init_step(arkode, options.initial_step), "SetInitStep");
    }
  }

  static int Rhs(realtype t, N_Vector y, N_Vector ydot, void* data) {
    auto& self = *static_cast<Impl*>(data);
    return self.Guard([&] { self.problem.rhs(t, View(y), View(ydot)); });
  }

  static int Events(realtype t, N_Vector y, realtype* g, void* data) {
    auto& self = *static_cast<Impl*>(data);
    return self.Guard([&] {
      self.problem.events(t, View(y), Eigen::Map<Eigen::VectorXd>(g, self.problem.num_events));
    });
  }

  // After every accepted step: refuse a state that is no longer finite (an unstable fixed
  // step; adaptive steps are refused by ARKODE's error test), then project. ARKODE's dense
  // output (Advance's interpolation at t_out and at roots) then interpolates between
  // projected step states, so Advance projects its interpolated output again. With this hook
  // ARKODE re-evaluates f at the changed state: Dormand-Prince's first-same-as-last stage is
  // not reused, 7 instead of 6 rhs calls per step.
  static int PostprocessStep(realtype t, N_Vector y, void* data) {
    auto& self = *static_cast<Impl*>(data);
    return self.Guard([&] {
      auto y_view = View(y);
      if (!y_view.allFinite()) {
        throw SimulationError(t, fmt::format("integration failed at t = {} s: the state is not "
                                             "finite (a fixed step beyond the {} method's "
                                             "stability limit, or a model that broke down)",
                                             t, OdeMethodName(self.options.method)));
      }
      if (self.problem.project) self.problem.project(t, y_view);
    });
  }

  static int Jacobian(realtype t, N_Vector y, N_Vector /*fy*/, SUNMatrix dfdy, void* data,
                      N_Vector /*tmp1*/, N_Vector /*tmp2*/, N_Vector /*tmp3*/) {
    auto& self = *static_cast<Impl*>(data);
    return self.Guard([&] {
      const auto n = self.problem.size;
      self.problem.jacobian(t, View(y),
                            Eigen::Map<Eigen::MatrixXd>(SUNDenseMatrix_Data(dfdy), n, n));
    });
  }

  // OdeNewton::kSparse: problem.newton_solver as a direct linear solver of a NewtonMatrix, so
  // that ARKODE's own Newton machinery runs as for the dense LU (when to refresh the Jacobian,
  // the retry with a fresh one after a failure, the convergence-rate estimate kept from the
  // last setup, the counters). A matrix-embedded solver (SUNLINEARSOLVER_MATRIX_EMBEDDED) gets
  // none of it: ARKODE 6.4 disables lsetup for that type, so the solver would have to choose its
  // Jacobians itself, and ARKODE resets the rate to 1 at every stage: measured 28 % (a flexible
  // chain) and 66 % (stiff modes) more Newton iterations with the same dense LU behind it.
  static int NewtonJacobian(realtype t, N_Vector y, N_Vector /*fy*/, SUNMatrix J, void* data, N_Vector /*tmp1*/,
                            N_Vector /*tmp2*/, N_Vector /*tmp3*/) {
    auto& self = *static_cast<Impl*>(data);
    return self.Guard([&] {
      self.problem.newton_solver->Evaluate(t, View(y));
      NewtonMatrixOf(J) = {1.0, 0.0};
    });
  }
  static SUNLinearSolver_Type NewtonSolverType(SUNLinearSolver /*solver*/) { return SUNLINEARSOLVER_DIRECT; }
  static SUNLinearSolver_ID NewtonSolverId(SUNLinearSolver /*solver*/) { return SUNLINEARSOLVER_CUSTOM; }
  static int NewtonSetup(SUNLinearSolver solver, SUNMatrix A) {
    auto& self = *static_cast<Impl*>(solver->content);
    return self.Guard([&] {
      const NewtonMatrix& newton = NewtonMatrixOf(A);
      FLEXMBS_CHECK(newton.identity == 1.0 && newton.jacobian < 0.0,
                    fmt::format("Newton matrix {} J + {} I is not I - gamma J", newton.jacobian, newton.identity));
      self.problem.newton_solver->Factorize(-newton.jacobian);
    });
  }
  static int NewtonSolve(SUNLinearSolver solver, SUNMatrix /*A*/, N_Vector x, N_Vector b, realtype /*tol*/) {
    auto& self = *static_cast<Impl*>(solver->content);
    return self.Guard([&] {
      auto x_view = View(x);
      x_view = View(b);
      self.problem.newton_solver->Solve(x_view);
    });
  }
  // The content is the Impl, not owned: free the shell only (SUNLinSolFree would free content).
  static int NewtonSolverFree(SUNLinearSolver solver) {
    SUNLinSolFreeEmpty(solver);
    return SUNLS_SUCCESS;
  }

  static void KeepError(int code, const char* /*module*/, const char* function, char* message,
                        void* data) {
    if (code < 0) static_cast<Impl*>(data)->arkode_error = fmt::format("{}: {}", function, message);
  }

  // Constructor steps. The SUNDIALS context, the state vector y over `state` and ERKStep
  // (Dormand-Prince 7(4)5) or ARKStep (the ARK4(3)6L[2]SA DIRK table alone) at t0.
  void CreateStepper(double t0) {
    FLEXMBS_CHECK(SUNContext_Create(nullptr, &context) == 0, "SUNContext_Create failed");
    y = N_VMake_Serial(problem.size, state.data(), context);
    FLEXMBS_CHECK(y != nullptr, "N_VMake_Serial failed");
    if (options.method == OdeMethod::kExplicit) {
      arkode = ERKStepCreate(&Impl::Rhs, t0, y, context);
      FLEXMBS_CHECK(arkode != nullptr, "ERKStepCreate failed");
      Check(ERKStepSetTableNum(arkode, ARKODE_DORMAND_PRINCE_7_4_5), "ERKStepSetTableNum");
      return;
    }
    // Implicit only: no explicit right-hand side, the DIRK table alone.
    arkode = ARKStepCreate(nullptr, &Impl::Rhs, t0, y, context);
    FLEXMBS_CHECK(arkode != nullptr, "ARKStepCreate failed");
    Check(ARKStepSetTableNum(arkode, ARKODE_ARK436L2SA_DIRK_6_3_4, ARKODE_ERK_NONE), "ARKStepSetTableNum");
  }

  // The implicit method's Newton solver: problem.newton_solver behind ARKODE's Newton
  // (OdeNewton::kSparse), else dense LU; then its settings.
  void AttachNewton() {
    sparse_newton = UsesSparseNewton(problem, options);
    if (sparse_newton) {
      matrix = NewNewtonMatrix(context);
      linear_solver = SUNLinSolNewEmpty(context);
      FLEXMBS_CHECK(matrix != nullptr && linear_solver != nullptr, "Newton solver not created");
      linear_solver->content = this;
      linear_solver->ops->gettype = &Impl::NewtonSolverType;
      linear_solver->ops->getid = &Impl::NewtonSolverId;
      linear_solver->ops->setup = &Impl::NewtonSetup;
      linear_solver->ops->solve = &Impl::NewtonSolve;
      linear_solver->ops->free = &Impl::NewtonSolverFree;
      Check(ARKStepSetLinearSolver(arkode, linear_solver, matrix), "ARKStepSetLinearSolver");
      Check(ARKStepSetJacFn(arkode, &Impl::NewtonJacobian), "ARKStepSetJacFn");
    } else {
      // Newton on the stage equations with dense LU of I - gamma h df/dy. Without
      // problem.jacobian (or with OdeJacobian::kDifferenceQuotients) ARKODE forms df/dy by
      // difference quotients (arkLsDQJac: one rhs call per column); an analytic Jacobian goes
      // through ARKStepSetJacFn (any ARKLsJacFn filling the dense SUNMatrix column-major).
      matrix = SUNDenseMatrix(problem.size, problem.size, context);
      linear_solver = SUNLinSol_Dense(y, matrix, context);
      FLEXMBS_CHECK(matrix != nullptr && linear_solver != nullptr,
                    "dense linear solver not created");
      Check(ARKStepSetLinearSolver(arkode, linear_solver, matrix), "ARKStepSetLinearSolver");
      if (problem.jacobian && options.jacobian == OdeJacobian::kModel) {
        Check(ARKStepSetJacFn(arkode, &Impl::Jacobian), "ARKStepSetJacFn");
      }
    }
    // Refactor I - gamma h df/dy whenever gamma changes. ARKODE's default (only beyond a 20 %
    // change) keeps a stale matrix while its Newton test judges the first iterate with the
    // convergence rate of an earlier solve (reset only by a refactorisation): after exact
    // solves (a linear problem) that rate is tiny, the first iterate is accepted, and the
    // stage error is (change of gamma) x (correction), 1e5 x the tolerance on an oscillator.
    Check(ARKStepSetDeltaGammaMax(arkode, kDeltaGammaMax), "ARKStepSetDeltaGammaMax");
    // A fixed step cannot be cut when Newton stalls: give it more iterations.
    if (options.fixed_step > 0.0) {
      Check(ARKStepSetMaxNonlinIters(arkode, kFixedStepNewtonIterations), "ARKStepSetMaxNonlinIters");
    }
    // ARKODE's Hermite dense output uses f at the step ends, which amplifies errors in stiff
    // components by their large Lipschitz constant; its Lagrange module is meant for stiff
    // problems.
    Check(ARKStepSetInterpolantType(arkode, ARK_INTERP_LAGRANGE), "ARKStepSetInterpolantType");
  }

  // The settings of either method: user data, error handler, tolerances, step limits, the
  // post-processing of steps (projection, the fixed step's finiteness check) and the events.
  void ConfigureCommon() {
    Check(api->set_user_data(arkode, this), "SetUserData");
    Check(api->set_err_handler(arkode, &Impl::KeepError, this), "SetErrHandlerFn");
    Check(api->set_tolerances(arkode, options.relative_tolerance, options.absolute_tolerance), "SStolerances");
    Check(api->set_max_num_steps(arkode, options.max_steps_per_call), "SetMaxNumSteps");
    Check(api->set_max_step(arkode, options.max_step), "SetMaxStep");
    SetFirstStep();
    if (problem.project || options.fixed_step > 0.0) {
      Check(api->set_postprocess_step(arkode, &Impl::PostprocessStep), "SetPostprocessStepFn");
    }
    if (problem.num_events > 0) {
      Check(api->root_init(arkode, problem.num_events, &Impl::Events), "RootInit");
      // An event function that is zero at the start (a contact that just closed) is normal.
      Check(api->set_no_inactive_root_warn(arkode), "SetNoInactiveRootWarn");
    }
  }
};

OdeIntegrator::OdeIntegrator(OdeProblem problem, const OdeOptions& options, double t0,
                             const Eigen::VectorXd& y0)
    : impl_(std::make_unique<Impl>()) {
  ValidateOptions(options);
  FLEXMBS_CHECK(problem.size > 0 && y0.size() == problem.size && problem.rhs,
                fmt::format("ODE problem of size {} with y0 of size {}", problem.size, y0.size()));
  FLEXMBS_CHECK(problem.num_events >= 0 && (problem.num_events == 0 || problem.events),
                "ODE problem: num_events without an event function");
  FLEXMBS_CHECK(std::isfinite(t0) && y0.allFinite(), "ODE problem: initial state not finite");
  Impl& m = *impl_;
  m.problem = std::move(problem);
  m.options = options;
  m.api = options.method == OdeMethod::kExplicit ? &kErkStep : &kArkStep;
  m.t = t0;
  m.state = y0;
  m.event_directions.assign(static_cast<std::size_t>(m.problem.num_events), 0);

  m.CreateStepper(t0);
  if (options.method != OdeMethod::kExplicit) m.AttachNewton();
  m.ConfigureCommon();
}

OdeIntegrator::~OdeIntegrator() = default;

OdeStop OdeIntegrator::Advance(double t_out) {
  Impl& m = *impl_;
  FLEXMBS_CHECK(std::isfinite(t_out) && t_out >= m.t,
                fmt::format("integrator asked to go from t = {} s back to t = {} s", m.t, t_out));
  std::fill(m.event_directions.begin(), m.event_directions.end(), 0);
  // ARKODE refuses a first tout within round-off of t0 (ARK_TOO_CLOSE): nothing to do anyway.
  if (t_out - m.t <=
      4.0 * std::numeric_limits<double>::epsilon() * std::max(std::abs(m.t), std::abs(t_out))) {
    m.t = t_out;
    return OdeStop::kReachedTime;
  }
  m.arkode_error.clear();
  const Eigen::VectorXd last_state = m.state;
  try {
    double t_reached = m.t;
    const int flag = m.api->evolve(m.arkode, t_out, m.y, &t_reached, ARK_NORMAL);
    if (m.callback_error) std::rethrow_exception(std::exchange(m.callback_error, nullptr));
    if (flag < 0) {
      throw SimulationError(t_reached,
                            fmt::format("integration failed at t = {} s: {} ({})", t_reached,
                                        FlagName(*m.api, flag), m.arkode_error));
    }
    if (m.problem.project) m.problem.project(t_reached, m.state);
    m.t = t_reached;
    if (flag != ARK_ROOT_RETURN) return OdeStop::kReachedTime;
    m.Check(m.api->get_root_info(m.arkode, m.event_directions.data()), "GetRootInfo");
    return OdeStop::kEvent;
  } catch (...) {
    // time() and state() stay the last good pair. Copied into the same buffer: m.y wraps it.
    m.state = last_state;
    throw;
  }
}

const std::vector<int>& OdeIntegrator::event_directions() const { return impl_->event_directions; }

void OdeIntegrator::Reset(double t, const Eigen::VectorXd& y) {
  Impl& m = *impl_;
  FLEXMBS_CHECK(y.size() == m.problem.size && std::isfinite(t) && y.allFinite(),
                fmt::format("integrator reset with a state of size {} (expected {}) or not finite",
                            y.size(), m.problem.size));
  m.state = y;  // same size: no reallocation, m.y still wraps it
  m.Check(m.api->reset(m.arkode, t, m.y), "Reset");
  m.SetFirstStep();
  m.t = t;
  std::fill(m.event_directions.begin(), m.event_directions.end(), 0);
}

double OdeIntegrator::time() const { return impl_->t; }

const Eigen::VectorXd& OdeIntegrator::state() const { return impl_->state; }

// ARKODE's counters: Reset keeps them.
OdeStatistics OdeIntegrator::statistics() const {
  const Impl& m = *impl_;
  OdeStatistics s;
  m.Check(m.api->get_num_steps(m.arkode, &s.steps), "GetNumSteps");
  m.Check(m.api->get_num_err_test_fails(m.arkode, &s.error_test_failures), "GetNumErrTestFails");
  if (m.options.method == OdeMethod::kExplicit) {
    m.Check(ERKStepGetNumRhsEvals(m.arkode, &s.rhs_evaluations), "ERKStepGetNumRhsEvals");
    return s;
  }
  long explicit_evaluations = 0;
  long implicit_evaluations = 0;
  long jacobian_quotient_evaluations = 0;
  m.Check(ARKStepGetNumRhsEvals(m.arkode, &explicit_evaluations, &implicit_evaluations),
          "ARKStepGetNumRhsEvals");
  m.Check(ARKStepGetNumLinRhsEvals(m.arkode, &jacobian_quotient_evaluations),
          "ARKStepGetNumLinRhsEvals");
  s.rhs_evaluations = explicit_evaluations + implicit_evaluations + jacobian_quotient_evaluations;
  m.Check(ARKStepGetNumNonlinSolvIters(m.arkode, &s.newton_iterations),
          "ARKStepGetNumNonlinSolvIters");
  s.sparse_newton = m.sparse_newton;
  m.Check(ARKStepGetNumJacEvals(m.arkode, &s.jacobian_evaluations), "ARKStepGetNumJacEvals");
  m.Check(ARKStepGetNumLinSolvSetups(m.arkode, &s.newton_setups), "ARKStepGetNumLinSolvSetups");
  return s;
}

}  // namespace flexmbs::mbs
