// `flexmbs reduce`: mesh, assemble and reduce a body, and write its `.sid.h5` file.
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>

#include "app/command_support.h"
#include "app/commands.h"
#include "core/error.h"
#include "fem/assembly.h"
#include "fem/body_spec.h"
#include "fem/mass_properties.h"
#include "reduction/correction_modes.h"
#include "reduction/craig_bampton.h"
#include "reduction/modal_basis.h"
#include "reduction/reduced_body_file.h"
#include "reduction/reduction_spec.h"
#include "reduction/slepc_solver.h"

namespace flexmbs::app {
namespace {

struct ReduceOptions {
  std::string body_file;
  std::string output;
  bool json = false;
};

// The basis the spec asks for, before correction modes.
reduction::ReducedBasis BuildBasis(const reduction::ReductionSpec& spec, const reduction::FeModel& model,
                                   const reduction::BoundaryConditions& conditions,
                                   const reduction::Eigensolver& solver) {
  reduction::EigenOptions eigen;
  eigen.num_modes = spec.num_modes;
  eigen.max_frequency_hz = spec.max_frequency_hz;
  switch (spec.method) {
    case reduction::ReductionMethod::kFreeFree: {
      reduction::FreeFreeOptions options;
      options.eigen = eigen;
      options.rigid_modes = spec.exact_rigid_body_modes ? reduction::RigidModes::kExact
                                                        : reduction::RigidModes::kComputed;
      return reduction::FreeFreeModalBasis(model, options, solver);
    }
    case reduction::ReductionMethod::kFixedInterface:
      return reduction::FixedInterfaceModalBasis(model, conditions, eigen, solver);
    case reduction::ReductionMethod::kCraigBampton:
      return reduction::CraigBamptonBasis(model, conditions, eigen, solver);
  }
  throw InternalError("unknown reduction method");
}

// The file content of a basis of `mesh`.
reduction::ReducedBody ToReducedBody(const fem::BodySpec& body, const fem::Mesh& mesh,
                                     const fem::SystemMatrices& system, const fem::MassProperties& props,
                                     const reduction::ReductionSpec& spec,
                                     const reduction::ReducedBasis& basis) {
  reduction::ReducedBody out;
  out.name = body.name;
  out.mass_properties = props;
  out.node_positions = mesh.nodes;
  out.node_sets = mesh.node_sets;
  out.phi = basis.Phi;
  out.mode_names = basis.names;
  for (reduction::ModeKind kind : basis.kinds) out.mode_kinds.emplace_back(reduction::ModeKindName(kind));
  out.frequency_hz = basis.frequency_hz;
  out.relative_residuals = basis.relative_residuals;
  out.stiffness_reduced = basis.K_reduced;
  out.mass_reduced = basis.M_reduced;
  out.participation = basis.Phi.transpose() * (system.mass * fem::RigidBodyModes(mesh.nodes));
  out.provenance = {{"body_file", body.file.string()},
                    {"geometry_file", body.geometry_file.string()},
                    {"nodes", std::to_string(mesh.num_nodes())},
                    {"elements", std::to_string(mesh.num_elements())},
                    {"reduction_method", basis.method},
                    {"reduction", basis.description},
                    {"eigensolver", basis.eigensolver.empty() ? spec.eigensolver : basis.eigensolver}};
  for (const fem::ElementBlock& block : mesh.blocks) {
    out.provenance["material " + block.region] =
        fmt::format("{}: E = {:g} Pa, nu = {:g}, rho = {:g} kg/m^3", block.material.name,
                    block.material.youngs_modulus_pa, block.material.poisson_ratio,
                    block.material.density_kg_m3);
  }
  return out;
}

// The largest finite value of `v`, or NaN if none.
double MaxFinite(const Eigen::VectorXd& v) {
  double max = std::nan("");
  for (double x : v) {
    if (std::isfinite(x)) max = std::isnan(max) ? x : std::max(max, x);
  }
  return max;
}

void Report(const ReduceOptions& options, const reduction::ReducedBasis& basis,
            const fem::Mesh& mesh, double mesh_seconds, double assembly_seconds, double reduction_seconds) {
  const reduction::ModeCounts counts = basis.Counts();
  if (options.json) {
    nlohmann::json j;
    j["output"] = options.output;
    j["method"] = basis.method;
    j["dofs"] = mesh.num_dofs();
    j["modes"] = {{"rigid", counts.rigid}, {"normal", counts.normal}, {"constraint", counts.constraint},
                  {"static_correction", counts.static_correction}, {"total", counts.total()}};
    j["mode_names"] = basis.names;
    j["frequency_hz"] = ToJson(basis.frequency_hz);
    j["relative_residuals"] = ToJson(basis.relative_residuals);
    j["eigensolver"] = basis.eigensolver;
    j["seconds"] = {{"mesh", mesh_seconds}, {"assembly", assembly_seconds}, {"reduction", reduction_seconds}};
    fmt::print("{}\n", j.dump(2));
    return;
  }
  fmt::print("wrote           {}\n", options.output);
  fmt::print("basis           {}\n", basis.description);
  fmt::print("modes           {}\n", reduction::FormatModeCounts(counts));
  fmt::print("DOF             {} -> {}\n", mesh.num_dofs(), basis.num_modes());
  for (Eigen::Index k = 0; k < basis.num_modes(); ++k) {
    const double f = basis.frequency_hz(k);
    fmt::print("  {:>3}  {:<28} {}\n", k + 1, basis.names[static_cast<std::size_t>(k)],
               std::isnan(f) ? std::string("-") : fmt::format("{:.6g} Hz", f));
  }
  const double max_residual = MaxFinite(basis.relative_residuals);
  fmt::print("max residual    {}\n", std::isnan(max_residual) ? std::string("- (no eigenpairs of the full model)")
                                                               : fmt::format("{:.3g}", max_residual));
  fmt::print("time            mesh {:.3f} s, assembly {:.3f} s, reduction {:.3f} s\n", mesh_seconds,
             assembly_seconds, reduction_seconds);
}

void RunReduce(const ReduceOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  CheckOutputFolder("-o", options.output);
  Progress progress;
  const fem::BodySpec body = fem::LoadBodySpec(options.body_file);
  const reduction::ReductionSpec spec = reduction::LoadReductionSpec(options.body_file, body.node_sets);
  // Under `mpirun` with the slepc backend every rank runs the command; rank 0 writes and reports.
  std::optional<reduction::SlepcSession> mpi;
  if (spec.eigensolver == "slepc") mpi.emplace();
  const bool writer = !mpi || reduction::SlepcSession::Rank() == 0;

  progress.Show(fmt::format("meshing {} ...", body.geometry_file.string()));
  const fem::Mesh mesh = fem::BuildBodyMesh(body);
  const double mesh_seconds = SecondsSince(start);
  progress.Show(fmt::format("assembling {} DOF ...", mesh.num_dofs()));
  const auto assembly_start = std::chrono::steady_clock::now();
  const fem::SystemMatrices system = fem::AssembleBodySystem(body, mesh);
  const double assembly_seconds = SecondsSince(assembly_start);

  progress.Show(fmt::format("reducing ({}) ...", reduction::MethodName(spec.method)));
  const auto reduction_start = std::chrono::steady_clock::now();
  const reduction::FeModel model{system.stiffness, system.mass, mesh.nodes};
  const reduction::BoundaryConditions conditions = reduction::ResolveConditions(spec, mesh.node_sets);
  const std::unique_ptr<reduction::Eigensolver> solver = reduction::MakeEigensolver(spec.eigensolver);
  reduction::ReducedBasis basis = BuildBasis(spec, model, conditions, *solver);
  if (!spec.corrections.empty()) {
    const std::vector<reduction::LoadSet> loads = reduction::ResolveLoadSets(spec, mesh.node_sets);
    basis = reduction::AddStaticCorrectionModes(model, basis, loads).basis;
  }
  if (spec.orthonormalize) basis = reduction::OrthonormalizeBasis(model, basis);
  const double reduction_seconds = SecondsSince(reduction_start);
  progress.Clear();
  if (!writer) return;

  const fem::MassProperties props = fem::MassPropertiesFromMassMatrix(system.mass, mesh.nodes);
  reduction::WriteReducedBody(options.output, ToReducedBody(body, mesh, system, props, spec, basis));
  Report(options, basis, mesh, mesh_seconds, assembly_seconds, reduction_seconds);
}

}  // namespace

void AddReduceCommand(CLI::App& app) {
  auto options = std::make_shared<ReduceOptions>();
  CLI::App* cmd = app.add_subcommand(
      "reduce", "Mesh, assemble and reduce a body (modal or Craig-Bampton) and write its .sid.h5 file");
  cmd->add_option("body", options->body_file, "Body file (YAML) with a 'reduction' section")->required();
  cmd->add_option("-o,--output", options->output, "The reduced body file to write (.sid.h5)")->required();
  cmd->add_flag("--json", options->json, "Print the report as JSON (keys documented in docs/cli.md)");
  cmd->callback([options] { RunReduce(*options); });
}

}  // namespace flexmbs::app
