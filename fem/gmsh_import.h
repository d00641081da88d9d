#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "fem/mesh.h"

namespace flexmbs::fem {

/// How to turn a geometry file into a solid mesh.
struct MeshingOptions {
  double mesh_size_m = 0.0;  ///< largest element edge [m]; 0 keeps the sizes in the file
  int element_order = 2;     ///< 1 (tet4, hex8, wedge6) or 2 (tet10, hex20, wedge15)
};

/// Meshes a `.geo` or `.step`/`.stp` file with gmsh (3-D, quadratic elements incomplete, i.e.
/// serendipity hex20/wedge15), or reads a ready `.msh` file as it is. Elements come from the
/// physical volumes (each becomes a region named after it), or from every volume if the file
/// defines none. `node_set_names` are physical groups of any dimension whose nodes are
/// collected. Materials are left default: the caller assigns them per region.
/// Throws InputError naming `path` for a missing or unreadable file, a gmsh error, an unknown
/// physical group, a mesh without volume elements, or an unsupported element type.
Mesh ImportMesh(const std::filesystem::path& path, const MeshingOptions& options,
                const std::vector<std::string>& node_set_names);

}  // namespace flexmbs::fem
