#include "reduction/sid_body_builder.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numeric>
#include <optional>

#include "core/error.h"
#include "core/sha256.h"
#include "fem/boundary_surface.h"
#include "fem/mass_properties.h"
#include "reduction/contact_surface.h"
#include "reduction/damping.h"
#include "reduction/geometric_stiffening.h"
#include "reduction/sid_invariants.h"
#include "reduction/sid_nodes.h"

namespace flexmbs::reduction {
namespace {

/// The largest finite entry of `v`, or NaN if none.
double MaxFinite(const Eigen::VectorXd& v) {
  double max = std::nan("");
  for (double x : v) {
    if (std::isfinite(x)) max = std::isnan(max) ? x : std::max(max, x);
  }
  return max;
}

/// Adds the stiffening matrices to the order-1 blocks of Ct, Cr and Oe (docs/sid.md):
/// Ct.m1[j](i, a) = K0t_a(i, j), Cr.m1[j](i, a) += K0r_a(i, j), Oe.m1[j](i, l) += K0omega_l(i, j).
void AddStiffeningToInvariants(const sid::GeometricStiffening& stiffening, sid::ReducedBody* body) {
  const Eigen::Index n = body->num_modes();
  body->Ct.m1.assign(static_cast<std::size_t>(n), Eigen::MatrixXd::Zero(n, 3));
  for (Eigen::Index j = 0; j < n; ++j) {
    const auto jj = static_cast<std::size_t>(j);
    for (std::size_t a = 0; a < 3; ++a) {
      const auto column = static_cast<Eigen::Index>(a);
      body->Ct.m1[jj].col(column) = stiffening.K0t[a].col(j);
      body->Cr.m1[jj].col(column) += stiffening.K0r[a].col(j);
    }
    for (std::size_t l = 0; l < 6; ++l) body->Oe.m1[jj].col(static_cast<Eigen::Index>(l)) += stiffening.K0omega[l].col(j);
  }
}

/// The interface a node is coupled through, to load it with unit forces and moments.
InterfaceSpec NodeInterface(const sid::Node& node) {
  InterfaceSpec interface;
  interface.name = node.name;
  interface.nodes = node.fe_nodes;
  interface.coupling = node.coupling == "rigid"       ? Coupling::kRigid
                       : node.coupling == "averaging" ? Coupling::kAveraging
                                                      : Coupling::kNodes;
  if (interface.coupling != Coupling::kNodes) interface.marker_position = node.origin.m0.col(0);
  return interface;
}

/// The order-1 stiffening blocks of a node's phi or psi: m1[j](a, i) = -K0_a(i, j) (docs/sid.md,
/// nodes); none if `K0` is empty (a single FE node takes no moments).
std::vector<Eigen::MatrixXd> NodeStiffeningBlocks(const std::array<Eigen::MatrixXd, 3>& K0) {
  if (K0[0].size() == 0) return {};
  const Eigen::Index n = K0[0].rows();
  std::vector<Eigen::MatrixXd> m1(static_cast<std::size_t>(n), Eigen::MatrixXd(3, n));
  for (Eigen::Index j = 0; j < n; ++j) {
    for (std::size_t a = 0; a < 3; ++a) {
      m1[static_cast<std::size_t>(j)].row(static_cast<Eigen::Index>(a)) = -K0[a].col(j).transpose();
    }
  }
  return m1;
}

/// Every boundary face of `mesh` as linear polygons through its FE nodes (fem::BoundarySurface
/// of all nodes, its vertices mapped back to FE nodes): the SID body's visual surface.
sid::VisualSurface VisualSurfaceOf(const fem::Mesh& mesh) {
  std::vector<int> all_nodes(static_cast<std::size_t>(mesh.num_nodes()));
  std::iota(all_nodes.begin(), all_nodes.end(), 0);
  const fem::PolygonSurface polygons = fem::BoundarySurface(mesh, all_nodes);
  sid::VisualSurface surface;
  surface.face_sizes = polygons.face_sizes;
  surface.face_nodes.reserve(polygons.face_vertices.size());
  for (int v : polygons.face_vertices) surface.face_nodes.push_back(polygons.fe_nodes[static_cast<std::size_t>(v)]);
  return surface;
}

}  // namespace

std::map<std::string, std::string> ReductionProvenance(const fem::BodySpec& body, const ReductionSpec& reduction,
                                                       const SidSpec& sid, const fem::Mesh& mesh,
                                                       const ReducedBasis& basis) {
  std::map<std::string, std::string> out = {
      {"body_file", body.file.string()},
      {"geometry_file", body.geometry_file.string()},
      {"geometry_sha256", Sha256OfFile(body.geometry_file)},
      {"mesh_sha256", fem::MeshSha256(mesh)},
      {"nodes", std::to_string(mesh.num_nodes())},
      {"elements", std::to_string(mesh.num_elements())},
      {"mass_matrix", body.mass_matrix == fem::MassMatrixKind::kConsistent
                          ? "consistent"
                          : "lumped for the modes, consistent for the invariants"},
      {"reduction_method", basis.method},
      {"reduction", basis.description},
      {"eigensolver", basis.eigensolver.empty() ? reduction.eigensolver : basis.eigensolver},
      {"geometric_stiffening", sid.geometric_stiffening ? "yes" : "no"},
  };
  const double max_residual = MaxFinite(basis.relative_residuals);
  out["max_relative_residual"] = std::isnan(max_residual) ? "-" : fmt::format("{:.3g}", max_residual);
  std::map<std::string, Eigen::Index> counts;
  for (const fem::ElementBlock& block : mesh.blocks) {
    counts[std::string(fem::Traits(block.type).name)] += block.num_elements();
    out["material " + block.region] =
        fmt::format("{}: E = {:g} Pa, nu = {:g}, rho = {:g} kg/m^3", block.material.name,
                    block.material.youngs_modulus_pa, block.material.poisson_ratio, block.material.density_kg_m3);
  }
  for (const auto& [type, count] : counts) out["elements " + type] = std::to_string(count);
  return out;
}

sid::ReducedBody BuildReducedBody(const SidSource& source, const ReducedBasis& basis) {
  return BuildReducedBody(source.mesh, FeModel{source.system.stiffness, source.system.mass, source.mesh.nodes},
                          source.mass_matrix, source.sid, basis);
}

sid::ReducedBody BuildReducedBody(const fem::Mesh& mesh, const FeModel& model, fem::MassMatrixKind mass_matrix,
                                  const SidSpec& sid_spec, const ReducedBasis& basis) {
  const Eigen::MatrixXd& Phi = basis.Phi;
  const Eigen::Index n = basis.num_modes();
  // The invariants need the consistent mass matrix even where the modes used a lumped one.
  std::optional<fem::SystemMatrices> consistent;
  std::optional<eigensolvers::SparseOperator> consistent_mass;
  if (model.assembled() && mass_matrix != fem::MassMatrixKind::kConsistent) {
    consistent = fem::AssembleSystem(mesh, fem::MassMatrixKind::kConsistent);
    consistent_mass.emplace(consistent->mass);
  }
  const eigensolvers::SymmetricOperator& M = consistent_mass        ? *consistent_mass
                               : model.operators()    ? model.operators()->consistent_mass()
                                                      : model.mass();

  sid::ReducedBody out;
  const fem::MassProperties props = eigensolvers::MassPropertiesOf(M, mesh.nodes);
  out.mass = props.mass_kg;
  out.center_of_mass = props.p_BoCm_B;
  out.inertia_about_center_of_mass = props.I_Cm_B;
  out.mode_names = basis.names;
  for (ModeKind kind : basis.kinds) out.mode_kinds.emplace_back(ModeKindName(kind));
  out.frequency_hz = basis.frequency_hz;
  out.relative_residuals = basis.relative_residuals;

  InertiaInvariants inertia =
      model.assembled() ? ComputeInertiaInvariants(consistent ? consistent->mass : model.M(), mesh.nodes, Phi)
                        : ComputeInertiaInvariants(M, mesh.nodes, Phi);
  out.mdCM = std::move(inertia.mdCM);
  out.J = std::move(inertia.J);
  out.Ct = std::move(inertia.Ct);
  out.Cr = std::move(inertia.Cr);
  out.Me = std::move(inertia.Me);
  out.Gr = std::move(inertia.Gr);
  out.Ge = std::move(inertia.Ge);
  out.Oe = std::move(inertia.Oe);
  out.Ke.m0 = basis.K_reduced;
  ReducedDamping damping = DampingMatrix(sid_spec.damping, model, basis);
  out.De.m0 = std::move(damping.De);
  out.damping = std::move(damping.description);
  out.ksigma.m0 = Eigen::VectorXd::Zero(n);

  out.node_positions = mesh.nodes;
  out.node_sets = mesh.node_sets;
  out.phi = Phi;
  out.nodes = MarkerNodes(mesh, Phi, basis.held_by, sid_spec.markers);
  out.surfaces = ContactSurfaces(mesh, sid_spec.contact_surfaces, Phi);
  // In the order of their names, the order the .sid.h5 file gives them back in (docs/sid.md):
  // the body reduce exports (--format sid-ascii) numbers its nodes as export does from the file.
  const auto by_name = [](const auto& a, const auto& b) { return a.name < b.name; };
  std::sort(out.nodes.begin(), out.nodes.end(), by_name);
  std::sort(out.surfaces.begin(), out.surfaces.end(), by_name);
  out.visual_surface = VisualSurfaceOf(mesh);

  if (sid_spec.geometric_stiffening) {
    std::vector<InterfaceSpec> loaded;
    for (const sid::Node& node : out.nodes) loaded.push_back(NodeInterface(node));
    StiffeningResult stiffening = ComputeGeometricStiffening(mesh, model, basis.held_by, Phi, loaded,
                                                              basis.held_factorization.get());
    out.stiffening = std::move(stiffening.body);
    AddStiffeningToInvariants(out.stiffening, &out);
    for (std::size_t k = 0; k < out.nodes.size(); ++k) {
      out.nodes[k].phi.m1 = NodeStiffeningBlocks(stiffening.nodes[k].K0F);
      out.nodes[k].psi.m1 = NodeStiffeningBlocks(stiffening.nodes[k].K0M);
    }
  }
  return out;
}

}  // namespace flexmbs::reduction
