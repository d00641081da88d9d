#pragma once

// Static (residual) correction modes: the static response of the body to named loads, added
// to a basis so that it reproduces the static deflection under those loads exactly
// (residual-flexibility and attachment modes: Craig & Kurdila, "Fundamentals of Structural
// Dynamics", 2nd ed. 2006, chapter on component-mode synthesis).
//
// The static responses are those of the body held as the basis is (static_response.h): with
// supports clamped and interfaces held, x = G K_oo^-1 G^T f (with the Craig-Bampton constraint
// modes this spans every static solution under f: the static u = Psi q_b + G K_oo^-1 G^T f
// because G^T K Psi = 0), or for a free-free body by inertia relief, M-orthogonal to the rigid
// modes.
// Each new mode is then M-orthogonalised against the basis (all columns except constraint
// modes, whose unit boundary motion would be lost; for a Craig-Bampton basis the new modes
// thus stay interface-held) and against the correction modes before it, normalised to unit
// modal mass, or dropped if what remains is below `dependency_tolerance` of its M-norm.

#include <Eigen/Core>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "reduction/modal_basis.h"

namespace flexmbs::reduction {

/// How a load set's nodes are loaded.
enum class LoadDistribution {
  /// One load case per direction: a unit total force [N] shared by the nodes in proportion to
  /// their weights (a distributed load with unit resultant).
  kResultant,
  /// One load case per node and direction: a unit force at each node alone (attachment modes of
  /// a contact surface: lets contact forces anywhere on it deform the body as the full model).
  kPerNode,
};

/// A named load set: where static loads act (a force application area, a contact surface).
struct LoadSet {
  /// Names the modes: "static_correction_<name>[_n<node>][_<x|y|z>]" (the axis suffix when no
  /// direction is given).
  std::string name;
  std::vector<int> nodes;  ///< node indices, no duplicates
  /// The load direction in B (any length > 0; normalised). Unset: three cases, x, y and z.
  std::optional<Eigen::Vector3d> direction;
  LoadDistribution distribution = LoadDistribution::kResultant;
  /// kResultant only: a share w_n > 0 per node (e.g. its tributary area); empty: equal shares.
  std::vector<double> weights;
};

struct CorrectionOptions {
  /// A new mode whose M-norm after M-orthogonalisation against the basis is below this
  /// fraction of its M-norm before is linearly dependent on the basis and dropped.
  double dependency_tolerance = 1e-8;
};

/// The basis with the correction modes appended, and what was dropped.
struct CorrectionResult {
  ReducedBasis basis;  ///< method gets "+static_correction"; kinds kStaticCorrection, NaN frequencies
  Eigen::Index added = 0;
  /// One line per dropped load case: its mode name and why.
  std::vector<std::string> dropped;
};

/// Appends the static correction modes of `loads` to `basis` (see the file comment), held as
/// basis.held_by says. Throws a one-line InputError for: a bad model, a basis of another size, no
/// load sets, a load set with no name, no nodes (empty), a node out of range or twice, a zero or
/// non-finite direction, bad weights, a mode name already in the basis or made twice (two load
/// sets of one name); conditions that do not hold the body; a free body whose
/// stiffness with a 3-2-1 support is singular (a disconnected part or a mechanism).
CorrectionResult AddStaticCorrectionModes(const FeModel& model, const ReducedBasis& basis,
                                          std::span<const LoadSet> loads, const CorrectionOptions& options = {});

/// The unit load vectors of one load set (3 num_nodes x cases) and their mode-name suffixes,
/// in the order AddStaticCorrectionModes uses. Throws InputError as above.
struct LoadCases {
  Eigen::MatrixXd F;
  std::vector<std::string> names;
};
LoadCases BuildLoadCases(Eigen::Index num_nodes, const LoadSet& load);

}  // namespace flexmbs::reduction
