#include "reduction/sid_spec.h"

#include <fmt/format.h>

#include <algorithm>

#include "core/error.h"
#include "reduction/spec_support.h"

namespace flexmbs::reduction {
namespace {

// In the order of the MarkerCoupling enum.
const std::vector<std::string_view> kMarkerCouplings = {"node", "rigid", "averaging"};

// A damping ratio or Rayleigh coefficient: >= 0 (finite by AsDouble).
double ReadNonNegative(const YamlNode& node, std::string_view what) {
  const double value = node.AsDouble();
  if (value < 0.0) node.Fail(fmt::format("{} {:g} must be >= 0", what, value));
  return value;
}

MarkerSetting ReadMarker(const YamlNode& node, const std::vector<std::string>& node_sets) {
  node.RejectUnknownKeys({"name", "node_set", "coupling", "position"});
  MarkerSetting marker;
  marker.source = node;
  const YamlNode name = node.Required("name");
  marker.name = name.AsString();
  if (marker.name.empty()) name.Fail("a marker name must not be empty");
  marker.node_set = ReadNodeSetName(node.Required("node_set"), node_sets);
  marker.coupling =
      static_cast<MarkerCoupling>(node.Required("coupling").AsChoice(kMarkerCouplings));
  if (node.Has("position")) {
    const YamlNode position = node.Required("position");
    if (marker.coupling == MarkerCoupling::kNode) {
      position.Fail(
          "a 'node' marker sits at its FE node: a position is for rigid or averaging markers");
    }
    marker.p_BoMarker_B = ReadVector3(position);
  }
  return marker;
}

DampingSpec ReadDamping(const YamlNode& node) {
  node.RejectUnknownKeys({"modal_ratio", "modal_ratios", "rayleigh"});
  DampingSpec damping;
  damping.source = node;
  const int given =
      int{node.Has("modal_ratio")} + int{node.Has("modal_ratios")} + int{node.Has("rayleigh")};
  if (given != 1) node.Fail("give exactly one of 'modal_ratio', 'modal_ratios' or 'rayleigh'");
  if (node.Has("modal_ratio")) {
    damping.kind = DampingKind::kModal;
    damping.modal_ratio = ReadNonNegative(node.Required("modal_ratio"), "damping ratio");
  } else if (node.Has("modal_ratios")) {
    damping.kind = DampingKind::kModal;
    const YamlNode list = node.Required("modal_ratios");
    damping.source = list;
    for (const YamlNode& ratio : list.AsList())
      damping.modal_ratios.push_back(ReadNonNegative(ratio, "damping ratio"));
    if (damping.modal_ratios.empty())
      list.Fail("give one damping ratio per elastic mode (or 'modal_ratio' for all)");
  } else {
    damping.kind = DampingKind::kRayleigh;
    const YamlNode rayleigh = node.Required("rayleigh");
    rayleigh.RejectUnknownKeys({"mass", "stiffness"});
    if (!rayleigh.Has("mass") && !rayleigh.Has("stiffness")) {
      rayleigh.Fail("give 'mass' (a [1/s]) and/or 'stiffness' (b [s]) of De = a Me + b Ke");
    }
    if (rayleigh.Has("mass")) {
      damping.rayleigh_mass_per_s = ReadNonNegative(rayleigh.Required("mass"), "mass coefficient");
    }
    if (rayleigh.Has("stiffness")) {
      damping.rayleigh_stiffness_s =
          ReadNonNegative(rayleigh.Required("stiffness"), "stiffness coefficient");
    }
  }
  return damping;
}

}  // namespace

std::string_view MarkerCouplingName(MarkerCoupling coupling) {
  return kMarkerCouplings[static_cast<std::size_t>(coupling)];
}

void MarkerSetting::Fail(std::string_view problem) const {
  if (source) source->Fail(problem);
  throw InputError(fmt::format("sid.markers '{}': {}", name, problem));
}

void DampingSpec::Fail(std::string_view problem) const {
  if (source) source->Fail(problem);
  throw InputError(fmt::format("sid.damping: {}", problem));
}

void CheckModalRatioCount(const DampingSpec& damping, Eigen::Index num_elastic_modes) {
  if (damping.kind != DampingKind::kModal || damping.modal_ratios.empty()) return;
  const auto given = static_cast<Eigen::Index>(damping.modal_ratios.size());
  if (given != num_elastic_modes) {
    damping.Fail(fmt::format("{} damping ratio{} for {} elastic mode{} of the reduced system",
                             given, given == 1 ? "" : "s", num_elastic_modes,
                             num_elastic_modes == 1 ? "" : "s"));
  }
}

SidSpec LoadSidSpec(const std::filesystem::path& body_file,
                    const std::vector<std::string>& node_sets,
                    const std::vector<std::string>& reserved_names) {
  const YamlNode root = YamlNode::LoadFile(body_file);
  SidSpec spec;
  if (!root.Has("sid")) return spec;
  const YamlNode section = root.Required("sid");
  section.RejectUnknownKeys({"markers", "contact_surfaces", "damping", "geometric_stiffening"});
  if (section.Has("markers")) {
    for (const YamlNode& node : section.Required("markers").AsList()) {
      MarkerSetting marker = ReadMarker(node, node_sets);
      const bool reserved = std::find(reserved_names.begin(), reserved_names.end(), marker.name) !=
                            reserved_names.end();
      if (reserved) {
        node.Required("name").Fail(
            fmt::format("'{}' is the name of an interface marker of the reduction", marker.name));
      }
      const bool repeated =
          std::any_of(spec.markers.begin(), spec.markers.end(),
                      [&](const MarkerSetting& m) { return m.name == marker.name; });
      if (repeated)
        node.Required("name").Fail(fmt::format("marker name '{}' is used twice", marker.name));
      spec.markers.push_back(std::move(marker));
    }
  }
  if (section.Has("contact_surfaces")) {
    for (const YamlNode& node : section.Required("contact_surfaces").AsList()) {
      std::string name = ReadNodeSetName(node, node_sets);
      if (std::find(spec.contact_surfaces.begin(), spec.contact_surfaces.end(), name) !=
          spec.contact_surfaces.end()) {
        node.Fail(fmt::format("contact surface '{}' is listed twice", name));
      }
      spec.contact_surfaces.push_back(std::move(name));
    }
  }
  if (section.Has("damping")) spec.damping = ReadDamping(section.Required("damping"));
  if (section.Has("geometric_stiffening")) {
    spec.geometric_stiffening = section.Required("geometric_stiffening").AsBool();
  }
  return spec;
}

void CheckMarkerNodeSets(const std::vector<MarkerSetting>& markers,
                         const std::map<std::string, std::vector<int>>& node_sets) {
  for (const MarkerSetting& marker : markers) {
    const auto it = node_sets.find(marker.node_set);
    if (it == node_sets.end())
      marker.Fail(fmt::format("the mesh has no node set '{}'", marker.node_set));
    const std::size_t count = it->second.size();
    if (count == 0) marker.Fail(fmt::format("node set '{}' has no nodes", marker.node_set));
    if (marker.coupling == MarkerCoupling::kNode && count != 1) {
      marker.Fail(
          fmt::format("coupling 'node' needs a node set of exactly one FE node; '{}' has {}",
                      marker.node_set, count));
    }
  }
}

}  // namespace flexmbs::reduction
