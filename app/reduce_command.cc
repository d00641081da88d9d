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
#include "reduction/correction_modes.h"
#include "reduction/craig_bampton.h"
#include "reduction/modal_basis.h"
#include "reduction/sid_body_builder.h"
#include "reduction/sid_nodes.h"
#include "reduction/sid_spec.h"
#include "reduction/reduction_spec.h"
#include "reduction/slepc_solver.h"
#include "sid/body_formats.h"

namespace flexmbs::app {
namespace {

struct ReduceOptions {
  std::string body_file;
  std::string output;
  std::string format = "sid-h5";
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

// The largest finite value of `v`, or NaN if none.
double MaxFinite(const Eigen::VectorXd& v) {
  double max = std::nan("");
  for (double x : v) {
    if (std::isfinite(x)) max = std::isnan(max) ? x : std::max(max, x);
  }
  return max;
}

// Wall-clock time of each stage [s].
struct StageSeconds {
  double mesh = 0.0;
  double assembly = 0.0;
  double reduction = 0.0;
  double sid = 0.0;
};

void Report(const ReduceOptions& options, const reduction::ReducedBasis& basis, const fem::Mesh& mesh,
            const StageSeconds& seconds) {
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
    j["seconds"] = {{"mesh", seconds.mesh}, {"assembly", seconds.assembly}, {"reduction", seconds.reduction},
                    {"sid", seconds.sid}};
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
  fmt::print("time            mesh {:.3f} s, assembly {:.3f} s, reduction {:.3f} s, SID {:.3f} s\n", seconds.mesh,
             seconds.assembly, seconds.reduction, seconds.sid);
}

void RunReduce(const ReduceOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const sid::BodyFormat& format = sid::FindBodyFormat(options.format);
  CheckOutputFolder("-o", options.output);
  Progress progress;
  const fem::BodySpec body = fem::LoadBodySpec(options.body_file);
  const reduction::ReductionSpec spec = reduction::LoadReductionSpec(options.body_file, body.node_sets);
  const reduction::SidSpec sid_spec =
      reduction::LoadSidSpec(options.body_file, body.node_sets, reduction::InterfaceMarkerNames(spec));
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
  if (!writer) {
    progress.Clear();
    return;
  }

  progress.Show("computing the SID invariants ...");
  const auto sid_start = std::chrono::steady_clock::now();
  sid::ReducedBody reduced = reduction::BuildReducedBody({mesh, system, body.mass_matrix, sid_spec}, basis);
  reduced.name = body.name;
  reduced.provenance = reduction::ReductionProvenance(body, spec, sid_spec, mesh, basis);
  const double sid_seconds = SecondsSince(sid_start);
  progress.Clear();
  format.write(options.output, reduced);
  Report(options, basis, mesh, {mesh_seconds, assembly_seconds, reduction_seconds, sid_seconds});
}

}  // namespace

void AddReduceCommand(CLI::App& app) {
  auto options = std::make_shared<ReduceOptions>();
  CLI::App* cmd = app.add_subcommand(
      "reduce", "Mesh, assemble and reduce a body (modal or Craig-Bampton) and write its .sid.h5 file");
  cmd->add_option("body", options->body_file, "Body file (YAML) with a 'reduction' section")->required();
  cmd->add_option("-o,--output", options->output, "The reduced body file to write (.sid.h5)")->required();
  cmd->add_option("--format", options->format, FormatHelp())->default_str("sid-h5");
  cmd->add_flag("--json", options->json, "Print the report as JSON (keys documented in docs/cli.md)");
  cmd->callback([options] { RunReduce(*options); });
}

}  // namespace flexmbs::app
