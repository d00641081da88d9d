#pragma once

// The reduced damping matrix De of a basis (SID `De`, docs/sid.md).
//
// * Rayleigh: De = a Me + b Ke (Rayleigh 1877; Craig & Kurdila, "Fundamentals of Structural
//   Dynamics", 2nd ed. 2006, on proportional damping): mode k of the reduced system has
//   zeta_k = a / (2 omega_k) + b omega_k / 2.
// * Modal ratios: with V the Me-orthonormal eigenvectors of the reduced system,
//   Ke V = Me V diag(omega^2), V^T Me V = I,
//
//       De = Me V diag(2 zeta_k omega_k) V^T Me,
//
//   so that V^T De V = diag(2 zeta_k omega_k): every mode of the reduced system decouples with
//   ratio zeta_k (Craig & Kurdila 2006, modal damping). For an Me-orthonormal modal basis
//   (V = I) this is diag(2 zeta omega); for a Craig-Bampton basis it damps the normal modes of
//   the reduced system, which mix constraint and fixed-interface modes. Rigid-body modes
//   (zero frequency to round-off) get no damping; ratios are per elastic mode, ascending
//   frequency.

#include <Eigen/Core>
#include <string>

#include "reduction/modal_basis.h"
#include "reduction/sid_spec.h"

namespace flexmbs::reduction {

/// A reduced damping matrix and how it was made.
struct ReducedDamping {
  Eigen::MatrixXd De;       ///< n x n [N s/m per unit q], symmetric
  std::string description;  ///< one line: "none", "modal 2 %", "Rayleigh a = 0.5 1/s, b = 1e-05 s"
};

/// De of `basis` (its K_reduced and M_reduced; M_reduced positive definite) as `damping` says
/// (see the file comment). Zero frequency: lambda <= kZeroEigenvalue trace(K) / trace(M) of the
/// full `model`, as for the bases. Throws InputError (DampingSpec::Fail) if per-mode ratios do
/// not match the number of elastic modes.
ReducedDamping DampingMatrix(const DampingSpec& damping, const FeModel& model,
                             const ReducedBasis& basis);

}  // namespace flexmbs::reduction
