#pragma once

// The outer surface of a solid mesh as polygons: the faces of volume elements that belong to
// exactly one element, oriented outward, for contact surfaces (sid::ContactSurface).

#include <Eigen/Core>
#include <array>
#include <vector>

#include "fem/mesh.h"

namespace flexmbs::fem {

/// One face of a volume element on the mesh boundary. Nodes in the element face's order: the
/// corners counter-clockwise seen from outside the element, then (quadratic elements) the
/// mid-side node of edge corner k -> corner k + 1 for each k.
struct BoundaryFace {
  std::array<int, 8> nodes{};  ///< node indices (0-based into Mesh::nodes); num_nodes used
  int num_corners = 0;         ///< 3 or 4
  int num_nodes = 0;           ///< num_corners (linear) or 2 num_corners (quadratic)
};

/// The faces of all volume elements of `mesh` that no other element shares (matched by their
/// corner nodes), in block and element order. Orientation: outward for elements with a positive
/// Jacobian (the face tables are those of gmsh's reference elements, ReferenceElement).
std::vector<BoundaryFace> BoundaryFaces(const Mesh& mesh);

/// A polygon mesh of (part of) the boundary, in the body frame B, undeformed.
struct PolygonSurface {
  std::vector<int> fe_nodes;    ///< per vertex: its FE node, ascending
  Eigen::MatrixX3d vertices;    ///< V x 3: p_BoV_B [m]
  std::vector<int> face_sizes;  ///< per polygon: 3 or 4
  std::vector<int>
      face_vertices;  ///< vertex indices (0-based), concatenated; counter-clockwise from outside
  Eigen::MatrixX3d face_normals;  ///< F x 3: unit outward normals
  /// Per polygon: |a| [m^2] with a = 1/2 sum_k v_k x v_(k+1) its vector area (Newell), which is
  /// the area of a planar polygon; the normal is a / |a|.
  Eigen::VectorXd face_areas;

  Eigen::Index num_faces() const { return static_cast<Eigen::Index>(face_sizes.size()); }
};

/// The boundary faces (of `faces`, from BoundaryFaces(mesh)) whose nodes all lie in
/// `node_set` (sorted node indices), as polygons through the FE nodes. A quadratic face is split
/// through its mid-side nodes so that the polygons follow the curved face: a 6-node triangle into
/// 4 triangles (3 corner triangles and the middle one), an 8-node quadrilateral into 4 corner
/// triangles and the inner quadrilateral of its mid-side nodes. Empty if no face qualifies.
PolygonSurface BoundarySurface(const Mesh& mesh, const std::vector<BoundaryFace>& faces,
                               const std::vector<int>& node_set);

/// BoundarySurface(mesh, BoundaryFaces(mesh), node_set).
PolygonSurface BoundarySurface(const Mesh& mesh, const std::vector<int>& node_set);

}  // namespace flexmbs::fem
