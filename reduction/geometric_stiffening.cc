#include "reduction/geometric_stiffening.h"

#include <fmt/format.h>

#include <Eigen/Geometry>

#include "core/error.h"
#include "fem/geometric_stiffness.h"
#include "reduction/sid_invariants.h"
#include "reduction/static_response.h"

namespace flexmbs::reduction {
namespace {

using Index = Eigen::Index;

constexpr Index kBodyCases = 12;  // t_x..t_z, r_x..r_z, omega_1..omega_6

Index NumNodeCases(const InterfaceSpec& node) { return node.coupling == Coupling::kNodes ? 3 : 6; }

}  // namespace

Eigen::MatrixXd BuildStiffeningLoads(const FeModel& model, std::span<const InterfaceSpec> nodes) {
  const Index num_nodes = model.nodes.cols();
  Index num_cases = kBodyCases;
  for (const InterfaceSpec& node : nodes) num_cases += NumNodeCases(node);

  // Body forces per unit mass at the nodes, then f = M b (exact for b linear in r).
  Eigen::MatrixXd b(3 * num_nodes, kBodyCases);
  for (Index n = 0; n < num_nodes; ++n) {
    const Eigen::Vector3d r = model.nodes.col(n);
    for (int a = 0; a < 3; ++a) {
      b.block<3, 1>(3 * n, a) = -Eigen::Vector3d::Unit(a);
      b.block<3, 1>(3 * n, 3 + a) = -Eigen::Vector3d::Unit(a).cross(r);
    }
    for (int l = 0; l < 6; ++l) b.block<3, 1>(3 * n, 6 + l) = -CentrifugalBasis()[static_cast<std::size_t>(l)] * r;
  }
  Eigen::MatrixXd F = Eigen::MatrixXd::Zero(3 * num_nodes, num_cases);
  F.leftCols(kBodyCases) = model.M * b;

  Index column = kBodyCases;
  for (const InterfaceSpec& node : nodes) {
    for (const int v : node.nodes) {
      if (v < 0 || v >= num_nodes) {
        throw InputError(fmt::format("geometric stiffening: node '{}': FE node {} is outside the mesh's node range "
                                     "[0, {})", node.name, v, num_nodes));
      }
    }
    if (node.coupling == Coupling::kNodes) {
      if (node.nodes.size() != 1) {
        throw InputError(fmt::format("geometric stiffening: node '{}': a node-set node must have exactly one FE node, "
                                     "not {} (couple several rigidly or by averaging)", node.name, node.nodes.size()));
      }
      for (int a = 0; a < 3; ++a) F(3 * Index{node.nodes[0]} + a, column++) = 1.0;
      continue;
    }
    // A unit force / moment at the marker acts on the nodes as W^T e.
    const Eigen::MatrixXd Wt = Eigen::MatrixXd(RigidFitOperator(model.nodes, node)).transpose();
    F.middleCols(column, 6) = Wt;
    column += 6;
  }
  return F;
}

StiffeningResult ComputeGeometricStiffening(const fem::Mesh& mesh, const FeModel& model,
                                            const BoundaryConditions& held_by, const Eigen::MatrixXd& Phi,
                                            std::span<const InterfaceSpec> nodes) {
  ValidateModel(model);
  if (mesh.num_nodes() != model.nodes.cols()) {
    throw InputError(fmt::format("geometric stiffening: the mesh has {} nodes, the model {}", mesh.num_nodes(),
                                 model.nodes.cols()));
  }
  if (Phi.rows() != model.K.rows()) {
    throw InputError(fmt::format("geometric stiffening: the basis has {} rows, the model {} DOF", Phi.rows(),
                                 model.K.rows()));
  }
  const Eigen::MatrixXd F = BuildStiffeningLoads(model, nodes);
  const StaticResponses responses = SolveStaticResponses(model, held_by, F, "geometric stiffening");
  std::vector<Eigen::MatrixXd> K0 = fem::ProjectedGeometricStiffness(mesh, responses.X, Phi);

  StiffeningResult result;
  auto take = [&, c = std::size_t{0}]() mutable { return std::move(K0[c++]); };
  for (Eigen::MatrixXd& K : result.body.K0t) K = take();
  for (Eigen::MatrixXd& K : result.body.K0r) K = take();
  for (Eigen::MatrixXd& K : result.body.K0omega) K = take();
  for (const InterfaceSpec& node : nodes) {
    NodeStiffening& s = result.nodes.emplace_back();
    for (Eigen::MatrixXd& K : s.K0F) K = take();
    if (node.coupling == Coupling::kNodes) continue;
    for (Eigen::MatrixXd& K : s.K0M) K = take();
  }
  return result;
}

}  // namespace flexmbs::reduction
