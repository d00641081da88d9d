#pragma once
// What the Polygonal Contact Model requires of a surface (docs/contact.md, "Polygonal Contact
// Model"): triangles, one orientation throughout, and for a body's whole surface no holes.

#include <string_view>

#include "contact/geometry/sphere_surface.h"

namespace flexmbs::contact {

/// Checks `mesh` (named `name` in the messages) is a triangle surface fit for PCM: every face a
/// triangle of three distinct valid vertices and positive area, no directed edge used by two
/// triangles (two neighbours running their shared edge the same way: one of them is flipped),
/// and, if `closed`, every edge shared by exactly two triangles (an edge with one triangle is
/// the rim of a hole). Throws a one-line InputError naming the surface, the face or edge and
/// what is wrong; the caller adds the file and item.
void RequirePcmSurface(const PolygonMesh& mesh, std::string_view name, bool closed);

}  // namespace flexmbs::contact
