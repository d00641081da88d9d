#pragma once

#include <Eigen/Core>
#include <vector>

#include "sid/reduced_body.h"

namespace flexmbs::reduction {

/// The modal assurance criterion of every column pair (Allemang & Brown 1982):
/// MAC(i, j) = (a_i . b_j)^2 / ((a_i . a_i)(b_j . b_j)), 1 for the same shape at any scale,
/// 0 for orthogonal shapes. A and B have the same number of rows.
Eigen::MatrixXd MacMatrix(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B);

/// Effective modal mass of each mode along each axis of B [kg] (n x 3):
/// m_eff(k, d) = (Phi_k^T M t_d)^2 / (Phi_k^T M Phi_k), from the file's Ct (order 0: the
/// participation factors Phi^T M t_d) and Me. For a complete M-orthonormal basis the columns sum to the body's mass.
Eigen::MatrixXd EffectiveModalMass(const sid::ReducedBody& body);

/// A mode of A and the mode of B most like it.
struct ModePair {
  Eigen::Index a = 0;
  Eigen::Index b = 0;
  double frequency_a_hz = 0.0;
  double frequency_b_hz = 0.0;
  double relative_error = 0.0;  ///< f_B / f_A - 1; 0 if both are 0 (exact rigid modes)
  double mac = 0.0;
};

/// Two reduced bases of one body compared.
struct BasisComparison {
  Eigen::MatrixXd mac;  ///< n_A x n_B
  /// For each mode of A with a frequency (rigid and normal modes): the mode of B with a frequency
  /// and the largest MAC. Repeated frequencies make single-mode MAC ambiguous: within such a
  /// cluster, compare the frequencies, not the pairing.
  std::vector<ModePair> pairs;
  Eigen::MatrixXd effective_mass_a;  ///< n_A x 3 [kg]
  Eigen::MatrixXd effective_mass_b;  ///< n_B x 3 [kg]
};

/// Compares two bases of the same mesh. Throws InputError if the meshes differ (node count or
/// positions beyond 1e-12 of the body's size).
BasisComparison CompareBases(const sid::ReducedBody& a, const sid::ReducedBody& b);

}  // namespace flexmbs::reduction
