#pragma once

// The full FE model's modes that a reduced body's system modes approximate (`flexmbs compare
// A.sid.h5 body.yaml`): the body constrained as the reduced basis constrains it, and its lowest
// modes.
//
// The system modes of a basis (basis_comparison.h SystemModes) are Rayleigh-Ritz approximations
// of the modes of the body in the space its columns can reach. Every basis clamps the supports
// (zero rows). A free-free modal basis leaves the rest free. A fixed-interface modal basis holds
// its interfaces too (its columns vanish there, or at an averaging interface's marker). A
// Craig-Bampton basis lets the interfaces move (its constraint modes), so its space is that of
// u = B q_b + G u_o (interface_coupling.h) with q_b free: node-set and averaging (RBE3)
// interfaces then restrict nothing, but a rigid (RBE2) interface keeps its nodes on a rigid
// motion of its marker, a constraint that belongs to the model as an RBE2 element does in an FE
// code. The full model's partners of a Craig-Bampton body's system modes are therefore the modes
// of the body held by its supports with its rigid interfaces' nodes moving rigidly with their
// free markers (free-free without supports: 6 rigid-body modes, then elastic).

#include <Eigen/Core>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "eigensolvers/eigensolver.h"
#include "reduction/interface_coupling.h"
#include "reduction/modal_basis.h"
#include "reduction/reduction_spec.h"

namespace flexmbs::reduction {

/// The reduction method of a basis from its method name (ReducedBasis::method, a `.sid.h5`
/// file's provenance "reduction_method"): names beginning "free_free_modal",
/// "fixed_interface_modal" or "craig_bampton" (with "+static_correction", "_orthonormalized",
/// "+orthonormalized" after them); nothing for any other name.
std::optional<ReductionMethod> BasisReductionMethod(std::string_view basis_method);

/// How the full model is constrained for its modes to be the partners of a basis's system modes.
struct FullModelConditions {
  /// Clamped: the supports, and for a fixed-interface basis also the interfaces (held as
  /// FixedInterfaceModalBasis holds them).
  BoundaryConditions held;
  /// Craig-Bampton only: the rigid (RBE2) interfaces, whose nodes move rigidly with their
  /// marker, the marker free.
  std::vector<InterfaceSpec> rigid;

  /// "free (no supports)", "support 'root'", "support 'root', interface 'tip' rigid (marker
  /// free)": for reports and messages.
  std::string Describe() const;
};

/// The conditions of the full model whose modes the system modes of a basis made by `method`
/// with `conditions` approximate (see the file comment): free-free: none; Craig-Bampton: the
/// supports held and the rigid interfaces kept rigid; fixed-interface: supports and interfaces
/// held.
FullModelConditions SystemModeConditions(ReductionMethod method, const BoundaryConditions& conditions);

/// The number of modes of the model under `conditions`: its DOF if it is free, else the DOF
/// of its admissible displacements (BuildConstraintTransform; throws its InputErrors).
Eigen::Index AvailableModes(const FeModel& model, const FullModelConditions& conditions);

/// The lowest min(count, AvailableModes) modes of the full model under `conditions`,
/// M-orthonormal, ascending, with their frequencies and residuals, as a ReducedBasis whose
/// columns are the modes: free (nothing held, no rigid interface): FreeFreeModalBasis (six exact
/// rigid-body modes at 0 Hz, "rigid_tx" ..., then count - 6 elastic "normal_k"); held, no rigid
/// interface: FixedInterfaceModalBasis. With rigid interfaces: the eigenpairs of
/// T^T K T x = lambda T^T M T x, T = [B G] of BuildConstraintTransform(supports, rigid
/// interfaces) (supports clamped, the interfaces' nodes on their markers' rigid motion, the
/// markers free), expanded u = T x; eigenvalues with |lambda| <= kZeroEigenvalue
/// trace(K) / trace(M) are rigid-body modes at 0 Hz ("rigid_k"), the others "normal_k".
/// `model` must be assembled. Throws a one-line InputError for count < 7 on a free body (it
/// needs an elastic mode), and the builders' and the eigensolver's InputErrors (conditions that
/// do not hold the body, ...).
ReducedBasis FullModelModes(const FeModel& model, const FullModelConditions& conditions, Eigen::Index count,
                            const eigensolvers::Eigensolver& solver);

}  // namespace flexmbs::reduction
