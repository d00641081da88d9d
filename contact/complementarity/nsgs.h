#pragma once

#include <Eigen/Core>

#include "contact/complementarity/friction_contact_problem.h"
#include "contact/complementarity/solution.h"

namespace flexmbs::contact {

/// Options of SolveFrictionNsgs.
struct NsgsOptions {
  double tolerance = 1e-10;   ///< stop when FrictionContactError <= tolerance
  int max_iterations = 10000; ///< most sweeps over all contacts
  Eigen::VectorXd initial_r;  ///< warm start, d n entries; empty: r = 0
};

/// Non-smooth Gauss-Seidel (Moreau 1994; Jean 1999, "The non-smooth contact dynamics method"):
/// sweeps the contacts in order, solving each contact's problem
///   u_i = W_ii r_i + (q_i + sum_{j != i} W_ij r_j)
/// with the others held: exactly for d = 2 (SolvePlanarContact), by local Alart-Curnier Newton
/// for d = 3 (SolveSpatialContact). Needs every W_ii positive definite. Like Siconos' fc3d_nsgs
/// (light error with full final), each sweep measures the relative change of r and evaluates
/// FrictionContactError when that change falls below its threshold, tightening the threshold
/// when the full error is still above tolerance. iterations counts sweeps.
FrictionContactSolution SolveFrictionNsgs(const FrictionContactProblem& problem, const NsgsOptions& options = {});

}  // namespace flexmbs::contact
