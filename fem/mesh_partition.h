#pragma once
// Element partitions of a mesh for distributed assembly: which rank integrates which element,
// the node numbering that makes each rank's DOF rows contiguous, and one rank's share.

#include <Eigen/Core>
#include <vector>

#include "fem/mesh.h"

namespace flexmbs::fem {

/// A contiguous index range [begin, end).
struct IndexRange {
  Eigen::Index begin = 0;
  Eigen::Index end = 0;
};

/// Part `part` of an even split of `count` items into `parts` contiguous ranges (the first
/// count % parts ranges are one longer).
IndexRange EvenPartition(Eigen::Index count, int parts, int part);

/// An element partition into `parts` and the node numbering that goes with it. Elements are
/// numbered over the mesh's blocks in order. Node n becomes global node new_node[n]; part p owns
/// (assembles the DOF rows of) the global nodes [node_offsets[p], node_offsets[p + 1]).
struct MeshPartition {
  int parts = 1;
  std::vector<int> element_part;            ///< per element: its part
  std::vector<int> new_node;                ///< per mesh node: its global (partition-ordered) index
  std::vector<Eigen::Index> node_offsets;   ///< parts + 1 entries
};

/// Recursive coordinate bisection of the element centroids: the elements are split at the
/// median along the longest extent of their centroids into two groups sized in proportion to
/// the parts each gets, recursively (Berger & Bokhari 1987). Parts are contiguous in space, so
/// a part's interface with the others is small. A node belongs to the lowest part among its
/// elements' parts (a node of no element to part 0); nodes are renumbered part by part,
/// keeping their mesh order within a part. Preconditions: parts >= 1.
MeshPartition PartitionByCoordinateBisection(const Mesh& mesh, int parts);

/// The partition that keeps the mesh order: EvenPartition of the elements (blocks in order)
/// and of the nodes (identity numbering).
MeshPartition PartitionInMeshOrder(const Mesh& mesh, int parts);

/// One part of a partitioned mesh: what a rank needs to assemble its elements.
struct MeshPart {
  /// The part's elements (blocks of the mesh with their elements of this part, empty blocks
  /// dropped) over the nodes they use, in local numbering. No node sets.
  Mesh mesh;
  std::vector<int> global_node;     ///< per local node: its global (partition-ordered) index
  IndexRange owned_nodes;           ///< the global nodes whose DOF rows this part assembles
  Eigen::Index num_global_nodes = 0;
};

/// Part `part` of `partition` of `mesh`. Preconditions: 0 <= part < partition.parts.
MeshPart ExtractMeshPart(const Mesh& mesh, const MeshPartition& partition, int part);

}  // namespace flexmbs::fem
