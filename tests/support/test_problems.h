#pragma once

// Small FE problems built in code (no gmsh) for the eigensolver tests.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "fem/assembly.h"
#include "fem/material.h"
#include "fem/mesh.h"

namespace flexmbs::testing {

/// Steel: E = 210 GPa, nu = 0.3, rho = 7850 kg/m^3.
fem::IsotropicMaterial Steel();

/// A structured hex8 mesh of the box [0, size(0)] x [0, size(1)] x [0, size(2)] with
/// `cells` cells per axis. Elements whose centre has x < split_x form a block of material
/// `left`, the others a block of material `right` (one block if split_x <= 0).
fem::Mesh HexBox(const Eigen::Vector3i& cells, const Eigen::Vector3d& size, const fem::IsotropicMaterial& left,
                 const fem::IsotropicMaterial& right, double split_x = 0.0);
/// A one-material hex8 box.
fem::Mesh HexBox(const Eigen::Vector3i& cells, const Eigen::Vector3d& size,
                 const fem::IsotropicMaterial& material);

/// The nodes of `mesh` with coordinate `axis` equal to `value` (within 1e-12 of the box).
std::vector<int> NodesOnPlane(const fem::Mesh& mesh, int axis, double value);

/// K = diag(1, 1, 1, 1, 1, 2, 3, ..., n - 4), M = I (n x n): a 5-fold lowest eigenvalue that
/// single-vector Lanczos sees only once per run.
struct DiagonalProblem {
  Eigen::SparseMatrix<double> K, M;
};
DiagonalProblem FiveFoldLowestEigenvalue(int n);

/// Reference eigenpairs of K phi = lambda M phi by Eigen's dense generalized solver in
/// shift-invert form: M x = mu (K - sigma M) x (Cholesky of K - sigma M, Householder
/// tridiagonalisation, QR), lambda = sigma + 1 / mu. Ascending, M-orthonormal. The inverted
/// form makes the low eigenvalues accurate relative to themselves (absolute error
/// ~ eps / mu_max = eps (lambda_1 - sigma)); the direct form K x = lambda M x has absolute
/// error ~ eps lambda_max, 1e-4 relative for lambda_1 when lambda_max / lambda_1 = 1e12.
/// K - sigma M must be positive definite.
struct DenseEigen {
  Eigen::VectorXd values;
  Eigen::MatrixXd vectors;
};
DenseEigen SolveDense(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M, double sigma);

/// The sine of the largest principal angle between span(A) and span(B) in the M inner
/// product: the largest singular value of (I - P_B) Q_A, Q_A an M-orthonormal basis of
/// span(A), P_B the M-orthogonal projector onto span(B). Spans of equal dimension; 0 means
/// equal subspaces.
double LargestPrincipalAngleSine(const Eigen::SparseMatrix<double>& M, const Eigen::MatrixXd& A,
                                 const Eigen::MatrixXd& B);

}  // namespace flexmbs::testing
