#pragma once

#include <limits>
#include <string>

#include <Eigen/Core>

namespace flexmbs::contact {

/// How a complementarity solve ended. A solver that stops without meeting its tolerance sets
/// converged = false and says why in message; it never returns an unconverged result silently.
struct SolveStatus {
  int iterations = 0;  ///< sweeps, Newton steps or pivots, as the solver counts them
  double error = std::numeric_limits<double>::infinity();  ///< the problem's error measure at the end
  bool converged = false;  ///< error <= the requested tolerance (a pivoting solver: a solution found)
  std::string message;     ///< one line: what happened ("converged", "ray termination at pivot 3", ...)
};

/// An LCP solve's result: z and w = M z + q, with its status.
struct LcpSolution : SolveStatus {
  Eigen::VectorXd z;  ///< the unknown, n
  Eigen::VectorXd w;  ///< M z + q, n
};

/// A friction-contact solve's result: reactions r and local velocities u = W r + q, with its status.
struct FrictionContactSolution : SolveStatus {
  Eigen::VectorXd r;  ///< reactions (impulses), d n; per contact (normal, tangent[, tangent])
  Eigen::VectorXd u;  ///< local relative velocities W r + q, d n, same layout
};

}  // namespace flexmbs::contact
