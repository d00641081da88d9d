#pragma once

// Small meshes for the fem verification tests: structured boxes of every element type built
// directly as fem::Mesh (no gmsh), and one gmsh-meshed cylinder with curved tet10.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <random>
#include <vector>

#include "fem/mesh.h"

namespace flexmbs::fem::testing {

/// A steel-like material (E = 210 GPa, nu = 0.3, rho = 7850 kg/m^3).
IsotropicMaterial Steel();

/// A structured mesh of the box [0, size(0)] x [0, size(1)] x [0, size(2)]: one block, or two
/// for a mixed mesh.
struct BoxMesh {
  Mesh mesh;
  std::vector<bool> on_boundary;  ///< per node: lies on a face of the box
  /// Per mid-side node of a quadratic mesh, the two corner nodes of its edge; -1 otherwise.
  std::vector<std::array<int, 2>> edge_of;
  Eigen::Vector3d cell_size;  ///< edge lengths of one structured cell [m]
};

/// A box of `cells` structured cells of element type `type`: each cell is one hexahedron,
/// six tetrahedra (Kuhn split along the cell's main diagonal, conforming) or two wedges (split
/// along the xy diagonal). Quadratic types get straight edges with mid-side nodes at the edge
/// midpoints. All elements have positive Jacobians, nodes are in gmsh order.
/// Mixed mesh: cells with x index >= `second_from` are of `second_type`, in a second block
/// (region "box 2"); only hexahedra and wedges of one order mix conformingly.
BoxMesh StructuredBox(ElementType type, const Eigen::Vector3i& cells, const Eigen::Vector3d& size,
                      ElementType second_type, int second_from);
/// The single-type box (see above).
inline BoxMesh StructuredBox(ElementType type, const Eigen::Vector3i& cells,
                             const Eigen::Vector3d& size) {
  return StructuredBox(type, cells, size, type, cells(0));
}

/// A tet10 mesh of a solid cylinder (axis along z from `base`), meshed by gmsh through
/// fem::ImportMesh from a small OpenCASCADE .geo file written to a temporary directory. Mid-side
/// nodes on the curved surface lie on the cylinder, so boundary elements have curved faces.
/// Every block gets Steel().
Mesh GmshCylinder(double radius, double length, const Eigen::Vector3d& base, double mesh_size);

/// Moves every interior (non-boundary) corner node by a uniform random offset of at most
/// `corner_fraction` of the cell size per axis, re-centres mid-side nodes on their (straight)
/// edges, then moves interior mid-side nodes off their edges by at most `curve_fraction` of the
/// cell size (curved edges). The box's outer surface is unchanged.
void DistortInterior(BoxMesh* box, double corner_fraction, double curve_fraction,
                     std::mt19937* rng);

/// Maps every node x -> R x + t (a rigid motion of the whole mesh).
void Transform(Mesh* mesh, const Eigen::Matrix3d& R, const Eigen::Vector3d& t);

/// The smallest Jacobian determinant of all elements at their stiffness and mass points.
double MinJacobian(const Mesh& mesh);

/// The block A(rows, cols) of the sparse matrix A, as a new sparse matrix.
Eigen::SparseMatrix<double> Submatrix(const Eigen::SparseMatrix<double>& A,
                                      const std::vector<int>& rows, const std::vector<int>& cols);

/// A random rotation matrix (uniform enough for tests: from a random unit quaternion).
Eigen::Matrix3d RandomRotation(std::mt19937* rng);

}  // namespace flexmbs::fem::testing
