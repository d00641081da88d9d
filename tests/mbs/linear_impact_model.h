#pragma once
// A full linear FE model with unilateral contacts, integrated without any of the multibody code:
// the reference the reduced flexible bodies' contact runs are measured against (tests/mbs/
// bar_impact_test.cc). Nodal displacements x from the mesh's rest positions, velocities v, and
// contacts whose gaps are affine in x, g = g0 + H x, against fixed obstacles, with Newton's
// impact law at e = 0 (a contact point that closes stays at the obstacle until its force would
// pull), stepped by the same Moreau-Jean theta method (theta = 1/2) as mbs/moreau_jean.h:
//   A = M + h^2/4 K,  A (v_free - v_k) = -h K (x_k + h/2 v_k),
//   active: g(x_k) + h/2 H v_k <= 0,  U = H_a v_k+1 >= 0 _|_ P >= 0,  A v_k+1 = A v_free + H_a^T P,
//   x_k+1 = x_k + h/2 (v_k + v_k+1).
// The contact LCP (W = H_a A^-1 H_a^T, symmetric positive definite for independent DOFs) is solved
// by projected Gauss-Seidel, not the Lemke pivoting the multibody stepper uses.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace flexmbs::mbs::testing {

/// The model: stiffness K [N/m] and mass M [kg] (n x n, free or supported), contact rows H
/// (c x n) and gaps at x = 0, g0 (c) [m].
struct LinearContactModel {
  Eigen::SparseMatrix<double> K, M;
  Eigen::MatrixXd H;
  Eigen::VectorXd g0;
};

/// A run's history: per step its end time [s] and the contact impulse over it summed over the
/// contacts [N s]; the final displacements and velocities, and the wall time of the steps [s].
struct LinearImpactHistory {
  std::vector<double> t;
  std::vector<double> impulse;
  Eigen::VectorXd x, v;
  double seconds = 0.0;
};

/// Integrates `model` from x = 0, v = v0 by steps of h to end_time (the last step may end past it
/// by less than h).
LinearImpactHistory IntegrateLinearImpact(const LinearContactModel& model, const Eigen::VectorXd& v0, double h,
                                          double end_time);

/// max_k |sum_{i<=k} a_i - sum_{i<=k} b_i| over the common entries: the largest difference of the
/// impulse two runs of the same steps have transferred up to a step [N s].
double LargestCumulativeDifference(const std::vector<double>& a, const std::vector<double>& b);

}  // namespace flexmbs::mbs::testing
