#include "fem/geometric_stiffness.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <span>

#include "core/error.h"
#include "fem/assembly.h"
#include "fem/element_integrator.h"

namespace flexmbs::fem {
namespace {

using Index = Eigen::Index;

// The symmetric stress components in the order the projection stacks them: (k, l) pairs.
constexpr std::array<std::array<int, 2>, 6> kVoigtPairs{{{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {2, 0}}};
// Upper bound on the entries of the buffer of mode-gradient products (16 MB).
constexpr Index kBufferEntries = Index{1} << 21;

void CheckJacobian(const ElementBlock& block, Index e, double min_det) {
  if (!(min_det > 0.0)) {
    throw InputError(fmt::format("region '{}': {} element {} has non-positive Jacobian determinant {:.3g} at a "
                                 "geometric-stiffness point",
                                 block.region, Traits(block.type).name,
                                 block.element_ids[static_cast<std::size_t>(e)], min_det));
  }
}

void CheckRows(const Mesh& mesh, Index rows, const char* what) {
  if (rows != mesh.num_dofs()) {
    throw InputError(fmt::format("geometric stiffness: {} has {} rows, the mesh {} DOF", what, rows, mesh.num_dofs()));
  }
}

}  // namespace

Eigen::SparseMatrix<double> AssembleGeometricStiffness(const Mesh& mesh, const Eigen::VectorXd& u) {
  CheckRows(mesh, u.size(), "the displacement");
  Eigen::SparseMatrix<double> K_G = SystemPattern(mesh);
  Eigen::MatrixXd k_G;
  Eigen::Matrix3Xd X, u_e;
  for (const ElementBlock& block : mesh.blocks) {
    ElementIntegrator integrator(block.type);
    const int n = integrator.num_nodes();
    X.resize(3, n);
    u_e.resize(3, n);
    for (Index e = 0; e < block.num_elements(); ++e) {
      const auto nodes = block.connectivity.col(e);
      for (int a = 0; a < n; ++a) {
        X.col(a) = mesh.nodes.col(nodes(a));
        u_e.col(a) = u.segment<3>(3 * Index{nodes(a)});
      }
      CheckJacobian(block, e, integrator.ScalarGeometricStiffness(X, block.material, u_e, &k_G));
      AddScalarElementMatrix(std::span<const int>(nodes.data(), static_cast<std::size_t>(n)), k_G, &K_G);
    }
  }
  return K_G;
}

std::vector<Eigen::MatrixXd> ProjectedGeometricStiffness(const Mesh& mesh, const Eigen::MatrixXd& U,
                                                         const Eigen::MatrixXd& Phi) {
  CheckRows(mesh, U.rows(), "the displacement matrix");
  CheckRows(mesh, Phi.rows(), "the basis");
  const Index m = Phi.cols(), C = U.cols();
  // K0.col(c) = the upper triangle (packed by columns) of Phi^T K_G(sigma(u_c)) Phi = the sum
  // over points of P (products of mode gradients, 6 packed triangles per point) times S (the
  // six stress components of every field, 6 x C per point), flushed from buffers of `capacity`
  // points as one matrix product.
  const Index packed = m * (m + 1) / 2;
  Eigen::MatrixXd K0 = Eigen::MatrixXd::Zero(packed, C);
  const Index capacity = std::clamp<Index>(kBufferEntries / std::max<Index>(6 * packed, 1), 1, 512);
  Eigen::MatrixXd P(packed, 6 * capacity), S(6 * capacity, C);
  Index filled = 0;
  auto flush = [&] {
    K0.noalias() += P.leftCols(6 * filled) * S.topRows(6 * filled);
    filled = 0;
  };

  Eigen::MatrixXd PhiT_e, UT_e, Z_phi, Z_u, product(m, m);
  Eigen::VectorXd weights;
  std::vector<Eigen::Matrix3Xd> gradients;
  Eigen::Matrix3Xd X;
  for (const ElementBlock& block : mesh.blocks) {
    ElementIntegrator integrator(block.type);
    const int n = integrator.num_nodes();
    X.resize(3, n);
    PhiT_e.resize(3 * m, n);  // (i m + j, a): mode j at node a along axis i
    UT_e.resize(3 * C, n);    // (i C + c, a): field c at node a along axis i
    for (Index e = 0; e < block.num_elements(); ++e) {
      const auto nodes = block.connectivity.col(e);
      for (int a = 0; a < n; ++a) {
        X.col(a) = mesh.nodes.col(nodes(a));
        for (int i = 0; i < 3; ++i) {
          PhiT_e.block(i * m, a, m, 1) = Phi.row(3 * Index{nodes(a)} + i).transpose();
          UT_e.block(i * C, a, C, 1) = U.row(3 * Index{nodes(a)} + i).transpose();
        }
      }
      CheckJacobian(block, e, integrator.GeometricStiffnessPoints(X, &weights, &gradients));
      for (std::size_t q = 0; q < gradients.size(); ++q) {
        const double w = weights(static_cast<Index>(q));
        Z_phi.noalias() = PhiT_e * gradients[q].transpose();  // (i m + j, k) = d phi_j,i / dx_k
        Z_u.noalias() = UT_e * gradients[q].transpose();      // (i C + c, k) = d u_c,i / dx_k
        for (std::size_t v = 0; v < kVoigtPairs.size(); ++v) {
          const auto [k, l] = kVoigtPairs[v];
          // Y_k(j, i) = d phi_j,i / dx_k; P_v = Y_k Y_l^T (+ its transpose for k != l).
          const Eigen::Map<const Eigen::MatrixXd> Y_k(Z_phi.col(k).data(), m, 3);
          const Eigen::Map<const Eigen::MatrixXd> Y_l(Z_phi.col(l).data(), m, 3);
          product.noalias() = w * Y_k * Y_l.transpose();
          double* column = P.col(6 * filled + static_cast<Index>(v)).data();
          for (Index j = 0; j < m; ++j) {
            for (Index i = 0; i <= j; ++i) *column++ = k == l ? product(i, j) : product(i, j) + product(j, i);
          }
        }
        for (Index c = 0; c < C; ++c) {
          Eigen::Matrix3d grad_u;
          for (int i = 0; i < 3; ++i) grad_u.row(i) = Z_u.row(i * C + c);
          const Eigen::Matrix3d sigma = LinearElasticStress(grad_u, block.material);
          for (std::size_t v = 0; v < kVoigtPairs.size(); ++v) {
            S(6 * filled + static_cast<Index>(v), c) = sigma(kVoigtPairs[v][0], kVoigtPairs[v][1]);
          }
        }
        if (++filled == capacity) flush();
      }
    }
  }
  flush();
  std::vector<Eigen::MatrixXd> result(static_cast<std::size_t>(C), Eigen::MatrixXd(m, m));
  for (Index c = 0; c < C; ++c) {
    Eigen::MatrixXd& K = result[static_cast<std::size_t>(c)];
    const double* column = K0.col(c).data();
    for (Index j = 0; j < m; ++j) {
      for (Index i = 0; i <= j; ++i) K(i, j) = K(j, i) = *column++;
    }
  }
  return result;
}

}  // namespace flexmbs::fem
