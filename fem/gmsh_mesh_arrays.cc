#include "fem/gmsh_mesh_arrays.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <numeric>
#include <optional>
#include <string_view>

#include "core/error.h"

namespace flexmbs::fem {
namespace {

namespace fs = std::filesystem;

/// Throws InputError unless `b` (not empty) is of a supported type with a whole number of
/// elements' node tags; returns its type.
ElementType CheckedBlockType(const fs::path& path, const GmshElementBlock& b) {
  const std::optional<ElementType> type = FromGmshType(b.gmsh_type);
  if (!type) {
    std::vector<std::string_view> supported;
    for (const ElementTraits& t : kElementTraits) supported.push_back(t.name);
    throw InputError(fmt::format(
        "{}: region '{}': element {} is a {} (gmsh type {}), which flexmbs does not support (supported: {})",
        path.string(), b.region, b.element_tags.front(), GmshTypeName(b.gmsh_type), b.gmsh_type,
        fmt::join(supported, ", ")));
  }
  const auto n = static_cast<std::size_t>(Traits(*type).num_nodes);
  if (b.node_tags.size() != n * b.element_tags.size()) {
    throw InputError(fmt::format("{}: region '{}': {} {} elements with {} node tags (expected {} per element)",
                                 path.string(), b.region, b.element_tags.size(), Traits(*type).name,
                                 b.node_tags.size(), n));
  }
  return *type;
}

/// Throws InputError unless `nodes` has three finite coordinates per tag.
void CheckNodes(const fs::path& path, const GmshNodes& nodes) {
  if (nodes.coords.size() != 3 * nodes.tags.size()) {
    throw InputError(fmt::format("{}: the mesher returned {} nodes with {} coordinates (expected 3 per node)",
                                 path.string(), nodes.tags.size(), nodes.coords.size()));
  }
  for (std::size_t i = 0; i < nodes.tags.size(); ++i) {
    const double* p = &nodes.coords[3 * i];
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
      throw InputError(fmt::format("{}: node {} has a non-finite coordinate ({}, {}, {})", path.string(),
                                   nodes.tags[i], p[0], p[1], p[2]));
    }
  }
}

/// Positions into `nodes.tags` sorted by tag (stable: of a tag given twice, the last comes last).
std::vector<std::size_t> SortedByTag(const GmshNodes& nodes) {
  std::vector<std::size_t> order(nodes.tags.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return nodes.tags[a] < nodes.tags[b]; });
  return order;
}

/// The position in `nodes.tags` of `tag` (the last one if given twice), or nullopt;
/// `by_tag` is SortedByTag(nodes).
std::optional<std::size_t> FindNode(const GmshNodes& nodes, const std::vector<std::size_t>& by_tag,
                                    std::size_t tag) {
  const auto after = std::upper_bound(by_tag.begin(), by_tag.end(), tag,
                                      [&](std::size_t t, std::size_t p) { return t < nodes.tags[p]; });
  if (after == by_tag.begin() || nodes.tags[*(after - 1)] != tag) return std::nullopt;
  return *(after - 1);
}

}  // namespace

Mesh MeshFromGmshArrays(const fs::path& path, std::vector<GmshElementBlock> blocks, const GmshNodes& nodes) {
  std::erase_if(blocks, [](const GmshElementBlock& b) { return b.element_tags.empty() && b.node_tags.empty(); });
  if (blocks.empty()) throw InputError(fmt::format("{}: the mesh has no volume elements", path.string()));
  std::vector<ElementType> types;
  for (const GmshElementBlock& b : blocks) {
    if (b.element_tags.empty()) {
      throw InputError(fmt::format("{}: region '{}': {} node tags without elements", path.string(), b.region,
                                   b.node_tags.size()));
    }
    types.push_back(CheckedBlockType(path, b));
  }
  CheckNodes(path, nodes);

  // Every element node has coordinates; the nodes in use, in tag order, are the mesh's.
  const std::vector<std::size_t> by_tag = SortedByTag(nodes);
  Mesh mesh;
  for (std::size_t j = 0; j < blocks.size(); ++j) {
    const GmshElementBlock& b = blocks[j];
    const auto n = static_cast<std::size_t>(Traits(types[j]).num_nodes);
    for (std::size_t k = 0; k < b.node_tags.size(); ++k) {
      if (!FindNode(nodes, by_tag, b.node_tags[k])) {
        throw InputError(fmt::format("{}: region '{}': element {} uses node {}, which has no coordinates",
                                     path.string(), b.region, b.element_tags[k / n], b.node_tags[k]));
      }
      mesh.node_ids.push_back(b.node_tags[k]);
    }
  }
  std::sort(mesh.node_ids.begin(), mesh.node_ids.end());
  mesh.node_ids.erase(std::unique(mesh.node_ids.begin(), mesh.node_ids.end()), mesh.node_ids.end());
  mesh.nodes.resize(3, static_cast<Eigen::Index>(mesh.node_ids.size()));
  for (std::size_t i = 0; i < mesh.node_ids.size(); ++i) {
    const double* p = &nodes.coords[3 * *FindNode(nodes, by_tag, mesh.node_ids[i])];
    mesh.nodes.col(static_cast<Eigen::Index>(i)) = Eigen::Vector3d(p[0], p[1], p[2]);
  }

  for (std::size_t j = 0; j < blocks.size(); ++j) {
    GmshElementBlock& b = blocks[j];
    ElementBlock block;
    block.type = types[j];
    block.region = b.region;
    block.connectivity.resize(Traits(block.type).num_nodes, static_cast<Eigen::Index>(b.element_tags.size()));
    for (std::size_t k = 0; k < b.node_tags.size(); ++k) {
      const auto at = std::lower_bound(mesh.node_ids.begin(), mesh.node_ids.end(), b.node_tags[k]);
      block.connectivity.data()[k] = static_cast<int>(at - mesh.node_ids.begin());  // found: checked above
    }
    block.element_ids = std::move(b.element_tags);
    mesh.blocks.push_back(std::move(block));
  }
  return mesh;
}

std::vector<int> MeshNodesOfTags(const Mesh& mesh, const std::vector<std::size_t>& tags) {
  std::vector<int> indices;
  for (std::size_t tag : tags) {
    const auto at = std::lower_bound(mesh.node_ids.begin(), mesh.node_ids.end(), tag);
    if (at != mesh.node_ids.end() && *at == tag) indices.push_back(static_cast<int>(at - mesh.node_ids.begin()));
  }
  std::sort(indices.begin(), indices.end());
  indices.erase(std::unique(indices.begin(), indices.end()), indices.end());
  return indices;
}

}  // namespace flexmbs::fem
