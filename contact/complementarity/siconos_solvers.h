#pragma once

#include <Eigen/Core>

#include "contact/complementarity/friction_contact_problem.h"
#include "contact/complementarity/lcp_problem.h"
#include "contact/complementarity/solution.h"

namespace flexmbs::contact {

/// Options passed to a Siconos numerics 4.4 solver; everything else keeps Siconos' defaults.
struct SiconosOptions {
  double tolerance = 1e-10;    ///< SICONOS_DPARAM_TOL
  int max_iterations = 10000;  ///< SICONOS_IPARAM_MAX_ITER (pivots for Lemke, sweeps for NSGS)
  /// Friction solvers: the reactions handed to the driver, which its solvers start from (d n
  /// entries); empty: r = 0.
  Eigen::VectorXd initial_r;
};

// The wrappers below copy the problem into Siconos' dense NumericsMatrix, call its driver and
// return Siconos' result with its iteration count. error is Siconos' own error function on the
// result (lcp_compute_error, fc2d_compute_error, fc3d_compute_error); converged requires Siconos'
// info == 0 *and* error <= tolerance, because Siconos 4.4 reports some failures with info == 0
// (see docs/contact.md) — message then says so.

/// LCP by Siconos' lexicographic Lemke (SICONOS_LCP_LEMKE, lcp_lexicolemke). The driver's
/// shortcuts for q >= 0 and n = 1 are switched off (SKIP_TRIVIAL), so Lemke itself runs.
LcpSolution SiconosLcpLemke(const LcpProblem& problem, const SiconosOptions& options = {});

/// LCP by Siconos' projected Gauss-Seidel (SICONOS_LCP_PGS, lcp_pgs; no relaxation).
LcpSolution SiconosLcpPgs(const LcpProblem& problem, const SiconosOptions& options = {});

/// Friction contact by Siconos' NSGS: fc2d_nsgs_dense (SICONOS_FRICTION_2D_NSGS) for d = 2,
/// fc3d_nsgs (SICONOS_FRICTION_3D_NSGS, local solver ONECONTACT_NSN_GP_HYBRID) for d = 3.
FrictionContactSolution SiconosFrictionNsgs(const FrictionContactProblem& problem,
                                            const SiconosOptions& options = {});

/// Spatial friction contact (d = 3) by Siconos' global semi-smooth Newton on Alart-Curnier's
/// function (SICONOS_FRICTION_3D_NSN_AC, fc3d_nonsmooth_Newton_AlartCurnier).
FrictionContactSolution SiconosFrictionAlartCurnier(const FrictionContactProblem& problem,
                                                    const SiconosOptions& options = {});

/// Spatial friction contact (d = 3) by Siconos' proximal point method (SICONOS_FRICTION_3D_PROX,
/// fc3d_proximal, internal solver NSN_AC). Siconos 4.4's defaults: the proximal weight alpha = 5
/// times the error (unscaled), times 10 after an internal failure; each internal solve to
/// max(error / 10, tolerance / contacts). iterations counts the proximal iterations; message
/// ends with the internal Newton steps over all of them.
FrictionContactSolution SiconosFrictionProximal(const FrictionContactProblem& problem,
                                                const SiconosOptions& options = {});

/// Siconos' lcp_compute_error at z (to check that LcpError agrees).
double SiconosLcpError(const LcpProblem& problem, const Eigen::VectorXd& z);

/// Siconos' fc2d_compute_error or fc3d_compute_error at r with norm = ||q|| as its NSGS passes it
/// (to check that FrictionContactError agrees).
double SiconosFrictionContactError(const FrictionContactProblem& problem, const Eigen::VectorXd& r);

}  // namespace flexmbs::contact
