#pragma once

// Equal-frequency normal modes split by the mesh's mirror plane (issue 16): an eigensolver
// returns a repeated eigenvalue's modes as any M-orthonormal basis of its eigenspace, so on a
// body mirror-symmetric about its xy plane (a square beam centred on z = 0) each mode of a pair
// is a mixture of the in-plane and the out-of-plane one. This rotates each such cluster into
// modes even or odd under the reflection z -> -z, which a planar scene can keep or drop.

#include "reduction/modal_basis.h"

namespace flexmbs::reduction {

/// Two normal modes belong to one cluster when their eigenvalues lambda = (2 pi f)^2 differ by
/// at most this share of the larger. The Krylov eigensolvers converge each Ritz value to 1e-10
/// of itself (EigenOptions::tolerance), and a repeated eigenvalue came out within 1.2e-11 on the
/// square beam of tests/reduction/mirror_modes_test.cc; 1e-6 leaves four orders of margin and is
/// 5000 times below frequencies the mesh splits (5e-3: case 06's 616.0/619.3 Hz). A wider
/// cluster does nothing wrong: modes already even or odd, or not mapped onto each other by the
/// reflection, are left as they are, and the split's Rayleigh-Ritz keeps K_reduced diagonal.
inline constexpr double kEqualEigenvalue = 1e-6;
/// A cluster is split only when the reflection maps it onto itself: every eigenvalue of
/// C = Phi_c^T M P Phi_c within this of +1 or -1 (C is then orthogonal; a cluster that does not
/// commute with P, as under supports that are not symmetric, is left as it is).
inline constexpr double kMirrorInvariance = 1e-6;
/// FE nodes pair with their mirror images within this share of the mesh's largest coordinate
/// (the planar check's mbs::kMirrorDistance).
inline constexpr double kMirrorNodeDistance = 1e-9;

/// On a model whose nodes are mirror-symmetric about B's xy plane (MirrorPointsAboutXy), turns
/// each cluster of two or more kNormal columns of `basis` with equal eigenvalues
/// (kEqualEigenvalue) into modes even or odd under the reflection P (the mirror node's
/// u_x, u_y, -u_z): the eigenvectors V of C = Phi_c^T M P Phi_c (eigenvalues +-1) give
/// Phi_c V, and a Rayleigh-Ritz step within the even and within the odd columns keeps
/// Phi_c^T K Phi_c diagonal (even and odd modes are K- and M-orthogonal by the symmetry). The
/// cluster's columns are then sorted by their Ritz values, which become frequency_hz; the
/// relative residual of each new column is bounded by the root-sum-square of the cluster's
/// (Cauchy-Schwarz: the rotation is orthogonal), which it is set to; the floor is the cluster's
/// largest. Columns are M-orthonormal before and after. A body without the symmetry, single
/// modes, clusters already even or odd (C diagonal to kMirrorInvariance) and clusters P does not
/// map onto themselves are left bit for bit. Call before ComputeReducedMatrices.
void SplitEqualModesByMirror(const FeModel& model, ReducedBasis* basis);

}  // namespace flexmbs::reduction
