#pragma once

// Small readers shared by the body file's sections (reduction_spec, sid_spec): a choice among
// names, a 3-vector, a node set name checked against the body's node sets.

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include "core/yaml_node.h"

namespace flexmbs::reduction {


/// A list of three numbers (finite: YamlNode::AsDouble); else fails naming the count or the value.
Eigen::Vector3d ReadVector3(const YamlNode& node);

/// The node set named by `node`; fails with "'<name>' is not one of the body's node_sets (...)"
/// unless it is in `node_sets` (the body file's `node_sets:`).
std::string ReadNodeSetName(const YamlNode& node, const std::vector<std::string>& node_sets);

}  // namespace flexmbs::reduction
