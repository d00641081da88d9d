#pragma once
// A full linear FE model with unilateral contacts, integrated without any of the multibody code:
// the reference the reduced flexible bodies' contact runs are measured against (tests/mbs/
// bar_impact_test.cc, beam_stop_test.cc). Nodal displacements x from the mesh's rest positions,
// velocities v, and contacts whose gaps are affine in x, g = g0 + H x, against fixed obstacles,
// stepped by the theta method of mbs/moreau_jean.h:
//   A = M + h^2 theta^2 K,  A (v_free - v_k) = -h K (x_k + h theta v_k),
//   A v_k+1 = A v_free + H_a^T P,  x_k+1 = x_k + h (theta v_k+1 + (1 - theta) v_k),
// with the contact impulses P of one of three formulations (ContactFormulation):
//   velocity level (e = 0): active g(x_k) + h/2 H v_k <= 0,  0 <= P _|_ H_a v_k+1 >= 0;
//   position level (theta = 1): active g(x_k) + h H v_free <= 0,  0 <= P _|_ g(x_k) + h H_a v_k+1 >= 0;
//   penalty (a one-sided linear spring k per contact, evaluated where the theta method evaluates
//   forces, x_k+theta = x_k + h theta (theta v_k+1 + (1 - theta) v_k), exactly, kink included):
//   0 <= P _|_ g(x_k+theta) + P / (h k) >= 0, P = h k max(0, -g(x_k+theta)).
// Each is an LCP in P with W = H A^-1 H^T (symmetric positive definite for independent DOFs),
// solved by projected Gauss-Seidel, not the Lemke pivoting the multibody stepper uses.

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

/// How the contacts act (see the top of this file).
enum class ContactFormulation { kVelocityLevel, kPositionLevel, kPenalty };

/// The time scheme and contact formulation of a run.
struct ImpactScheme {
  double theta = 0.5;  ///< in [0.5, 1]; 1 for kPositionLevel
  ContactFormulation formulation = ContactFormulation::kVelocityLevel;
  double penalty_stiffness = 0.0;  ///< k [N/m] per contact, kPenalty only
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
                                          double end_time, const ImpactScheme& scheme = {});

/// max_k |sum_{i<=k} a_i - sum_{i<=k} b_i| over the common entries: the largest difference of the
/// impulse two runs of the same steps have transferred up to a step [N s].
double LargestCumulativeDifference(const std::vector<double>& a, const std::vector<double>& b);

}  // namespace flexmbs::mbs::testing
