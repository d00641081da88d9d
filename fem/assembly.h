#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <span>

#include "fem/element_integrator.h"
#include "fem/mesh.h"

namespace flexmbs::fem {

/// The global FE matrices of a mesh, DOF 3 n + i (node n, axis i of the body frame).
/// Both are symmetric and stored in full (both triangles), compressed column storage.
struct SystemMatrices {
  Eigen::SparseMatrix<double> stiffness;  ///< K [N/m]
  Eigen::SparseMatrix<double> mass;       ///< M [kg]
};

/// Receives the element matrices of an assembly loop, one element at a time. Lets one loop
/// fill a serial CSC matrix, a distributed PETSc matrix or a test's dense matrix.
class ElementMatrixVisitor {
 public:
  virtual ~ElementMatrixVisitor() = default;
  /// `nodes`: the element's global node indices; `K_e`: 3n x 3n stiffness;
  /// `m_e`: n x n scalar mass (the element mass is m_e (x) I_3).
  virtual void Visit(std::span<const int> nodes, const Eigen::MatrixXd& K_e,
                     const Eigen::MatrixXd& m_e) = 0;
};

/// Computes the element matrices of the elements with global indices [first, end) (blocks in
/// order, elements in order within a block) and hands each to `visitor`. Throws InputError
/// naming the element and its nodes if an element's Jacobian determinant is not positive.
void VisitElementMatrices(const Mesh& mesh, MassMatrixKind mass_kind, Eigen::Index first,
                          Eigen::Index end, ElementMatrixVisitor& visitor);

/// The zero matrix with the sparsity pattern of AssembleSystem (3 num_nodes square, full
/// storage): a 3x3 block for every pair of nodes that share an element.
Eigen::SparseMatrix<double> SystemPattern(const Mesh& mesh);

/// A(3 na + i, 3 nb + i) += a_e(a, b) for i = 0, 1, 2, na = nodes[a]: adds the element matrix
/// a_e (x) I_3 of a scalar element matrix a_e (n x n, e.g. a mass or geometric stiffness) into
/// A, which has SystemPattern's sparsity.
void AddScalarElementMatrix(std::span<const int> nodes, const Eigen::MatrixXd& a_e,
                            Eigen::SparseMatrix<double>* A);

/// Assembles K and M of the whole mesh. The sparsity pattern is built once from the node
/// adjacency and shared by both matrices (a lumped M is stored on that pattern's diagonal
/// only). Throws InputError for an element with a non-positive Jacobian.
SystemMatrices AssembleSystem(const Mesh& mesh, MassMatrixKind mass_kind);

}  // namespace flexmbs::fem
