#pragma once

// The Craig-Bampton basis (Craig & Bampton, "Coupling of substructures for dynamic analyses",
// AIAA Journal 6(7), 1968; Craig & Kurdila, "Fundamentals of Structural Dynamics", 2nd ed.
// 2006, chapter on component-mode synthesis) and its orthonormalised form.
//
// With the displacement split into boundary and interior parts, u = B q_b + G u_o
// (interface_coupling.h; for node-set interfaces simply u = [u_b; u_i]), the basis is
//
//     Phi = [Psi, Phi_n],   Psi = B + G X,   K_oo X = -G^T K B,   Phi_n = G phi_o,
//
// Psi the constraint modes (unit motion of one boundary coordinate, the interior statically
// condensed: for node sets Psi = [I; -K_ii^-1 K_ib]) and Phi_n the fixed-interface normal
// modes (K_oo phi_o = lambda M_oo phi_o, boundary held). K_oo = G^T K G is factorised once
// (Cholesky, ShiftedFactorization at sigma = 0). By construction G^T K Psi = 0: the constraint
// modes carry no force on interior DOF and are K-orthogonal to the normal modes, so K_reduced
// is block diagonal [Psi^T K Psi, 0; 0, diag(omega_n^2)].

#include "eigensolvers/eigensolver.h"
#include "reduction/interface_coupling.h"
#include "reduction/modal_basis.h"

namespace flexmbs::reduction {

/// The Craig-Bampton basis of a body with `conditions` (at least one interface; supports are
/// clamped and add no modes): the constraint modes of every interface in order (kConstraint,
/// named "constraint_" + ConstraintTransform::boundary_names), then the fixed-interface normal
/// modes (kNormal, "normal_k") chosen by `normal_modes` (the lowest num_modes, or all below
/// max_frequency_hz; both 0: none, which is Guyan's static condensation).
/// Frequencies and residuals of the normal modes are those of the fixed-interface problem.
/// K_oo is factorised once (held_factorization, kept in the basis) for the constraint modes,
/// the normal modes (SolveHeldModes) and later static solves; eigensolver_summary is set when
/// normal modes were computed.
/// Throws a one-line InputError for: no interface, bad interfaces (BuildConstraintTransform),
/// more normal modes than interior DOF, conditions that do not hold the body (K_ii singular,
/// e.g. a node set on one line of an otherwise free body: the message names the interfaces
/// and why), a band without modes, and the eigensolver's errors (prefixed).
ReducedBasis CraigBamptonBasis(const FeModel& model, const BoundaryConditions& conditions,
                               const eigensolvers::EigenOptions& normal_modes, const eigensolvers::Eigensolver& solver);

/// The orthonormalised form of a basis (used for Craig-Bampton): the small eigenproblem
/// K_reduced t = lambda M_reduced t is solved and Phi' = Phi T, so that M_reduced' = I and
/// K_reduced' = diag(lambda) (Rayleigh-Ritz, recomputed from the full K and M). The new columns
/// mix constraint, normal and correction columns: they are the normal modes of the reduced
/// system (kNormal, "reduced_normal_k"; kRigid, "reduced_rigid_k" for those at zero frequency
/// to round-off), Ritz approximations of the body's modes, with NaN residuals. The original
/// kinds, names and T (Phi' = Phi T) are kept in original_kinds/_names/_transform; the
/// eigenvalues equal those of the input's (K_reduced, M_reduced). held_by is kept.
ReducedBasis OrthonormalizeBasis(const FeModel& model, const ReducedBasis& basis);

}  // namespace flexmbs::reduction
