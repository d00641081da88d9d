#pragma once

// Comparing the modes of two representations of one body (`flexmbs compare`): two reduced
// bases, or a reduced body's system modes against its full FE model's modes. Both sides are
// mode sets on the same FE DOF (ModeSet); the comparison pairs them by the modal assurance
// criterion and reports frequency errors and effective modal masses.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "reduction/modal_basis.h"
#include "sid/reduced_body.h"

namespace flexmbs::reduction {

/// The modal assurance criterion of every column pair (Allemang & Brown 1982):
/// MAC(i, j) = (a_i . b_j)^2 / ((a_i . a_i)(b_j . b_j)), 1 for the same shape at any scale,
/// 0 for orthogonal shapes. A and B have the same number of rows.
Eigen::MatrixXd MacMatrix(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B);

/// Effective modal mass of each mode along each axis of B [kg] (n x 3):
/// m_eff(k, d) = L(k, d)^2 / m_k, with the participation factors L = Phi^T M t_d (n x 3, t_d the
/// unit translation along axis d) and the modal masses m_k = Phi_k^T M Phi_k [kg]. For a
/// complete basis of M-orthogonal modes the columns sum to the body's mass.
Eigen::MatrixXd EffectiveModalMass(const Eigen::MatrixXd& participation, const Eigen::VectorXd& modal_mass);
/// The same from a reduced body's file: L = Ct (order 0), m_k = Me(k, k) (order 0).
Eigen::MatrixXd EffectiveModalMass(const sid::ReducedBody& body);

/// One side of a comparison: mode shapes on the FE DOF with their frequencies and participation.
struct ModeSet {
  std::vector<std::string> names;  ///< per mode, unique
  Eigen::MatrixXd shapes;          ///< num_dofs x n: DOF 3 node + axis [m per unit modal coordinate]
  Eigen::VectorXd frequency_hz;    ///< per mode [Hz]; NaN: no frequency (the mode is not paired)
  Eigen::MatrixXd participation;   ///< n x 3: shapes^T M t_d [kg]
  Eigen::VectorXd modal_mass;      ///< n: diag(shapes^T M shapes) [kg]

  Eigen::Index size() const { return shapes.cols(); }
};

/// The columns of a reduced body's basis as they are in its file: phi, frequency_hz, the
/// participation Ct (order 0) and the modal masses diag(Me) (order 0).
ModeSet BasisModes(const sid::ReducedBody& body);

/// The columns of `basis`, a basis of `model` (Phi, frequency_hz, names), with participation
/// Phi^T M t_d and modal masses diag(Phi^T M Phi) from the model's M.
ModeSet BasisModes(const ReducedBasis& basis, const FeModel& model);

/// The system modes of a reduced body: the eigenpairs of its reduced matrices,
/// Ke x = lambda Me x (order 0, dense, all n of them, X^T Me X = I), expanded to the FE DOF,
/// shapes = phi X. They are the Rayleigh-Ritz approximations of the body's modes in the span of
/// its basis (Craig & Kurdila, "Fundamentals of Structural Dynamics", 2nd ed. 2006): for a
/// modal basis its own modes, for Craig-Bampton the body's modes with the interfaces free.
/// Participation X^T Ct, modal masses 1. An eigenvalue with |lambda| <= `zero_eigenvalue`
/// [rad^2/s^2] is a rigid-body mode at 0 Hz ("reduced_rigid_k"); the others are
/// "reduced_normal_k" at FrequenciesHz (a negative eigenvalue keeps its sign). Ascending.
/// Throws InputError "Me is not positive definite" if the dense Cholesky of Me fails.
ModeSet SystemModes(const sid::ReducedBody& body, double zero_eigenvalue);

/// A mode of A and the mode of B most like it.
struct ModePair {
  Eigen::Index a = 0;
  Eigen::Index b = 0;
  double frequency_a_hz = 0.0;
  double frequency_b_hz = 0.0;
  /// f / f_reference - 1, f_reference the frequency of the reference side (ErrorReference) and
  /// f the other one's; 0 if both are 0 (exact rigid modes).
  double relative_error = 0.0;
  double mac = 0.0;
};

/// The side whose frequencies relative errors are measured against.
enum class ErrorReference {
  kA,  ///< f_B / f_A - 1
  kB,  ///< f_A / f_B - 1
};

/// Two mode sets of one body compared.
struct BasisComparison {
  Eigen::MatrixXd mac;  ///< n_A x n_B
  /// For each mode of A with a frequency: the mode of B with a frequency and the largest MAC.
  /// Repeated frequencies make single-mode MAC ambiguous: within such a cluster, compare the
  /// frequencies, not the pairing.
  std::vector<ModePair> pairs;
  Eigen::MatrixXd effective_mass_a;  ///< n_A x 3 [kg]
  Eigen::MatrixXd effective_mass_b;  ///< n_B x 3 [kg]
};

/// Compares two mode sets on the same FE DOF (shapes with equal row counts).
BasisComparison CompareModes(const ModeSet& a, const ModeSet& b, ErrorReference reference);

/// Throws InputError unless the two meshes' node positions p_BoN_B [m] (3 x n) have the same
/// number of nodes at the same positions (within 1e-12 of the first mesh's size): "the meshes
/// differ (120 and 98 nodes)" or "(nodes up to 0.001 m apart)".
void CheckSameMesh(const Eigen::Matrix3Xd& nodes_a, const Eigen::Matrix3Xd& nodes_b);

/// Compares the basis columns of two reduced bodies of the same mesh (CheckSameMesh, then
/// CompareModes with A the reference).
BasisComparison CompareBases(const sid::ReducedBody& a, const sid::ReducedBody& b);

}  // namespace flexmbs::reduction
