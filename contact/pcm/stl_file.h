#pragma once
// Triangle surface meshes from STL files (ASCII or binary) for the Polygonal Contact Model
// (docs/contact.md, "Polygonal Contact Model"; docs/scene.md, `pcm_contact`).

#include <filesystem>

#include "contact/geometry/sphere_surface.h"

namespace flexmbs::contact {

/// The triangles of STL file `file` as a PolygonMesh in the file's frame and units (vertices_W
/// holds them as read; the caller places the mesh). A file starting with "solid" whose length is
/// not the binary layout's 84 + 50 n bytes is read as ASCII, otherwise as binary. Vertices with
/// exactly equal coordinates are merged into one, so that neighbouring triangles share their
/// edges; the facets' stored normals are ignored (the vertex order gives the orientation).
/// Throws a one-line InputError "STL file '<file>': <problem>" for an unreadable file, a
/// truncated binary file, malformed ASCII (with its line), no triangles, or a non-finite
/// coordinate.
PolygonMesh ReadStlFile(const std::filesystem::path& file);

}  // namespace flexmbs::contact
