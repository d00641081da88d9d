#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "fem/element_type.h"
#include "fem/material.h"

namespace flexmbs::fem {

/// Element connectivity: one column per element, node indices (0-based into Mesh::nodes) in
/// gmsh node order.
using Connectivity = Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic>;

/// Elements of one type in one region, all of one material.
struct ElementBlock {
  ElementType type;
  std::string region;  ///< physical volume name, or "volume <tag>" for an unnamed volume
  IsotropicMaterial material;
  Connectivity connectivity;             ///< num_nodes(type) x num_elements
  std::vector<std::size_t> element_ids;  ///< the source file's element tags, for messages

  Eigen::Index num_elements() const { return connectivity.cols(); }
};

/// A solid FE mesh in the body frame B. Degree of freedom 3 n + i is the displacement of
/// node n along axis i of B [m].
struct Mesh {
  Eigen::Matrix3Xd nodes;             ///< p_BoN_B of every node [m]
  std::vector<std::size_t> node_ids;  ///< the source file's node tags, for messages
  std::vector<ElementBlock> blocks;
  /// Named node sets (from physical groups): sorted, unique node indices.
  std::map<std::string, std::vector<int>> node_sets;

  Eigen::Index num_nodes() const { return nodes.cols(); }
  Eigen::Index num_dofs() const { return 3 * nodes.cols(); }
  /// Total element count over all blocks.
  Eigen::Index num_elements() const;
};

/// The SHA-256 digest of the mesh content (node coordinates; each block's element type, region
/// and connectivity), as 64 hex digits: equal meshes give equal digests, whatever file or
/// mesher version produced them.
std::string MeshSha256(const Mesh& mesh);

}  // namespace flexmbs::fem
