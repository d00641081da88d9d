#pragma once

#include <Eigen/Core>

namespace flexmbs::contact {

/// The linear complementarity problem LCP(M, q): find z with
///   z >= 0,  w = M z + q >= 0,  z^T w = 0
/// (Cottle, Pang & Stone, *The Linear Complementarity Problem*, 1992, §1.1). M is dense n x n;
/// the units of z and w are the caller's (impulses and velocities, forces and accelerations).
struct LcpProblem {
  Eigen::MatrixXd M;  ///< n x n; a P-matrix gives a unique solution for every q
  Eigen::VectorXd q;  ///< n
};

/// Throws InternalError unless M is square, q matches it and every entry is finite.
void CheckLcp(const LcpProblem& problem);

/// w = M z + q.
Eigen::VectorXd LcpVelocity(const LcpProblem& problem, const Eigen::VectorXd& z);

/// The LCP error as Siconos numerics 4.4 computes it (lcp_compute_error): ||min(z, w)||_2 with
/// w = M z + q, divided by ||q||_2 when ||q|| > DBL_EPSILON. Zero exactly at a solution; min(z, w)
/// is the natural map of the LCP (Cottle, Pang & Stone 1992, §1.5; Facchinei & Pang 2003, §1.5).
double LcpError(const LcpProblem& problem, const Eigen::VectorXd& z);

}  // namespace flexmbs::contact
