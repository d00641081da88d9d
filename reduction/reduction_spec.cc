#include "reduction/reduction_spec.h"

#include <algorithm>
#include <array>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/yaml_node.h"
#include "eigensolvers/eigensolver.h"
#include "reduction/spec_support.h"

namespace flexmbs::reduction {
namespace {

const std::vector<std::string_view> kMethods = {"free_free", "fixed_interface", "craig_bampton"};
// In the order of the Coupling enum.
const std::vector<std::string_view> kCouplings = {"nodes", "rigid", "averaging"};
// In the order of the LoadDistribution enum.
const std::vector<std::string_view> kDistributions = {"resultant", "per_node"};
// A support's components, axes of B.
const std::vector<std::string_view> kAxes = {"x", "y", "z"};

// A support: a node set name (x, y and z held) or {node_set, components: [x, y, z]}.
SupportSetting ReadSupport(const YamlNode& node, const std::vector<std::string>& node_sets) {
  SupportSetting spec;
  if (!node.Has("node_set") && !node.Has("components")) {
    spec.node_set = ReadNodeSetName(node, node_sets);
    return spec;
  }
  node.RejectUnknownKeys({"node_set", "components"});
  spec.node_set = ReadNodeSetName(node.Required("node_set"), node_sets);
  if (!node.Has("components")) return spec;
  const YamlNode components = node.Required("components");
  const std::vector<YamlNode> list = components.AsList();
  if (list.empty()) components.Fail("an empty list holds nothing: give x, y and/or z");
  spec.components = {false, false, false};
  for (const YamlNode& entry : list) {
    const auto axis = static_cast<std::size_t>(entry.AsChoice(kAxes));
    if (spec.components[axis]) entry.Fail(fmt::format("'{}' is listed twice", kAxes[axis]));
    spec.components[axis] = true;
  }
  return spec;
}

InterfaceSetting ReadInterface(const YamlNode& node, const std::vector<std::string>& node_sets) {
  node.RejectUnknownKeys({"node_set", "coupling", "marker"});
  InterfaceSetting spec;
  spec.node_set = ReadNodeSetName(node.Required("node_set"), node_sets);
  if (node.Has("coupling")) {
    spec.coupling = static_cast<Coupling>(node.Required("coupling").AsChoice(kCouplings));
  }
  if (node.Has("marker")) spec.p_BoMarker_B = ReadVector3(node.Required("marker"));
  return spec;
}

CorrectionSpec ReadCorrection(const YamlNode& node, const std::vector<std::string>& node_sets) {
  node.RejectUnknownKeys({"node_set", "direction", "distribution"});
  CorrectionSpec spec;
  spec.node_set = ReadNodeSetName(node.Required("node_set"), node_sets);
  if (node.Has("direction")) {
    const YamlNode direction = node.Required("direction");
    spec.direction = ReadVector3(direction);
    if (spec.direction->norm() == 0.0) direction.Fail("a load direction must not be zero");
  }
  if (node.Has("distribution")) {
    spec.distribution = static_cast<LoadDistribution>(node.Required("distribution").AsChoice(kDistributions));
  }
  return spec;
}

}  // namespace

std::string_view MethodName(ReductionMethod method) { return kMethods[static_cast<std::size_t>(method)]; }

BoundaryConditions ResolveConditions(const ReductionSpec& spec,
                                     const std::map<std::string, std::vector<int>>& node_sets) {
  BoundaryConditions conditions;
  for (const SupportSetting& s : spec.supports) {
    conditions.supports.push_back({s.node_set, node_sets.at(s.node_set), s.components});
  }
  for (const InterfaceSetting& setting : spec.interfaces) {
    InterfaceSpec interface;
    interface.name = setting.node_set;
    interface.nodes = node_sets.at(setting.node_set);
    interface.coupling = setting.coupling;
    interface.marker_position = setting.p_BoMarker_B;
    conditions.interfaces.push_back(std::move(interface));
  }
  return conditions;
}

ReductionSpec LoadReductionSpec(const std::filesystem::path& body_file,
                                const std::vector<std::string>& node_sets) {
  const YamlNode section = YamlNode::LoadFile(body_file).Required("reduction");
  section.RejectUnknownKeys({"method", "modes", "max_frequency_hz", "eigensolver", "rigid_body_modes",
                            "orthonormalize", "supports", "interfaces", "correction_modes"});
  ReductionSpec spec;
  if (section.Has("method")) {
    spec.method = static_cast<ReductionMethod>(section.Required("method").AsChoice(kMethods));
  }
  if (section.Has("modes")) {
    const YamlNode modes = section.Required("modes");
    spec.num_modes = modes.AsInt();
    if (spec.num_modes <= 0) modes.Fail(fmt::format("mode count {} must be > 0", spec.num_modes));
  }
  if (section.Has("max_frequency_hz")) {
    const YamlNode band = section.Required("max_frequency_hz");
    spec.max_frequency_hz = band.AsDouble();
    if (spec.max_frequency_hz <= 0.0) band.Fail(fmt::format("{:g} Hz must be > 0", spec.max_frequency_hz));
  }
  if (spec.num_modes == 0 && spec.max_frequency_hz == 0.0) {
    section.Fail("give the number of normal modes ('modes') or a band ('max_frequency_hz')");
  }
  if (section.Has("eigensolver")) {
    const YamlNode solver = section.Required("eigensolver");
    spec.eigensolver = solver.AsString();
    const std::vector<std::string> available = eigensolvers::AvailableEigensolvers();
    if (std::find(available.begin(), available.end(), spec.eigensolver) == available.end()) {
      solver.Fail(fmt::format("unknown eigensolver '{}' (available: {})", spec.eigensolver, fmt::join(available, ", ")));
    }
  }
  if (section.Has("rigid_body_modes")) {
    const std::vector<std::string_view> kRigid = {"exact", "computed"};
    spec.exact_rigid_body_modes = section.Required("rigid_body_modes").AsChoice(kRigid) == 0;
  }
  if (section.Has("orthonormalize")) spec.orthonormalize = section.Required("orthonormalize").AsBool();
  if (section.Has("supports")) {
    for (const YamlNode& node : section.Required("supports").AsList()) {
      spec.supports.push_back(ReadSupport(node, node_sets));
    }
  }
  if (section.Has("interfaces")) {
    for (const YamlNode& node : section.Required("interfaces").AsList()) {
      spec.interfaces.push_back(ReadInterface(node, node_sets));
    }
  }
  if (section.Has("correction_modes")) {
    for (const YamlNode& node : section.Required("correction_modes").AsList()) {
      spec.corrections.push_back(ReadCorrection(node, node_sets));
    }
  }
  if (spec.method == ReductionMethod::kCraigBampton && spec.interfaces.empty()) {
    section.Fail("method 'craig_bampton' needs at least one entry in 'interfaces'");
  }
  if (spec.method == ReductionMethod::kFixedInterface && spec.interfaces.empty() && spec.supports.empty()) {
    section.Fail("method 'fixed_interface' needs 'supports' or 'interfaces' to hold the body");
  }
  if (spec.method == ReductionMethod::kFreeFree && !(spec.interfaces.empty() && spec.supports.empty())) {
    section.Fail("method 'free_free' takes no 'supports' or 'interfaces' (use fixed_interface or craig_bampton)");
  }
  return spec;
}

std::vector<LoadSet> ResolveLoadSets(const ReductionSpec& spec,
                                     const std::map<std::string, std::vector<int>>& node_sets) {
  std::vector<LoadSet> loads;
  for (const CorrectionSpec& c : spec.corrections) {
    LoadSet load;
    load.name = c.node_set;
    load.nodes = node_sets.at(c.node_set);
    load.direction = c.direction;
    load.distribution = c.distribution;
    loads.push_back(std::move(load));
  }
  return loads;
}

}  // namespace flexmbs::reduction
