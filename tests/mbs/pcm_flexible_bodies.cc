#include "tests/mbs/pcm_flexible_bodies.h"

#include <Eigen/LU>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <memory>
#include <utility>

#include "contact/pcm/contact_element.h"
#include "eigensolvers/eigensolver.h"
#include "fem/assembly.h"
#include "mbs/pcm_surface.h"
#include "reduction/correction_modes.h"
#include "reduction/modal_basis.h"
#include "tests/support/test_problems.h"

namespace flexmbs::mbs::testing {

using Eigen::Index;

ClampedBox MakeClampedBox(const std::string& name, const Eigen::Vector3i& cells, const Eigen::Vector3d& size,
                          const NodeSelection& clamped, const std::string& surface, const NodeSelection& surface_nodes,
                          const NodeSelection& loaded, int normal_modes) {
  static const std::unique_ptr<eigensolvers::Eigensolver> solver = eigensolvers::MakeEigensolver("spectra");
  ClampedBox box;
  FeReducedBody& fe = box.fe;
  fe.mesh = flexmbs::testing::HexBox(cells, size, flexmbs::testing::Steel());
  box.clamped = clamped(fe.mesh);
  fe.mesh.node_sets[surface] = surface_nodes(fe.mesh);
  fem::SystemMatrices matrices = fem::AssembleSystem(fe.mesh, fem::MassMatrixKind::kConsistent);
  fe.K = std::move(matrices.stiffness);
  fe.M = std::move(matrices.mass);
  fe.sid_spec.contact_surfaces = {surface};
  fe.sid_spec.geometric_stiffening = false;
  reduction::BoundaryConditions conditions;
  conditions.supports.push_back({"clamped", box.clamped});
  eigensolvers::EigenOptions eigen;
  eigen.num_modes = normal_modes;
  const reduction::FeModel model{fe.K, fe.M, fe.mesh.nodes};
  const reduction::ReducedBasis modes = reduction::FixedInterfaceModalBasis(model, conditions, eigen, *solver);
  const reduction::LoadSet patch{"patch", loaded(fe.mesh), std::nullopt, reduction::LoadDistribution::kPerNode, {}};
  fe.basis = patch.nodes.empty() ? modes : reduction::AddStaticCorrectionModes(model, modes, std::span(&patch, 1)).basis;
  fe.body = Reduce(fe, fe.basis);
  fe.body.name = name;
  return box;
}

std::vector<int> SideFaceNodes(const fem::Mesh& mesh, double side_x, double side_y) {
  std::vector<int> sides;
  for (const int axis : {0, 1}) {
    for (const double at : {0.0, axis == 0 ? side_x : side_y}) {
      for (const int node : flexmbs::testing::NodesOnPlane(mesh, axis, at)) sides.push_back(node);
    }
  }
  std::sort(sides.begin(), sides.end());
  sides.erase(std::unique(sides.begin(), sides.end()), sides.end());
  return sides;
}

std::vector<int> NodesInBox(const fem::Mesh& mesh, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  std::vector<int> nodes;
  for (Index k = 0; k < mesh.num_nodes(); ++k) {
    const Eigen::Vector3d p = mesh.nodes.col(k);
    if ((p.array() >= lo.array() - 1e-12).all() && (p.array() <= hi.array() + 1e-12).all()) {
      nodes.push_back(static_cast<int>(k));
    }
  }
  return nodes;
}

Unknown Translation(const MultibodySystem& system, int b, int axis) {
  return {system.position_offset(b) + axis, system.velocity_offset(b) + axis};
}

std::vector<Unknown> ModalCoordinates(const MultibodySystem& system, int b) {
  std::vector<Unknown> unknowns;
  for (Index k = 0; k < system.body(b).num_modes(); ++k) {
    unknowns.push_back({system.position_offset(b) + 7 + k, system.velocity_offset(b) + 6 + k});
  }
  return unknowns;
}

int SolveStatics(const MultibodySystem& system, const std::vector<Unknown>& unknowns, const Eigen::VectorXd& extra,
                 double step, double tolerance, Eigen::VectorXd& y) {
  const Index n = static_cast<Index>(unknowns.size());
  y.tail(system.num_velocities()).setZero();
  const auto residual = [&](const Eigen::VectorXd& state) {
    const Eigen::VectorXd h = system.Forces(0.0, state);
    Eigen::VectorXd r(n);
    for (Index k = 0; k < n; ++k) r(k) = h(unknowns[static_cast<std::size_t>(k)].velocity) + extra(k);
    return r;
  };
  for (int iteration = 0; iteration < 30; ++iteration) {
    const Eigen::VectorXd r = residual(y);
    if (r.cwiseAbs().maxCoeff() < tolerance) return iteration;
    Eigen::MatrixXd J(n, n);
    for (Index k = 0; k < n; ++k) {
      Eigen::VectorXd plus = y, minus = y;
      plus(unknowns[static_cast<std::size_t>(k)].position) += step;
      minus(unknowns[static_cast<std::size_t>(k)].position) -= step;
      J.col(k) = (residual(plus) - residual(minus)) / (2.0 * step);
    }
    const Eigen::VectorXd dx = J.partialPivLu().solve(-r);
    for (Index k = 0; k < n; ++k) y(unknowns[static_cast<std::size_t>(k)].position) += dx(k);
  }
  return -1;
}

namespace {

/// The side's triangles in W, deformed: p_WBo + R (p_BoV_B + phi_V q).
contact::PolygonMesh DeformedTriangles(const ReferenceSide& side) {
  contact::PolygonMesh mesh = side.triangles_B;
  if (side.surface == nullptr) {
    mesh.vertices_W = (side.R_WB * side.triangles_B.vertices_W).colwise() + side.p_WBo_W;
    return mesh;
  }
  const Index V = side.surface->vertices.rows();
  const Eigen::Matrix3Xd s_B = side.surface->vertices.transpose() + (side.surface->phi * side.q).reshaped(3, V);
  mesh.vertices_W = (side.R_WB * s_B).colwise() + side.p_WBo_W;
  return mesh;
}

/// Adds the force f_W [N] spread by `weights` over face `face`'s vertices to their FE nodes, in B.
void Spread(const ReferenceSide& side, int face, const Eigen::Vector3d& weights, const Eigen::Vector3d& f_W,
            Eigen::VectorXd& f) {
  if (side.surface == nullptr) return;
  for (int k = 0; k < 3; ++k) {
    const int vertex = side.triangles_B.face_vertices[static_cast<std::size_t>(3 * face + k)];
    const int node = side.surface->fe_nodes[static_cast<std::size_t>(vertex)];
    f.segment<3>(3 * node) += weights(k) * (side.R_WB.transpose() * f_W);
  }
}

}  // namespace

std::array<Eigen::VectorXd, 2> ReferenceNodalLoads(const ReferenceSide& A, const ReferenceSide& B,
                                                   const contact::ElasticFoundation& law, double max_depth) {
  const contact::PolygonMesh mesh_A = DeformedTriangles(A), mesh_B = DeformedTriangles(B);
  std::vector<contact::FacePair> pairs;
  for (int a = 0; a < static_cast<int>(mesh_A.face_sizes.size()); ++a) {
    for (int b = 0; b < static_cast<int>(mesh_B.face_sizes.size()); ++b) pairs.push_back({a, b});
  }
  const auto size = [](const ReferenceSide& side) { return side.box == nullptr ? Index{0} : side.box->fe.K.rows(); };
  std::array<Eigen::VectorXd, 2> f{Eigen::VectorXd::Zero(size(A)), Eigen::VectorXd::Zero(size(B))};
  for (const contact::PcmElement& element : contact::ContactElements(mesh_A, mesh_B, pairs, max_depth)) {
    const Eigen::Vector3d F = contact::Evaluate(law, element, Eigen::Vector3d::Zero()).force_W;
    Spread(A, element.face_A, element.weights_A, F, f[0]);
    Spread(B, element.face_B, element.weights_B, -F, f[1]);
  }
  return f;
}

Eigen::VectorXd ClampedStaticResponse(const ClampedBox& box, const Eigen::VectorXd& f) {
  const Index N = box.fe.K.rows();
  std::vector<bool> held(static_cast<std::size_t>(N), false);
  for (const int node : box.clamped) {
    for (int a = 0; a < 3; ++a) held[static_cast<std::size_t>(3 * node + a)] = true;
  }
  std::vector<Index> free;
  for (Index i = 0; i < N; ++i) {
    if (!held[static_cast<std::size_t>(i)]) free.push_back(i);
  }
  Eigen::SparseMatrix<double> P(N, static_cast<Index>(free.size()));  // free DOF -> all DOF
  for (std::size_t j = 0; j < free.size(); ++j) P.insert(free[j], static_cast<Index>(j)) = 1.0;
  const Eigen::SparseMatrix<double> K_ff = P.transpose() * box.fe.K * P;
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> factor(K_ff);
  return P * factor.solve(P.transpose() * f);
}

}  // namespace flexmbs::mbs::testing
