#include "fem/nodal_rotation.h"

#include <fmt/format.h>

#include <Eigen/LU>
#include <optional>

#include "core/error.h"
#include "fem/element_integrator.h"
#include "fem/reference_element.h"

namespace flexmbs::fem {
namespace {

// The source file's tag of element e of `block` (its 1-based position if the block has none).
std::size_t ElementTag(const ElementBlock& block, Eigen::Index e) {
  const auto k = static_cast<std::size_t>(e);
  return k < block.element_ids.size() ? block.element_ids[k] : k + 1;
}

}  // namespace

Eigen::MatrixXd NodalRotation(const Mesh& mesh, int node, const Eigen::MatrixXd& Phi) {
  FLEXMBS_CHECK(node >= 0 && node < mesh.num_nodes(), "node index in range");
  FLEXMBS_CHECK(Phi.rows() == mesh.num_dofs(), "one row of Phi per DOF");
  Eigen::MatrixXd weighted_sum = Eigen::MatrixXd::Zero(3, Phi.cols());
  double total_volume = 0.0;
  for (const ElementBlock& block : mesh.blocks) {
    const ReferenceElement& reference = ReferenceElement::Of(block.type);
    std::optional<ElementIntegrator> integrator;
    for (Eigen::Index e = 0; e < block.num_elements(); ++e) {
      Eigen::Index local = -1;
      for (Eigen::Index a = 0; a < block.connectivity.rows(); ++a) {
        if (block.connectivity(a, e) == node) local = a;
      }
      if (local < 0) continue;
      const Eigen::Index num_element_nodes = block.connectivity.rows();
      Eigen::Matrix3Xd X(3, num_element_nodes);
      for (Eigen::Index a = 0; a < num_element_nodes; ++a)
        X.col(a) = mesh.nodes.col(block.connectivity(a, e));
      Eigen::Matrix3Xd dN;
      reference.Evaluate(reference.nodes().col(local), nullptr, &dN);
      const Eigen::Matrix3d J = dN * X.transpose();  // J(i, j) = dx_j / dxi_i
      if (!(J.determinant() > 0.0)) {
        throw InputError(fmt::format(
            "region '{}': {} element {}: Jacobian {:g} at node {} is not positive", block.region,
            Traits(block.type).name, ElementTag(block, e), J.determinant(), node));
      }
      const Eigen::Matrix3Xd grad = J.inverse() * dN;  // grad(j, a) = dN_a / dx_j at the node
      if (!integrator) integrator.emplace(block.type);
      double volume = 0.0;
      Eigen::Vector3d first;
      Eigen::Matrix3d second;
      integrator->VolumeMoments(X, 1.0, &volume, &first, &second);
      // psi_e = 1/2 sum_a grad N_a x u_a, weighted by the element volume.
      for (Eigen::Index a = 0; a < num_element_nodes; ++a) {
        const Eigen::Vector3d g = 0.5 * volume * grad.col(a);
        const auto u = Phi.middleRows<3>(3 * static_cast<Eigen::Index>(block.connectivity(a, e)));
        weighted_sum.row(0) += g(1) * u.row(2) - g(2) * u.row(1);
        weighted_sum.row(1) += g(2) * u.row(0) - g(0) * u.row(2);
        weighted_sum.row(2) += g(0) * u.row(1) - g(1) * u.row(0);
      }
      total_volume += volume;
    }
  }
  if (total_volume == 0.0) {
    throw InputError(fmt::format("node {}: no element holds it: its rotation is undefined", node));
  }
  return weighted_sum / total_volume;
}

}  // namespace flexmbs::fem
