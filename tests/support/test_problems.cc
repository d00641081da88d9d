#include "tests/support/test_problems.h"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <cmath>
#include <string>

namespace flexmbs::testing {

fem::IsotropicMaterial Steel() { return {"steel", 210e9, 0.3, 7850.0}; }

fem::Mesh HexBox(const Eigen::Vector3i& cells, const Eigen::Vector3d& size, const fem::IsotropicMaterial& left,
                 const fem::IsotropicMaterial& right, double split_x) {
  fem::Mesh mesh;
  const Eigen::Vector3i points = cells.array() + 1;
  const auto node = [&](int i, int j, int k) { return i + points(0) * (j + points(1) * k); };
  mesh.nodes.resize(3, points.prod());
  for (int k = 0; k < points(2); ++k) {
    for (int j = 0; j < points(1); ++j) {
      for (int i = 0; i < points(0); ++i) {
        mesh.nodes.col(node(i, j, k)) = Eigen::Vector3d(size(0) * i / cells(0), size(1) * j / cells(1),
                                                        size(2) * k / cells(2));
      }
    }
  }
  for (Eigen::Index n = 0; n < mesh.num_nodes(); ++n) mesh.node_ids.push_back(static_cast<std::size_t>(n) + 1);

  std::vector<std::vector<int>> columns(2);
  for (int k = 0; k < cells(2); ++k) {
    for (int j = 0; j < cells(1); ++j) {
      for (int i = 0; i < cells(0); ++i) {
        // gmsh hexahedron order: bottom face counter-clockwise, then the top face.
        const int hex[8] = {node(i, j, k),         node(i + 1, j, k),         node(i + 1, j + 1, k),
                            node(i, j + 1, k),     node(i, j, k + 1),         node(i + 1, j, k + 1),
                            node(i + 1, j + 1, k + 1), node(i, j + 1, k + 1)};
        const double centre_x = size(0) * (i + 0.5) / cells(0);
        const int block = (split_x > 0.0 && centre_x >= split_x) ? 1 : 0;
        columns[static_cast<std::size_t>(block)].insert(columns[static_cast<std::size_t>(block)].end(), hex, hex + 8);
      }
    }
  }
  std::size_t next_id = 1;
  for (int b = 0; b < 2; ++b) {
    const std::vector<int>& c = columns[static_cast<std::size_t>(b)];
    if (c.empty()) continue;
    fem::ElementBlock block;
    block.type = fem::ElementType::kHex8;
    block.region = b == 0 ? "left" : "right";
    block.material = b == 0 ? left : right;
    block.connectivity = Eigen::Map<const fem::Connectivity>(c.data(), 8, static_cast<Eigen::Index>(c.size() / 8));
    for (Eigen::Index e = 0; e < block.num_elements(); ++e) block.element_ids.push_back(next_id++);
    mesh.blocks.push_back(std::move(block));
  }
  return mesh;
}

fem::Mesh HexBox(const Eigen::Vector3i& cells, const Eigen::Vector3d& size,
                 const fem::IsotropicMaterial& material) {
  return HexBox(cells, size, material, material, 0.0);
}

DiagonalProblem FiveFoldLowestEigenvalue(int n) {
  std::vector<Eigen::Triplet<double>> k, m;
  for (int i = 0; i < n; ++i) {
    k.emplace_back(i, i, i < 5 ? 1.0 : 1.0 + (i - 4));
    m.emplace_back(i, i, 1.0);
  }
  DiagonalProblem p{Eigen::SparseMatrix<double>(n, n), Eigen::SparseMatrix<double>(n, n)};
  p.K.setFromTriplets(k.begin(), k.end());
  p.M.setFromTriplets(m.begin(), m.end());
  return p;
}

std::vector<int> NodesOnPlane(const fem::Mesh& mesh, int axis, double value) {
  std::vector<int> nodes;
  for (Eigen::Index n = 0; n < mesh.num_nodes(); ++n) {
    if (std::abs(mesh.nodes(axis, n) - value) <= 1e-12) nodes.push_back(static_cast<int>(n));
  }
  return nodes;
}

DenseEigen SolveDense(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M, double sigma) {
  const Eigen::MatrixXd Md(M);
  const Eigen::MatrixXd Ad = Eigen::MatrixXd(K) - sigma * Md;
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(Md, Ad, Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
  const Eigen::Index n = Md.rows();
  DenseEigen result{Eigen::VectorXd(n), Eigen::MatrixXd(n, n)};
  // mu ascending <=> lambda descending: reverse. x^T A x = 1, so x^T M x = mu.
  for (Eigen::Index j = 0; j < n; ++j) {
    const double mu = solver.eigenvalues()(n - 1 - j);
    result.values(j) = sigma + 1.0 / mu;
    result.vectors.col(j) = solver.eigenvectors().col(n - 1 - j) / std::sqrt(mu);
  }
  return result;
}

double LargestPrincipalAngleSine(const Eigen::SparseMatrix<double>& M, const Eigen::MatrixXd& A,
                                 const Eigen::MatrixXd& B) {
  // M-orthonormal bases via the Cholesky factor of the (dense) M: with M = L L^T, span(A) is
  // M-orthonormal iff L^T A is orthonormal.
  const Eigen::MatrixXd Md(M);
  const Eigen::LLT<Eigen::MatrixXd> llt(Md);
  const Eigen::MatrixXd LA = llt.matrixU() * A;
  const Eigen::MatrixXd LB = llt.matrixU() * B;
  const Eigen::MatrixXd QA = Eigen::HouseholderQR<Eigen::MatrixXd>(LA).householderQ() *
                             Eigen::MatrixXd::Identity(LA.rows(), LA.cols());
  const Eigen::MatrixXd QB = Eigen::HouseholderQR<Eigen::MatrixXd>(LB).householderQ() *
                             Eigen::MatrixXd::Identity(LB.rows(), LB.cols());
  const Eigen::MatrixXd residual = QA - QB * (QB.transpose() * QA);
  return Eigen::JacobiSVD<Eigen::MatrixXd>(residual).singularValues()(0);
}

}  // namespace flexmbs::testing
