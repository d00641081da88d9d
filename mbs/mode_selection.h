#pragma once
// Which modes of a reduced body a scene keeps, and the body restricted to them (docs/mbs.md,
// "A scene keeps only the modes it names"). Restriction is exact: every SID block is a Galerkin
// projection onto the basis (docs/sid.md), so keeping modes is keeping rows and columns (and, for
// the Taylor blocks' m1/m2 lists, the blocks of the kept modes).
//
// Rigid-body motion. The floating frame carries the body's rigid motion; a combination of kept
// modes that moves the body rigidly repeats it, and the body's mass matrix is then singular. So
// modes of kind "rigid" (a free-free basis's six) are never kept: filters skip them and naming one
// is an error; and CheckNoRigidBodyMotion refuses any other kept set that spans a rigid motion
// (e.g. the constraint modes of the only interface of an unsupported Craig-Bampton body: hold
// the frame there by leaving that interface's constraint modes out).

#include <Eigen/Core>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "sid/reduced_body.h"

namespace flexmbs::mbs {

/// A mode named by its 0-based column index or by its name (sid::ReducedBody::mode_names).
using ModeId = std::variant<Eigen::Index, std::string>;

/// Which modes of a body a scene keeps: either an explicit list, or the filters (kind and
/// frequency, intersected). Nothing set keeps every mode that is not of kind "rigid".
struct ModeSelection {
  /// The modes by index or name; kept in the body's order whatever the list's order.
  std::optional<std::vector<ModeId>> modes;
  /// Kinds kept: "normal", "constraint", "static_correction" ("rigid" is refused).
  std::optional<std::vector<std::string>> kinds;
  /// Keeps the modes whose frequency_hz is <= this [Hz]; modes without a frequency (NaN:
  /// constraint and static correction modes) pass. Finite and >= 0.
  std::optional<double> max_frequency_hz;
};

/// The kept column indices of `body`, ascending. `body_name` names the body in messages.
/// Throws InputError "body '<name>': modes: <problem>" (one line) for: a list together with a
/// filter, an index out of range, an unknown mode name, a mode listed twice, a rigid mode listed,
/// an unknown kind, the kind "rigid", a kind listed twice, a frequency that is negative or not
/// finite, and a selection that keeps no mode.
std::vector<Eigen::Index> SelectModes(const sid::ReducedBody& body, const ModeSelection& selection,
                                      std::string_view body_name);

/// `body` with only the modes `keep` (column indices, distinct, in range; the new mode i is the
/// old keep[i]): refmod lists, every Taylor block (rows, columns and m1/m2 lists that index
/// modes), the stiffening matrices, the basis, the nodes' origin/phi/psi/AP and the surfaces'
/// phi. Exact (a Galerkin projection onto the kept modes) for every block; De too, as the same
/// projection of the reduced damping operator (a modal-ratio De of a basis that is not
/// M-orthonormal eigenvectors gives other ratios than a re-reduction would).
sid::ReducedBody RestrictModes(const sid::ReducedBody& body, const std::vector<Eigen::Index>& keep);

/// The smallest share of kinetic energy that deformation holds in any motion of the modes at
/// q = 0: the least eigenvalue lambda of (Me - C^T M_rr^-1 C) x = lambda Me x, C = [Ct Cr]^T,
/// M_rr = [m I, mdCM~^T; mdCM~, J] (the kinematic order-0 blocks). 1 for modes M-orthogonal to
/// every rigid motion, 0 for a combination that is a rigid motion. 1 for a body without modes.
/// Precondition: Me positive definite.
double MinimumDeformationShare(const sid::ReducedBody& body);

/// Share below which a motion of the modes counts as rigid: its deformation carries less than
/// 1e-8 of its kinetic energy (deformation amplitude 1e-4 of the motion). Exactly rigid
/// combinations of a reduction come out at the round-off of the invariants (~1e-14).
inline constexpr double kRigidMotionShare = 1e-8;

/// Throws InputError "body '<name>': modes: <modes> move the body rigidly, which the floating
/// frame already does: leave them out" if MinimumDeformationShare < kRigidMotionShare, naming
/// the modes that carry the rigid motion (the largest components of the eigenvector).
void CheckNoRigidBodyMotion(const sid::ReducedBody& body, std::string_view body_name);

}  // namespace flexmbs::mbs
