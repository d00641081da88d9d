#include "tests/mbs/flexible_test_bodies.h"

#include <memory>
#include <utility>

#include "fem/assembly.h"
#include "reduction/craig_bampton.h"
#include "eigensolvers/eigensolver.h"
#include "reduction/sid_body_builder.h"
#include "tests/support/test_problems.h"

namespace flexmbs::mbs::testing {
namespace {

using Eigen::Index;

const eigensolvers::Eigensolver& Solver() {
  static const std::unique_ptr<eigensolvers::Eigensolver> solver = eigensolvers::MakeEigensolver("spectra");
  return *solver;
}

/// The meshed beam with its node sets "root", "tip", "mid", "corner" and matrices.
FeReducedBody MeshedBeam(bool stiffening) {
  FeReducedBody fe;
  fe.mesh = flexmbs::testing::HexBox(Eigen::Vector3i(6, 2, 2), kBeamSize, flexmbs::testing::Steel());
  fe.mesh.node_sets["root"] = flexmbs::testing::NodesOnPlane(fe.mesh, 0, 0.0);
  fe.mesh.node_sets["tip"] = flexmbs::testing::NodesOnPlane(fe.mesh, 0, kBeamSize.x());
  fe.mesh.node_sets["mid"] = flexmbs::testing::NodesOnPlane(fe.mesh, 0, 0.5 * kBeamSize.x());
  for (Index k = 0; k < fe.mesh.num_nodes(); ++k) {
    if ((fe.mesh.nodes.col(k) - Eigen::Vector3d(0.5 * kBeamSize.x(), kBeamSize.y(), kBeamSize.z())).norm() < 1e-12) {
      fe.mesh.node_sets["corner"] = {static_cast<int>(k)};
    }
  }
  fem::SystemMatrices system = fem::AssembleSystem(fe.mesh, fem::MassMatrixKind::kConsistent);
  fe.K = std::move(system.stiffness);
  fe.M = std::move(system.mass);
  fe.sid_spec.markers = {{"mid", "mid", reduction::MarkerCoupling::kAveraging, std::nullopt, std::nullopt},
                         {"corner", "corner", reduction::MarkerCoupling::kNode, std::nullopt, std::nullopt}};
  fe.sid_spec.contact_surfaces = {"tip"};
  fe.sid_spec.damping.kind = reduction::DampingKind::kRayleigh;
  fe.sid_spec.damping.rayleigh_mass_per_s = kRayleighMassPerS;
  fe.sid_spec.damping.rayleigh_stiffness_s = kRayleighStiffnessS;
  fe.sid_spec.geometric_stiffening = stiffening;
  return fe;
}

reduction::InterfaceSpec TipInterface(const fem::Mesh& mesh) {
  reduction::InterfaceSpec tip;
  tip.name = "tip";
  tip.nodes = mesh.node_sets.at("tip");
  tip.coupling = reduction::Coupling::kRigid;
  return tip;
}

FeReducedBody CraigBampton(bool supported, int normal_modes, bool stiffening) {
  FeReducedBody fe = MeshedBeam(stiffening);
  reduction::BoundaryConditions conditions;
  if (supported) conditions.supports.push_back({"root", fe.mesh.node_sets.at("root")});
  conditions.interfaces.push_back(TipInterface(fe.mesh));
  eigensolvers::EigenOptions eigen;
  eigen.num_modes = normal_modes;
  fe.basis = reduction::CraigBamptonBasis({fe.K, fe.M, fe.mesh.nodes}, conditions, eigen, Solver());
  fe.body = Reduce(fe, fe.basis);
  return fe;
}

}  // namespace

sid::ReducedBody Reduce(const FeReducedBody& fe, const reduction::ReducedBasis& basis) {
  const fem::SystemMatrices views{fe.K, fe.M};
  sid::ReducedBody body =
      reduction::BuildReducedBody({fe.mesh, views, fem::MassMatrixKind::kConsistent, fe.sid_spec}, basis);
  body.name = "beam";
  return body;
}

const FeReducedBody& CraigBamptonBeam() {
  static const FeReducedBody fe = CraigBampton(true, 4, true);
  return fe;
}

const FeReducedBody& UnsupportedCraigBamptonBeam() {
  static const FeReducedBody fe = CraigBampton(false, 3, false);
  return fe;
}

const FeReducedBody& FreeFreeBeam() {
  static const FeReducedBody fe = [] {
    FeReducedBody out = MeshedBeam(true);
    reduction::FreeFreeOptions options;
    options.eigen.num_modes = 5;
    out.basis = reduction::FreeFreeModalBasis({out.K, out.M, out.mesh.nodes}, options, Solver());
    out.body = Reduce(out, out.basis);
    return out;
  }();
  return fe;
}

FeReducedBody FreeFreeBox(const Eigen::Vector3i& cells, const Eigen::Vector3d& size,
                          const fem::IsotropicMaterial& material,
                          const std::function<std::map<std::string, std::vector<int>>(const fem::Mesh&)>& node_sets,
                          const std::vector<std::string>& surfaces, double max_frequency_hz) {
  FeReducedBody fe;
  fe.mesh = flexmbs::testing::HexBox(cells, size, material);
  for (auto& [name, nodes] : node_sets(fe.mesh)) fe.mesh.node_sets[name] = std::move(nodes);
  fem::SystemMatrices system = fem::AssembleSystem(fe.mesh, fem::MassMatrixKind::kConsistent);
  fe.K = std::move(system.stiffness);
  fe.M = std::move(system.mass);
  fe.sid_spec.contact_surfaces = surfaces;
  fe.sid_spec.geometric_stiffening = false;
  reduction::FreeFreeOptions options;
  options.eigen.max_frequency_hz = max_frequency_hz;
  options.eigen.num_modes = static_cast<int>(fe.K.rows() - 6);
  fe.basis = reduction::FreeFreeModalBasis({fe.K, fe.M, fe.mesh.nodes}, options, Solver());
  return fe;
}

std::vector<Index> ElasticColumns(const reduction::ReducedBasis& basis) {
  std::vector<Index> keep;
  for (Index j = 0; j < basis.num_modes(); ++j) {
    if (basis.kinds[static_cast<std::size_t>(j)] != reduction::ModeKind::kRigid) keep.push_back(j);
  }
  return keep;
}

reduction::ReducedBasis KeepColumns(const reduction::ReducedBasis& basis, const std::vector<Index>& keep) {
  reduction::ReducedBasis out = basis;
  out.Phi = basis.Phi(Eigen::all, keep);
  out.kinds.clear();
  out.names.clear();
  for (Index j : keep) {
    out.kinds.push_back(basis.kinds[static_cast<std::size_t>(j)]);
    out.names.push_back(basis.names[static_cast<std::size_t>(j)]);
  }
  out.K_reduced = basis.K_reduced(keep, keep);
  out.M_reduced = basis.M_reduced(keep, keep);
  const auto pick = [&](const Eigen::VectorXd& v) { return v.size() == 0 ? v : Eigen::VectorXd(v(keep)); };
  out.frequency_hz = pick(basis.frequency_hz);
  out.relative_residuals = pick(basis.relative_residuals);
  out.residual_floors = pick(basis.residual_floors);
  return out;
}

Eigen::Matrix3d CentrifugalInertiaChange(const sid::GeometricStiffening& K0, const Eigen::VectorXd& a,
                                         const Eigen::VectorXd& b) {
  const auto form = [&](const Eigen::Vector3d& w) {
    const double products[6] = {w.x() * w.x(), w.y() * w.y(), w.z() * w.z(), w.x() * w.y(), w.y() * w.z(), w.z() * w.x()};
    double sum = 0.0;
    for (std::size_t l = 0; l < 6; ++l) sum -= products[l] * a.dot(K0.K0omega[l] * b);
    return sum;
  };
  Eigen::Matrix3d D;
  for (Index i = 0; i < 3; ++i) {
    for (Index j = 0; j < 3; ++j) {
      const Eigen::Vector3d e_i = Eigen::Vector3d::Unit(i), e_j = Eigen::Vector3d::Unit(j);
      D(i, j) = 0.5 * (form(e_i + e_j) - form(e_i) - form(e_j));
    }
  }
  return D;
}

}  // namespace flexmbs::mbs::testing
