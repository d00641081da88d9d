#include "contact/complementarity/siconos_solvers.h"

#include <memory>

#include <fmt/core.h>

#include <FrictionContactProblem.h>
#include <Friction_cst.h>
#include <LCP_Solvers.h>
#include <LinearComplementarityProblem.h>
#include <NonSmoothDrivers.h>
#include <NumericsMatrix.h>
#include <SolverOptions.h>
#include <fc3d_compute_error.h>
#include <lcp_cst.h>

#include "core/error.h"

// fc2d_compute_error.h declares its neighbour with C99 'restrict', which is not C++: declared here.
extern "C" int fc2d_compute_error(FrictionContactProblem* problem, double* z, double* w, double tolerance,
                                  double norm, double* error);

namespace flexmbs::contact {
namespace {

struct MatrixDeleter {
  void operator()(NumericsMatrix* m) const { NM_free(m); }
};
struct OptionsDeleter {
  void operator()(SolverOptions* o) const { solver_options_delete(o); }
};
using MatrixPtr = std::unique_ptr<NumericsMatrix, MatrixDeleter>;
using OptionsPtr = std::unique_ptr<SolverOptions, OptionsDeleter>;

// A dense NumericsMatrix owning a copy of A (column-major, as Eigen stores it).
MatrixPtr DenseCopy(const Eigen::MatrixXd& A) {
  const int rows = static_cast<int>(A.rows());
  const int cols = static_cast<int>(A.cols());
  MatrixPtr m(NM_create(NM_DENSE, rows, cols));
  Eigen::Map<Eigen::MatrixXd>(m->matrix0, rows, cols) = A;
  return m;
}

OptionsPtr Options(int solver, const SiconosOptions& options) {
  OptionsPtr o(solver_options_create(solver));
  o->dparam[SICONOS_DPARAM_TOL] = options.tolerance;
  o->iparam[SICONOS_IPARAM_MAX_ITER] = options.max_iterations;
  return o;
}

// The problem in Siconos' structs, with copies Siconos may write to.
struct SiconosLcp {
  MatrixPtr M;
  Eigen::VectorXd q;
  LinearComplementarityProblem lcp;
  explicit SiconosLcp(const LcpProblem& problem)
      : M(DenseCopy(problem.M)), q(problem.q), lcp{static_cast<int>(q.size()), M.get(), q.data()} {}
};

struct SiconosFc {
  MatrixPtr W;
  Eigen::VectorXd q, mu;
  ::FrictionContactProblem fc;
  explicit SiconosFc(const FrictionContactProblem& problem)
      : W(DenseCopy(problem.W)), q(problem.q), mu(problem.mu),
        fc{problem.dimension, problem.contacts(), W.get(), q.data(), mu.data()} {}
};

template <class Solution>
void SetStatus(Solution& s, int info, int iterations, double error, const SiconosOptions& options,
               const char* name) {
  s.iterations = iterations;
  s.error = error;
  s.converged = info == 0 && error <= options.tolerance;
  if (s.converged) {
    s.message = fmt::format("Siconos {}: converged after {} iterations", name, iterations);
  } else if (info == 0) {
    s.message = fmt::format("Siconos {}: info 0 (success) but error {:.3g} > tolerance {:.3g}", name, error,
                            options.tolerance);
  } else {
    s.message = fmt::format("Siconos {}: failed with info {} after {} iterations (error {:.3g})", name, info,
                            iterations, error);
  }
}

LcpSolution SolveLcp(const LcpProblem& problem, int solver, const SiconosOptions& options, const char* name) {
  CheckLcp(problem);
  if (problem.q.size() == 0) return {{0, 0.0, true, "empty LCP"}, {}, {}};  // Siconos is not asked
  SiconosLcp p(problem);
  OptionsPtr o = Options(solver, options);
  o->iparam[SICONOS_LCP_IPARAM_SKIP_TRIVIAL] = SICONOS_LCP_SKIP_TRIVIAL_YES;
  LcpSolution s;
  s.z = Eigen::VectorXd::Zero(p.q.size());
  s.w = Eigen::VectorXd::Zero(p.q.size());
  const int info = linearComplementarity_driver(&p.lcp, s.z.data(), s.w.data(), o.get());
  double error = 0.0;
  lcp_compute_error(&p.lcp, s.z.data(), s.w.data(), options.tolerance, &error);
  SetStatus(s, info, o->iparam[SICONOS_IPARAM_ITER_DONE], error, options, name);
  return s;
}

double FcError(SiconosFc& p, Eigen::VectorXd& r, Eigen::VectorXd& u, SolverOptions* o, double tolerance) {
  double error = 0.0;
  const double norm_q = p.q.norm();
  if (p.fc.dimension == 2) {
    fc2d_compute_error(&p.fc, r.data(), u.data(), tolerance, norm_q, &error);
  } else {
    fc3d_compute_error(&p.fc, r.data(), u.data(), tolerance, o, norm_q, &error);
  }
  return error;
}

FrictionContactSolution SolveFc(const FrictionContactProblem& problem, int solver, const SiconosOptions& options,
                                const char* name) {
  CheckFrictionContact(problem);
  if (problem.q.size() == 0) return {{0, 0.0, true, "no contacts"}, {}, {}};  // Siconos is not asked
  SiconosFc p(problem);
  OptionsPtr o = Options(solver, options);
  FrictionContactSolution s;
  FLEXMBS_CHECK(options.initial_r.size() == 0 || options.initial_r.size() == p.q.size(),
                "Siconos: the initial r must have d n entries");
  s.r = options.initial_r.size() == p.q.size() ? options.initial_r : Eigen::VectorXd::Zero(p.q.size());
  s.u = Eigen::VectorXd::Zero(p.q.size());
  const int info = problem.dimension == 2 ? fc2d_driver(&p.fc, s.r.data(), s.u.data(), o.get())
                                          : fc3d_driver(&p.fc, s.r.data(), s.u.data(), o.get());
  const double error = FcError(p, s.r, s.u, o.get(), options.tolerance);
  SetStatus(s, info, o->iparam[SICONOS_IPARAM_ITER_DONE], error, options, name);
  if (solver == SICONOS_FRICTION_3D_PROX) {
    // PROX counts its proximal iterations; each runs its internal NSN_AC to error / 10.
    s.message += fmt::format(" ({} internal Newton steps)",
                             o->iparam[SICONOS_FRICTION_3D_PROXIMAL_IPARAM_CUMULATIVE_ITER_DONE]);
  }
  return s;
}

}  // namespace

LcpSolution SiconosLcpLemke(const LcpProblem& problem, const SiconosOptions& options) {
  return SolveLcp(problem, SICONOS_LCP_LEMKE, options, "LCP Lemke");
}

LcpSolution SiconosLcpPgs(const LcpProblem& problem, const SiconosOptions& options) {
  return SolveLcp(problem, SICONOS_LCP_PGS, options, "LCP PGS");
}

FrictionContactSolution SiconosFrictionNsgs(const FrictionContactProblem& problem, const SiconosOptions& options) {
  return problem.dimension == 2 ? SolveFc(problem, SICONOS_FRICTION_2D_NSGS, options, "fc2d NSGS")
                                : SolveFc(problem, SICONOS_FRICTION_3D_NSGS, options, "fc3d NSGS");
}

FrictionContactSolution SiconosFrictionAlartCurnier(const FrictionContactProblem& problem,
                                                    const SiconosOptions& options) {
  FLEXMBS_CHECK(problem.dimension == 3, "Siconos NSN_AC solves spatial (d = 3) problems only");
  return SolveFc(problem, SICONOS_FRICTION_3D_NSN_AC, options, "fc3d NSN_AC");
}

FrictionContactSolution SiconosFrictionProximal(const FrictionContactProblem& problem,
                                                const SiconosOptions& options) {
  FLEXMBS_CHECK(problem.dimension == 3, "Siconos PROX solves spatial (d = 3) problems only");
  return SolveFc(problem, SICONOS_FRICTION_3D_PROX, options, "fc3d PROX");
}

double SiconosLcpError(const LcpProblem& problem, const Eigen::VectorXd& z) {
  CheckLcp(problem);
  SiconosLcp p(problem);
  Eigen::VectorXd z_copy = z;
  Eigen::VectorXd w(z.size());
  double error = 0.0;
  lcp_compute_error(&p.lcp, z_copy.data(), w.data(), 0.0, &error);
  return error;
}

double SiconosFrictionContactError(const FrictionContactProblem& problem, const Eigen::VectorXd& r) {
  CheckFrictionContact(problem);
  SiconosFc p(problem);
  OptionsPtr o = Options(problem.dimension == 2 ? SICONOS_FRICTION_2D_NSGS : SICONOS_FRICTION_3D_NSGS, {});
  Eigen::VectorXd r_copy = r;
  Eigen::VectorXd u(r.size());
  return FcError(p, r_copy, u, o.get(), 0.0);
}

}  // namespace flexmbs::contact
