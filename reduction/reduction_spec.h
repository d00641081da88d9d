#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace flexmbs::reduction {

/// Which basis `flexmbs reduce` builds.
enum class ReductionMethod {
  kFreeFree,        ///< free-free normal modes (six rigid-body modes included)
  kFixedInterface,  ///< normal modes with the interfaces held
  kCraigBampton,    ///< interface constraint modes plus fixed-interface normal modes
};

/// How an interface node set is tied to the basis.
enum class InterfaceCoupling {
  kNodes,    ///< every DOF of every node of the set is a boundary DOF
  kRigid,    ///< a 6-DOF marker the nodes follow rigidly (RBE2-like)
  kAverage,  ///< a 6-DOF marker moving with the weighted rigid fit of the nodes (RBE3-like)
};

/// One interface: a node set of the body and its coupling.
struct InterfaceSpec {
  std::string node_set;
  InterfaceCoupling coupling = InterfaceCoupling::kNodes;
  std::optional<Eigen::Vector3d> p_BoMarker_B;  ///< marker position [m]; default: the set's centroid
};

/// Static correction modes for unit loads on a node set, along the listed axes of B.
struct CorrectionSpec {
  std::string node_set;
  std::vector<int> axes;  ///< 0 = x, 1 = y, 2 = z
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
///       interfaces:
///         - {node_set: clamp, coupling: nodes}      # nodes | rigid | average
///         - {node_set: hub, coupling: rigid, marker: [0, 0, 0]}
///       correction_modes:
///         - {node_set: tip, axes: [y, z]}
struct ReductionSpec {
  ReductionMethod method = ReductionMethod::kFreeFree;
  int num_modes = 0;
  double max_frequency_hz = 0.0;
  std::string eigensolver = "spectra";
  bool exact_rigid_body_modes = true;
  bool orthonormalize = false;
  std::vector<InterfaceSpec> interfaces;
  std::vector<CorrectionSpec> corrections;
};

/// Reads the `reduction:` section of `body_file`; `node_sets` are the body's node set names
/// (every interface and correction set must be one of them). Throws InputError
/// "<file>:<line>:<col>: reduction.<item>: <problem>" for a missing section, an unknown
/// method, coupling, axis or eigensolver, neither modes nor max_frequency_hz, a non-positive
/// count or band, an interface missing where the method needs one, or an unknown node set.
ReductionSpec LoadReductionSpec(const std::filesystem::path& body_file,
                                const std::vector<std::string>& node_sets);

/// The method's name in files and reports ("free_free", ...).
std::string_view MethodName(ReductionMethod method);

}  // namespace flexmbs::reduction
