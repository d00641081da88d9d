#pragma once
// Triangle meshes for the Polygonal Contact Model's tests and bench: icospheres, a flat grid and
// random triangle soups.

#include <Eigen/Core>
#include <cstdint>

#include "contact/geometry/sphere_surface.h"

namespace flexmbs::contact::testing {

/// The icosahedron inscribed in the sphere (centre, radius [m]), each triangle split into four
/// `level` times with the new vertices pushed onto the sphere: 20 * 4^level triangles,
/// counter-clockwise seen from outside, closed.
PolygonMesh Icosphere(const Eigen::Vector3d& centre, double radius, int level);

/// The faces of Icosphere(centre 0, radius, level) whose three vertices lie below z = -0.6 radius:
/// the lower cap, where a sphere falling onto a plate can touch it (all of the sphere's vertices
/// kept).
PolygonMesh LowerCap(double radius, int level);

/// How a quad becomes triangles: two by the diagonal from its first corner, or four about its
/// centre (which keeps the quad's mirror symmetries).
enum class QuadSplit { kDiagonal, kFan };

/// The square [-half_width, half_width]^2 in the plane z = height [m], n x n squares each split
/// into two triangles (four as kFan) counter-clockwise seen from +z (its outward normal): 2 n^2
/// (4 n^2) triangles, open.
PolygonMesh FlatGrid(double half_width, int n, double height, QuadSplit split = QuadSplit::kDiagonal);

/// The box [-h, h] (half extents h [m]) as 12 triangles (24 split as kFan), counter-clockwise
/// seen from outside, closed.
PolygonMesh Box(const Eigen::Vector3d& half_extents, QuadSplit split = QuadSplit::kDiagonal);
/// The mesh's mirror image in the plane x = 0, its faces reordered to stay counter-clockwise.
PolygonMesh MirroredInX(PolygonMesh mesh);

/// `count` triangles with vertices uniform in the cube [0, size]^3, edges up to `edge` [m]
/// (each triangle a random point and two offsets), no shared vertices.
PolygonMesh RandomTriangles(int count, double size, double edge, std::uint32_t seed);

/// Moves every vertex by amplitude * (sin(k y + phase), sin(k z + phase), sin(k x + phase)) [m]:
/// a smooth deformation like a flexible body's.
void Wave(PolygonMesh& mesh, double amplitude, double wave_number, double phase);

}  // namespace flexmbs::contact::testing
