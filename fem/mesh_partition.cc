#include "fem/mesh_partition.h"

#include <algorithm>
#include <limits>
#include <numeric>

#include "core/error.h"

namespace flexmbs::fem {
namespace {

using Index = Eigen::Index;

// The centroid of every element (blocks in order), 3 x num_elements [m].
Eigen::Matrix3Xd ElementCentroids(const Mesh& mesh) {
  Eigen::Matrix3Xd out(3, mesh.num_elements());
  Index e = 0;
  for (const ElementBlock& block : mesh.blocks) {
    for (Index k = 0; k < block.num_elements(); ++k, ++e) {
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (Index a = 0; a < block.connectivity.rows(); ++a) sum += mesh.nodes.col(block.connectivity(a, k));
      out.col(e) = sum / static_cast<double>(block.connectivity.rows());
    }
  }
  return out;
}

// Assigns parts [first_part, first_part + parts) to the elements in [begin, end).
void Bisect(const Eigen::Matrix3Xd& centroids, std::vector<int>::iterator begin, std::vector<int>::iterator end,
            int first_part, int parts, std::vector<int>* element_part) {
  if (parts == 1 || end - begin <= 1) {
    for (auto it = begin; it != end; ++it) (*element_part)[static_cast<std::size_t>(*it)] = first_part;
    return;
  }
  Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d high = -low;
  for (auto it = begin; it != end; ++it) {
    low = low.cwiseMin(centroids.col(*it));
    high = high.cwiseMax(centroids.col(*it));
  }
  Index axis = 0;
  (high - low).maxCoeff(&axis);
  const int left_parts = parts / 2;
  const auto middle = begin + (end - begin) * left_parts / parts;
  std::nth_element(begin, middle, end, [&](int a, int b) { return centroids(axis, a) < centroids(axis, b); });
  Bisect(centroids, begin, middle, first_part, left_parts, element_part);
  Bisect(centroids, middle, end, first_part + left_parts, parts - left_parts, element_part);
}

// Numbers the nodes part by part (mesh order within a part) from each node's owning part.
void NumberNodes(const std::vector<int>& node_part, MeshPartition* partition) {
  partition->node_offsets.assign(static_cast<std::size_t>(partition->parts) + 1, 0);
  for (int p : node_part) ++partition->node_offsets[static_cast<std::size_t>(p) + 1];
  std::partial_sum(partition->node_offsets.begin(), partition->node_offsets.end(), partition->node_offsets.begin());
  std::vector<Index> next(partition->node_offsets.begin(), partition->node_offsets.end() - 1);
  partition->new_node.resize(node_part.size());
  for (std::size_t n = 0; n < node_part.size(); ++n) {
    partition->new_node[n] = static_cast<int>(next[static_cast<std::size_t>(node_part[n])]++);
  }
}

}  // namespace

IndexRange EvenPartition(Index count, int parts, int part) {
  FLEXMBS_CHECK(parts > 0 && part >= 0 && part < parts, "part must be in [0, parts)");
  const Index base = count / parts;
  const Index extra = count % parts;
  const Index begin = part * base + std::min<Index>(part, extra);
  return {begin, begin + base + (part < extra ? 1 : 0)};
}

MeshPartition PartitionByCoordinateBisection(const Mesh& mesh, int parts) {
  FLEXMBS_CHECK(parts >= 1, "a partition needs at least one part");
  MeshPartition out;
  out.parts = parts;
  const Index num_elements = mesh.num_elements();
  out.element_part.assign(static_cast<std::size_t>(num_elements), 0);
  std::vector<int> order(static_cast<std::size_t>(num_elements));
  std::iota(order.begin(), order.end(), 0);
  Bisect(ElementCentroids(mesh), order.begin(), order.end(), 0, parts, &out.element_part);

  std::vector<int> node_part(static_cast<std::size_t>(mesh.num_nodes()), parts);
  Index e = 0;
  for (const ElementBlock& block : mesh.blocks) {
    for (Index k = 0; k < block.num_elements(); ++k, ++e) {
      const int part = out.element_part[static_cast<std::size_t>(e)];
      for (Index a = 0; a < block.connectivity.rows(); ++a) {
        int& owner = node_part[static_cast<std::size_t>(block.connectivity(a, k))];
        owner = std::min(owner, part);
      }
    }
  }
  for (int& p : node_part) p = p == parts ? 0 : p;
  NumberNodes(node_part, &out);
  return out;
}

MeshPartition PartitionInMeshOrder(const Mesh& mesh, int parts) {
  MeshPartition out;
  out.parts = parts;
  out.element_part.resize(static_cast<std::size_t>(mesh.num_elements()));
  std::vector<int> node_part(static_cast<std::size_t>(mesh.num_nodes()));
  for (int p = 0; p < parts; ++p) {
    const IndexRange elements = EvenPartition(mesh.num_elements(), parts, p);
    const IndexRange nodes = EvenPartition(mesh.num_nodes(), parts, p);
    std::fill(out.element_part.begin() + elements.begin, out.element_part.begin() + elements.end, p);
    std::fill(node_part.begin() + nodes.begin, node_part.begin() + nodes.end, p);
  }
  NumberNodes(node_part, &out);
  return out;
}

MeshPart ExtractMeshPart(const Mesh& mesh, const MeshPartition& partition, int part) {
  FLEXMBS_CHECK(part >= 0 && part < partition.parts, "part must be in [0, parts)");
  MeshPart out;
  out.num_global_nodes = mesh.num_nodes();
  out.owned_nodes = {partition.node_offsets[static_cast<std::size_t>(part)],
                     partition.node_offsets[static_cast<std::size_t>(part) + 1]};
  // The part's nodes in ascending global order, so that its owned nodes come as one run.
  std::vector<int> local_of(static_cast<std::size_t>(mesh.num_nodes()), -1);
  std::vector<int> used;
  Index e = 0;
  for (const ElementBlock& block : mesh.blocks) {
    std::vector<Index> mine;
    for (Index k = 0; k < block.num_elements(); ++k, ++e) {
      if (partition.element_part[static_cast<std::size_t>(e)] == part) mine.push_back(k);
    }
    if (mine.empty()) continue;
    ElementBlock local{block.type, block.region, block.material, Connectivity(block.connectivity.rows(),
                                                                              static_cast<Index>(mine.size())), {}};
    for (std::size_t j = 0; j < mine.size(); ++j) {
      local.connectivity.col(static_cast<Index>(j)) = block.connectivity.col(mine[j]);
      if (!block.element_ids.empty()) local.element_ids.push_back(block.element_ids[static_cast<std::size_t>(mine[j])]);
      for (Index a = 0; a < block.connectivity.rows(); ++a) {
        const int node = block.connectivity(a, mine[j]);
        if (local_of[static_cast<std::size_t>(node)] < 0) {
          local_of[static_cast<std::size_t>(node)] = 0;
          used.push_back(node);
        }
      }
    }
    out.mesh.blocks.push_back(std::move(local));
  }
  std::sort(used.begin(), used.end(), [&](int a, int b) {
    return partition.new_node[static_cast<std::size_t>(a)] < partition.new_node[static_cast<std::size_t>(b)];
  });
  out.mesh.nodes.resize(3, static_cast<Index>(used.size()));
  out.global_node.resize(used.size());
  for (std::size_t j = 0; j < used.size(); ++j) {
    const auto node = static_cast<std::size_t>(used[j]);
    local_of[node] = static_cast<int>(j);
    out.mesh.nodes.col(static_cast<Index>(j)) = mesh.nodes.col(used[j]);
    out.global_node[j] = partition.new_node[node];
    if (!mesh.node_ids.empty()) out.mesh.node_ids.push_back(mesh.node_ids[node]);
  }
  for (ElementBlock& block : out.mesh.blocks) {
    for (int& node : block.connectivity.reshaped()) node = local_of[static_cast<std::size_t>(node)];
  }
  return out;
}

}  // namespace flexmbs::fem
