#pragma once

// The body held by its supports and interfaces, in the interior coordinates u_o of
// u = B q_b + G u_o (BuildConstraintTransform): the matrices of the held body and their
// factorisation, with the check that the conditions really hold it.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "eigensolvers/eigensolver.h"
#include "reduction/interface_coupling.h"
#include "reduction/modal_basis.h"
#include "eigensolvers/shifted_factorization.h"

namespace flexmbs::reduction {

/// K_oo = G^T K G and M_oo = G^T M G: stiffness [N/m] and mass [kg] of the body with supports
/// clamped and interfaces held (q_b = 0). Symmetric, full storage.
struct InteriorProblem {
  ConstraintTransform transform;
  Eigen::SparseMatrix<double> K_oo;
  Eigen::SparseMatrix<double> M_oo;
};

/// Builds the interior problem of `conditions` (which may be empty: then G = I, a free body).
/// Throws InputError for bad conditions (BuildConstraintTransform) or a bad model.
InteriorProblem BuildInteriorProblem(const FeModel& model, const BoundaryConditions& conditions);

/// The DOF (ascending) that `conditions` clamp, if they clamp whole node DOF only (supports,
/// node-set and rigid interfaces: G of BuildConstraintTransform then selects the other DOF);
/// nothing if an averaging interface ties DOF together. Throws BuildConstraintTransform's
/// InputErrors.
std::optional<std::vector<int>> ClampedDofs(const Eigen::Matrix3Xd& nodes, const BoundaryConditions& conditions);

/// The Cholesky factor of K_oo (sigma = 0). Throws a one-line InputError naming the conditions
/// and the reason if they do not hold the body: K_oo is not positive definite, or has an
/// eigenvalue at zero to round-off (HasZeroEnergyMode).
eigensolvers::ShiftedFactorization FactorHeldInterior(const FeModel& model, const BoundaryConditions& conditions,
                                        const InteriorProblem& interior);

/// The held body factorised once for every solve with its K_oo: the Craig-Bampton constraint
/// modes, the held check, the fixed-interface eigen-solve (Eigensolver::SolveFactorized at
/// shift 0) and the static solves after the basis (correction modes, geometric stiffening:
/// SolveStaticResponses). A basis carries it as ReducedBasis::held_factorization.
struct HeldFactorization {
  BoundaryConditions conditions;  ///< what holds the body
  ConstraintTransform transform;  ///< u = B q_b + G u_o of `conditions`
  eigensolvers::ShiftedFactorization factor;    ///< Cholesky factor of K_oo = G^T K G at sigma = 0 (FactorHeldInterior)
  double seconds = 0.0;           ///< wall-clock time of the factorisation and the held check [s]
};

/// FactorHeldInterior of `interior` (built from `conditions`), kept with copies of the
/// conditions and the transform, and timed. Throws as FactorHeldInterior. Precondition:
/// interior has interior DOF.
std::shared_ptr<const HeldFactorization> FactorHeldBody(const FeModel& model, const BoundaryConditions& conditions,
                                                        const InteriorProblem& interior);

/// Whether `held` was made for exactly `conditions`: the same supports (names, nodes) and
/// interfaces (names, nodes, coupling, marker, weights), in the same order.
bool FactorizedFor(const HeldFactorization& held, const BoundaryConditions& conditions);

/// Whether the fixed-interface eigen-solve of the held body can use its factor: `solver` uses a
/// given factorisation (Eigensolver::UsesGivenFactorization) and `options` asks for no shift
/// other than 0.
bool SharesHeldFactorization(const eigensolvers::Eigensolver& solver, const eigensolvers::EigenOptions& options);

/// The fixed-interface normal modes K_oo phi_o = lambda M_oo phi_o of `interior`, with their
/// summary for ReducedBasis::eigensolver_summary. With `held` (the factor of this interior) and
/// SharesHeldFactorization, solved by SolveFactorized at shift 0 and the held factorisation
/// counted in the summary (one factorisation, its time included); else by Solve with
/// `options` (`held` may then be null). The solver's InputErrors are prefixed with `what`.
struct HeldModes {
  eigensolvers::EigenSolution solution;
  EigensolverSummary summary;
};
HeldModes SolveHeldModes(const eigensolvers::Eigensolver& solver, const InteriorProblem& interior, const HeldFactorization* held,
                         const eigensolvers::EigenOptions& options, std::string_view what);

/// Whether the factorised K (sigma = 0) has an eigenvalue at zero to round-off relative to
/// trace(K)/trace(M): three steps of inverse iteration from two random vectors, then the
/// Rayleigh quotient of each. A numerically singular K can factorise with round-off pivots;
/// K^-1 then amplifies its null space by 1e8 or more per step, so a Rayleigh quotient drops to
/// round-off; for a positive definite K every Rayleigh quotient is >= lambda_1.
bool HasZeroEnergyMode(const eigensolvers::ShiftedFactorization& factor, const Eigen::SparseMatrix<double>& K,
                       const Eigen::SparseMatrix<double>& M);

/// Throws the one-line InputError "<conditions> do(es) not hold the body: ... (reason)", the
/// reason read from the geometry: all held nodes at one point or on one line, else a part not
/// connected to them or a mechanism.
[[noreturn]] void ThrowNotHeld(const FeModel& model, const BoundaryConditions& conditions);

}  // namespace flexmbs::reduction
