#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/yaml_node.h"

namespace flexmbs::reduction {

/// How a marker node is tied to the FE nodes of its node set.
enum class MarkerCoupling {
  kNode,       ///< the set's single FE node; rotation 1/2 curl u there (fem::NodalRotation)
  kRigid,      ///< RBE2-like rigid fit of the set's nodes (interface_coupling.h)
  kAveraging,  ///< RBE3-like weighted rigid fit of the set's nodes (interface_coupling.h)
};

/// "node", "rigid" or "averaging": the names used in files and in sid::Node::coupling.
std::string_view MarkerCouplingName(MarkerCoupling coupling);

/// A marker node of the `sid:` section: where joints, forces and outputs attach.
struct MarkerSetting {
  std::string name;      ///< unique among the body's markers and interface markers
  std::string node_set;  ///< one of the body's node sets
  MarkerCoupling coupling = MarkerCoupling::kAveraging;
  /// p_BoMarker_B [m] (rigid, averaging); unset: the centroid of the set's nodes.
  std::optional<Eigen::Vector3d> p_BoMarker_B;
  /// The marker's item in the body file, for problems found once the mesh is known; unset for
  /// settings made in code.
  std::optional<YamlNode> source;

  /// Throws InputError "<file>:<line>:<col>: sid.markers[i]: <problem>" (or, without a source,
  /// "sid.markers 'name': <problem>").
  [[noreturn]] void Fail(std::string_view problem) const;
};

/// How the reduced damping matrix De is made (reduction/damping.h).
enum class DampingKind {
  kNone,      ///< De = 0
  kModal,     ///< damping ratios of the elastic modes of the reduced system
  kRayleigh,  ///< De = a Me + b Ke
};

/// The `damping:` item of the `sid:` section.
struct DampingSpec {
  DampingKind kind = DampingKind::kNone;
  /// kModal: the ratio zeta [-] of every elastic mode, unless `modal_ratios` is given.
  double modal_ratio = 0.0;
  /// kModal: one ratio per elastic mode of the reduced system, ascending frequency; empty: all
  /// take `modal_ratio`.
  std::vector<double> modal_ratios;
  double rayleigh_mass_per_s = 0.0;   ///< kRayleigh: a [1/s]
  double rayleigh_stiffness_s = 0.0;  ///< kRayleigh: b [s]
  /// The damping item (its `modal_ratios` list if given) in the body file; unset if made in code.
  std::optional<YamlNode> source;

  /// Throws InputError "<file>:<line>:<col>: sid.damping...: <problem>" (or "sid.damping:
  /// <problem>" without a source).
  [[noreturn]] void Fail(std::string_view problem) const;
};

/// Throws InputError (DampingSpec::Fail) if `damping` lists per-mode ratios and their number is
/// not `num_elastic_modes` (the number of non-zero frequencies of the reduced system, known only
/// once the basis is built).
void CheckModalRatioCount(const DampingSpec& damping, Eigen::Index num_elastic_modes);

/// The `sid:` section of a body file: what the `.sid.h5` file holds beyond the basis.
///
///     sid:
///       markers:                  # besides the reduction's interface markers
///         - {name: mid, node_set: mid, coupling: averaging}   # node | rigid | averaging
///         - {name: tip, node_set: tip, coupling: rigid, position: [1, 0, 0]}
///       contact_surfaces: [pad, rim]   # node sets whose boundary faces become surfaces
///       damping: {modal_ratio: 0.02}   # or {modal_ratios: [0.01, 0.02]} (one per elastic
///                                      # mode), or {rayleigh: {mass: a, stiffness: b}}
///       geometric_stiffening: true     # default true
///
/// The section is optional: no markers, no surfaces, no damping, stiffening on.
struct SidSpec {
  std::vector<MarkerSetting> markers;
  std::vector<std::string> contact_surfaces;  ///< node set names, unique
  DampingSpec damping;
  bool geometric_stiffening = true;
};

/// Reads the `sid:` section of `body_file` (defaults if absent). `node_sets` are the body's
/// node set names (the body file's `node_sets:`); `reserved_names` the names the reduction's
/// interface markers take (sid_nodes.h), which markers must not reuse. Every marker needs
/// name, node_set and coupling. Throws InputError
/// "<file>:<line>:<col>: sid.<item>: <problem>" for an unknown key, an unknown node set or
/// coupling, an empty or duplicate marker name, a marker named like an interface, a position on
/// a `node` marker, a contact surface listed twice, a damping item that is not exactly one of
/// modal_ratio, modal_ratios, rayleigh, a negative ratio or Rayleigh coefficient, an empty
/// ratio list, or a Rayleigh item with neither coefficient. (Numbers must be finite:
/// YamlNode::AsDouble.)
SidSpec LoadSidSpec(const std::filesystem::path& body_file,
                    const std::vector<std::string>& node_sets,
                    const std::vector<std::string>& reserved_names);

/// Checks the markers against the mesh's node sets (name -> FE nodes): every set exists and is
/// not empty, and a `node` marker's set holds exactly one FE node. Throws InputError
/// (MarkerSetting::Fail) otherwise.
void CheckMarkerNodeSets(const std::vector<MarkerSetting>& markers,
                         const std::map<std::string, std::vector<int>>& node_sets);

}  // namespace flexmbs::reduction
