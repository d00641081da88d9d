#pragma once

#include <Eigen/Core>
#include <array>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "reduction/correction_modes.h"
#include "reduction/interface_coupling.h"

namespace flexmbs::reduction {

/// Which basis `flexmbs reduce` builds.
enum class ReductionMethod {
  kFreeFree,        ///< free-free normal modes (six rigid-body modes included)
  kFixedInterface,  ///< normal modes with the interfaces held
  kCraigBampton,    ///< interface constraint modes plus fixed-interface normal modes
};

/// One interface as the body file names it: a node set of the body and its coupling
/// (interface_coupling.h).
struct InterfaceSetting {
  std::string node_set;
  Coupling coupling = Coupling::kNodes;
  std::optional<Eigen::Vector3d> p_BoMarker_B;  ///< marker position [m]; default: the set's centroid
};

/// One support as the body file names it: a node set and the components it holds (a plain
/// name holds x, y and z; `{node_set: edges, components: [z]}` only z).
struct SupportSetting {
  std::string node_set;
  std::array<bool, 3> components = {true, true, true};  ///< held along x, y, z of B
};

/// Static correction modes for unit loads on a node set (correction_modes.h LoadSet).
struct CorrectionSpec {
  std::string node_set;
  std::optional<Eigen::Vector3d> direction;  ///< in B; unset: x, y and z
  LoadDistribution distribution = LoadDistribution::kResultant;
};

/// The `reduction:` section of a body file:
///
///     reduction:
///       method: craig_bampton        # free_free (default) | fixed_interface | craig_bampton
///       modes: 20                    # normal modes, and/or
///       max_frequency_hz: 2000       # all normal modes below this
///       eigensolver: spectra         # spectra (default) | slepc
///       rigid_body_modes: exact      # free_free: exact (default) | computed
///       orthonormalize: false        # craig_bampton: reduced M = I, K diagonal
///       supports: [clamp, {node_set: edges, components: [z]}]  # held during the reduction
///       interfaces:
///         - {node_set: tip, coupling: nodes}        # nodes | rigid | averaging
///         - {node_set: hub, coupling: rigid, marker: [0, 0, 0]}
///       correction_modes:
///         - {node_set: tip, direction: [0, 1, 0]}   # default: x, y and z
///         - {node_set: pad, distribution: per_node} # resultant (default) | per_node
struct ReductionSpec {
  ReductionMethod method = ReductionMethod::kFreeFree;
  int num_modes = 0;
  double max_frequency_hz = 0.0;
  std::string eigensolver = "spectra";
  bool exact_rigid_body_modes = true;
  bool orthonormalize = false;
  std::vector<SupportSetting> supports;
  std::vector<InterfaceSetting> interfaces;
  std::vector<CorrectionSpec> corrections;
};

/// Reads the `reduction:` section of `body_file`; `node_sets` are the body's node set names
/// (every interface and correction set must be one of them). Throws InputError
/// "<file>:<line>:<col>: reduction.<item>: <problem>" for a missing section, an unknown
/// method, coupling, distribution or eigensolver, a zero direction, neither modes nor max_frequency_hz, a non-positive
/// count or band, neither a support nor an interface where the method needs one, an
/// unknown node set, or a support's unknown, repeated or empty list of components.
ReductionSpec LoadReductionSpec(const std::filesystem::path& body_file,
                                const std::vector<std::string>& node_sets);

/// The supports and interfaces of `spec` with their node sets resolved (`node_sets`: the
/// mesh's named node sets, which LoadReductionSpec has checked the names against).
BoundaryConditions ResolveConditions(const ReductionSpec& spec,
                                     const std::map<std::string, std::vector<int>>& node_sets);

/// The load sets of `spec` with their node sets resolved.
std::vector<LoadSet> ResolveLoadSets(const ReductionSpec& spec,
                                     const std::map<std::string, std::vector<int>>& node_sets);

/// The method's name in files and reports ("free_free", ...).
std::string_view MethodName(ReductionMethod method);

}  // namespace flexmbs::reduction
