#pragma once

// Static responses of a body held as in its reduction, to many load vectors with one
// factorisation. Shared by the static correction modes (correction_modes.h) and the geometric
// stiffening load cases (geometric_stiffening.h).
//
// * Held body (held_by has supports or interfaces): x = G K_oo^-1 G^T f, the response with
//   supports clamped and interfaces held (u = B q_b + G u_o with q_b = 0; interior_problem.h).
//   A load on held DOF (or on an averaging interface's marker, W^T F with W G = 0) goes straight
//   into the hold: G^T f = 0, no response.
// * Free-free body (held_by empty), inertia relief (MSC Nastran Linear Static Analysis User's
//   Guide, "Inertia relief"): the load is balanced by the rigid-body inertia forces,
//   f_e = (I - M R R^T) f with R the M-orthonormal rigid modes, so that R^T f_e = 0; then
//   K x = f_e is solved with six DOF fixed as a statically determinate 3-2-1 support (three
//   far-apart nodes A, B, C: A in x, y, z, B in the two axes across AB, C normal to ABC), which
//   carries no reaction for a self-equilibrated load, so x is exact up to a rigid motion; finally
//   x -= R R^T M x (M-orthogonal to the rigid modes).

#include <Eigen/Core>
#include <string_view>
#include <vector>

#include "reduction/interface_coupling.h"
#include "reduction/modal_basis.h"

namespace flexmbs::reduction {

/// The static responses to the columns of a load matrix.
struct StaticResponses {
  Eigen::MatrixXd X;  ///< num_dofs x cases [m per unit load]
  /// Per case: the load reaches no interior DOF (held body only; it is carried by the supports
  /// or interfaces, and its column of X is zero).
  std::vector<bool> carried;
};

/// The static responses of the body held as `held_by` (see the file comment) to the loads F
/// (num_dofs x cases, DOF 3 n + i) [N], all solved with one factorisation: `held`'s if given
/// (the basis's ReducedBasis::held_factorization; no new factorisation), else a new one. `what`
/// prefixes the messages ("static correction modes"). Throws a one-line InputError for
/// conditions that do not hold the body (FactorHeldInterior), a free body whose nodes lie on
/// one line or whose stiffness with a 3-2-1 support is singular (a disconnected part or a
/// mechanism). Preconditions: a valid model (ValidateModel), F with num_dofs rows; `held`, if
/// given, factorised for `held_by` (FactorizedFor) and this model's K.
StaticResponses SolveStaticResponses(const FeModel& model, const BoundaryConditions& held_by,
                                     const Eigen::MatrixXd& F, std::string_view what,
                                     const HeldFactorization* held = nullptr);

}  // namespace flexmbs::reduction
