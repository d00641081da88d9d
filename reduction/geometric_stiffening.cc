#include "reduction/geometric_stiffening.h"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>

#include "core/centrifugal.h"
#include "core/error.h"
#include "fem/geometric_stiffness.h"
#include "reduction/sid_invariants.h"
#include "reduction/static_response.h"

namespace flexmbs::reduction {
namespace {

using Index = Eigen::Index;

constexpr Index kBodyCases = 12;  // t_x..t_z, r_x..r_z, omega_1..omega_6

Index NumNodeCases(const InterfaceSpec& node) { return node.coupling == Coupling::kNodes ? 3 : 6; }

// StiffeningProjection::kAssembled (see the header). S (N x 3n, row-major) holds the modes'
// components, so K_Gs S is one pass over K_Gs with contiguous rows.
std::vector<Eigen::MatrixXd> AssembledProjection(const fem::Mesh& mesh, const Eigen::MatrixXd& X,
                                                 const Eigen::MatrixXd& Phi) {
  const Index n = Phi.cols();
  const ModeComponents S = SplitModeComponents(Phi);
  std::vector<Eigen::MatrixXd> K0(static_cast<std::size_t>(X.cols()), Eigen::MatrixXd::Zero(n, n));
  ModeComponents K_S;
  for (Index c = 0; c < X.cols(); ++c) {
    if (X.col(c).isZero(0.0)) continue;  // a load carried by the hold: no stress
    // K_G = K_Gs (x) I_3 (fem/geometric_stiffness.h), the structure ScalarMassMatrix extracts.
    const Eigen::SparseMatrix<double> K_Gs = ScalarMassMatrix(fem::AssembleGeometricStiffness(mesh, X.col(c)));
    K_S.noalias() = K_Gs * S;
    Eigen::MatrixXd& K = K0[static_cast<std::size_t>(c)];
    for (Index a = 0; a < 3; ++a) {
      K.triangularView<Eigen::Lower>() += S.middleCols(a * n, n).transpose() * K_S.middleCols(a * n, n);
    }
    K = K.selfadjointView<Eigen::Lower>();
  }
  return K0;
}

}  // namespace

// The switch, measured by bench_sid_invariants (bench/README.md, "SID data") and a sweep of C
// on tet10 bars, 1 core. Time element / assembled at C = 18 (ratio > 1: assembled faster),
// 1.9e4, 9.9e4 and 2.9e5 DOF, two runs:
//   n = 10: 0.19-0.23, n = 20: 0.25-0.50, n = 30: 1.0-1.2, n = 40: 1.7, n = 50: 1.9-2.6,
//   n = 100: 4.1-5.9.
// Both ways cost O(DOF) at fixed n and C (measured DOF exponents 0.95-1.3), so the crossover
// does not move with the body's size. It moves with C: the element way's point products
// (18 n^2 per point) are shared by all cases, while the assembled way pays per case (one
// assembly of K_G and one projection), so more cases favour the element way; crossovers
// measured at 1.9e4 DOF: about 28 modes at C = 12, 30 at C = 18, 33 at C = 24, 38-40 at C = 48
// (+-4: a shared machine), hence n >= 24 + C / 3, held at 40 beyond C = 48 (not measured
// above). Below the crossover the n-independent assembly of the C matrices K_G dominates the
// assembled way (0.28 of 0.38 s at n = 10, 1.9e4 DOF). Projecting the full K_G instead of its
// scalar part (Phi^T (K_G Phi), one pass over K_G per column of Phi) was 3-6x slower at
// n = 100 and put the crossover at about 60.
bool AssembledProjectionIsFaster(Index num_modes, Index num_cases) {
  return num_modes >= std::min<Index>(24 + num_cases / 3, 40);
}

std::vector<Eigen::MatrixXd> ProjectedStiffeningMatrices(const fem::Mesh& mesh, const Eigen::MatrixXd& X,
                                                         const Eigen::MatrixXd& Phi, StiffeningProjection how) {
  if (how == StiffeningProjection::kAuto) {
    how = AssembledProjectionIsFaster(Phi.cols(), X.cols()) ? StiffeningProjection::kAssembled
                                                            : StiffeningProjection::kElementByElement;
  }
  if (how == StiffeningProjection::kElementByElement) return fem::ProjectedGeometricStiffness(mesh, X, Phi);
  if (X.rows() != mesh.num_dofs() || Phi.rows() != mesh.num_dofs()) {
    throw InputError(fmt::format("geometric stiffening: the responses have {} rows and the basis {}, the mesh {} DOF",
                                 X.rows(), Phi.rows(), mesh.num_dofs()));
  }
  return AssembledProjection(mesh, X, Phi);
}

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
  F.leftCols(kBodyCases) = model.mass().Times(b);

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
                                            std::span<const InterfaceSpec> nodes, const HeldFactorization* held) {
  ValidateModel(model);
  if (mesh.num_nodes() != model.nodes.cols()) {
    throw InputError(fmt::format("geometric stiffening: the mesh has {} nodes, the model {}", mesh.num_nodes(),
                                 model.nodes.cols()));
  }
  if (Phi.rows() != model.num_dofs()) {
    throw InputError(fmt::format("geometric stiffening: the basis has {} rows, the model {} DOF", Phi.rows(),
                                 model.num_dofs()));
  }
  const Eigen::MatrixXd F = BuildStiffeningLoads(model, nodes);
  const StaticResponses responses = SolveStaticResponses(model, held_by, F, "geometric stiffening", held);
  std::vector<Eigen::MatrixXd> K0 = ProjectedStiffeningMatrices(mesh, responses.X, Phi);

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
