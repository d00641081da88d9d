#pragma once
// The checks on what gmsh returns for a meshed model (node and element arrays), and the mesh
// built from them. Kept apart from the gmsh calls (gmsh_import.cc) so that they can be tested
// and fuzzed (fuzz/mesh_arrays_fuzz.cc) with arrays of any shape.

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "fem/mesh.h"

namespace flexmbs::fem {

/// Volume elements of one gmsh type in one region, as gmsh::model::mesh::getElements returns
/// them for one entity.
struct GmshElementBlock {
  int gmsh_type = 0;
  std::string region;
  std::vector<std::size_t> element_tags;
  std::vector<std::size_t> node_tags;  ///< the element's nodes in gmsh order, element after element
};

/// The model's nodes, as gmsh::model::mesh::getNodes returns them: x, y, z per tag [m].
struct GmshNodes {
  std::vector<std::size_t> tags;
  std::vector<double> coords;
};

/// Builds the mesh (without node sets) from `blocks` (at least one) and `nodes`, after checking
/// them: every block of a supported type and `num_nodes x elements` node tags, three finite
/// coordinates per node tag, and every element node among the tags (a tag given twice: its last
/// coordinates count). The nodes that elements use are numbered in tag order. Throws
/// InputError "<path>: ..." naming the region and element otherwise.
Mesh MeshFromGmshArrays(const std::filesystem::path& path, std::vector<GmshElementBlock> blocks,
                        const GmshNodes& nodes);

/// The mesh's node indices of the node `tags` of a physical group, sorted and unique; tags
/// that no element uses are left out.
std::vector<int> MeshNodesOfTags(const Mesh& mesh, const std::vector<std::size_t>& tags);

}  // namespace flexmbs::fem
