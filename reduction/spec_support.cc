#include "reduction/spec_support.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

namespace flexmbs::reduction {

Eigen::Vector3d ReadVector3(const YamlNode& node) {
  const std::vector<YamlNode> xyz = node.AsList();
  if (xyz.size() != 3) node.Fail(fmt::format("expected 3 coordinates, got {}", xyz.size()));
  return Eigen::Vector3d(xyz[0].AsDouble(), xyz[1].AsDouble(), xyz[2].AsDouble());
}

std::string ReadNodeSetName(const YamlNode& node, const std::vector<std::string>& node_sets) {
  const std::string name = node.AsString();
  if (std::find(node_sets.begin(), node_sets.end(), name) == node_sets.end()) {
    node.Fail(
        fmt::format("'{}' is not one of the body's node_sets ({})", name,
                    node_sets.empty() ? "none" : fmt::format("{}", fmt::join(node_sets, ", "))));
  }
  return name;
}

}  // namespace flexmbs::reduction
