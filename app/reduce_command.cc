// `flexmbs reduce`: mesh, assemble and reduce a body, and write its `.sid.h5` file.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sys/resource.h>

#include "app/command_support.h"
#include "app/commands.h"
#include "core/error.h"
#include "fem/assembly.h"
#include "fem/body_spec.h"
#include "reduction/correction_modes.h"
#include "reduction/craig_bampton.h"
#include "reduction/distributed_reduction.h"
#include "reduction/interior_problem.h"
#include "reduction/modal_basis.h"
#include "reduction/sid_body_builder.h"
#include "reduction/sid_nodes.h"
#include "reduction/sid_spec.h"
#include "reduction/reduction_spec.h"
#include "eigensolvers/distributed/slepc_solver.h"
#include "sid/body_formats.h"

namespace flexmbs::app {
namespace {

struct ReduceOptions {
  std::string body_file;
  std::string output;
  std::string format = "sid-h5";
  bool json = false;
};

// The eigen-solve's options the spec asks for (the normal modes; a free-free basis adds the
// rigid-body modes itself).
eigensolvers::EigenOptions EigenOptionsOf(const reduction::ReductionSpec& spec) {
  eigensolvers::EigenOptions eigen;
  eigen.num_modes = spec.num_modes;
  eigen.max_frequency_hz = spec.max_frequency_hz;
  return eigen;
}

// The free-free basis's options the spec asks for.
reduction::FreeFreeOptions FreeFreeOptionsOf(const reduction::ReductionSpec& spec) {
  reduction::FreeFreeOptions options;
  options.eigen = EigenOptionsOf(spec);
  options.rigid_modes =
      spec.exact_rigid_body_modes ? reduction::RigidModes::kExact : reduction::RigidModes::kComputed;
  return options;
}

// The basis the spec asks for, before correction modes.
reduction::ReducedBasis BuildBasis(const reduction::ReductionSpec& spec, const reduction::FeModel& model,
                                   const reduction::BoundaryConditions& conditions,
                                   const eigensolvers::Eigensolver& solver) {
  const eigensolvers::EigenOptions eigen = EigenOptionsOf(spec);
  switch (spec.method) {
    case reduction::ReductionMethod::kFreeFree:
      return reduction::FreeFreeModalBasis(model, FreeFreeOptionsOf(spec), solver);
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

// The MPI path's accounting (`reduce --json`, key "mpi"; docs/reduction.md, "Under MPI"): the
// solve's, and what the products and static solves with the kept matrices cost after it.
nlohmann::json MpiJson(const reduction::DistributedSolveStats& stats, double basis_seconds,
                       const eigensolvers::DistributedModelStats& after) {
  nlohmann::json ranks = nlohmann::json::array();
  for (const reduction::RankShare& r : stats.ranks) {
    const auto k = static_cast<std::size_t>(r.rank);
    ranks.push_back({{"rank", r.rank}, {"elements", r.elements}, {"nodes", r.nodes}, {"rows", r.rows},
                     {"nonzeros", r.nonzeros}, {"peak_rss_mb_after_solve", r.peak_rss_mb},
                     {"peak_rss_mb", k < after.peak_rss_mb.size() ? after.peak_rss_mb[k] : r.peak_rss_mb}});
  }
  return {{"ranks", ranks},
          {"products", {{"columns", after.product_columns}, {"seconds", after.product_seconds}}},
          {"static_solves",
           {{"factorizations", after.factorizations}, {"solves", after.static_solves},
            {"seconds", after.static_solve_seconds}}},
          {"seconds", {{"partition_scatter", stats.partition_seconds}, {"assembly", stats.assembly_seconds},
                       {"factorisation_solve", stats.solve_seconds}, {"gather", stats.gather_seconds},
                       {"basis_rank0", basis_seconds}}}};
}

// The eigen-solve's accounting (`reduce --json`, key "seconds.eigensolver"; docs/cli.md).
nlohmann::json EigensolverJson(const reduction::EigensolverSummary& s) {
  return {{"seconds", s.seconds},
          {"factorization_seconds", s.factorization_seconds},
          {"sturm_seconds", s.sturm_seconds},
          {"krylov_seconds", s.krylov_seconds},
          {"factorizations", s.factorizations},
          {"operator_applications", s.operator_applications},
          {"krylov_runs", s.krylov_runs},
          {"restarts", s.restarts},
          {"missed_mode_check", eigensolvers::MissedModeCheckName(s.missed_mode_check)},
          {"factorization", s.factorization},
          {"lanczos_block_size", s.lanczos_block_size}};
}

void Report(const ReduceOptions& options, const reduction::ReducedBasis& basis, const fem::Mesh& mesh,
            const StageSeconds& seconds, const std::optional<nlohmann::json>& mpi) {
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
    if (basis.eigensolver_summary) j["seconds"]["eigensolver"] = EigensolverJson(*basis.eigensolver_summary);
    if (mpi) {
      j["mpi"] = *mpi;
      // Rank 0's peak over the whole run, the SID invariants and the file included.
      rusage usage{};
      getrusage(RUSAGE_SELF, &usage);
      j["mpi"]["rank0_peak_rss_mb"] = static_cast<double>(usage.ru_maxrss) / 1024.0;
    }
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

// A body reduced: its mesh and matrices, the basis before correction modes, and the timings.
// Filled on the rank that writes (rank 0 under mpirun). On the distributed path the matrices
// stay distributed (`distributed`, on every rank) and `system` is empty.
struct Reduction {
  fem::Mesh mesh;
  fem::SystemMatrices system;
  std::unique_ptr<eigensolvers::DistributedModel> distributed;
  reduction::BoundaryConditions conditions;
  reduction::ReducedBasis basis;
  StageSeconds seconds;
  reduction::DistributedSolveStats solve_stats;  ///< the distributed path's accounting
  double basis_seconds = 0.0;                    ///< of the distributed path's basis on rank 0

  // The FE model: the assembled matrices, or the distributed ones' products.
  reduction::FeModel Model() const {
    return distributed ? reduction::FeModel(*distributed, mesh.nodes)
                       : reduction::FeModel(system.stiffness, system.mass, mesh.nodes);
  }
};

// Whether the reduction runs distributed end to end (SolveModesDistributed): the slepc backend
// and a free-free or fixed-interface basis held by whole clamped nodes (supports, node-set and
// rigid interfaces). Craig-Bampton and averaging interfaces take the path on which every rank
// assembles the whole K and M and SLEPc distributes the eigen-solve only.
bool RunsDistributed(const reduction::ReductionSpec& spec) {
  if (spec.eigensolver != "slepc") return false;
  if (spec.method == reduction::ReductionMethod::kFreeFree) return true;
  return spec.method == reduction::ReductionMethod::kFixedInterface &&
         std::none_of(spec.interfaces.begin(), spec.interfaces.end(), [](const reduction::InterfaceSetting& i) {
           return i.coupling == reduction::Coupling::kAveraging;
         });
}

// Every rank meshes and assembles the whole body; the eigensolver (serial, or SLEPc over the
// ranks) builds the basis on each. Returns false on the ranks that do not write.
bool ReduceOnEveryRank(const fem::BodySpec& body, const reduction::ReductionSpec& spec, bool writer,
                       std::chrono::steady_clock::time_point start, Progress& progress, Reduction* out) {
  progress.Show(fmt::format("meshing {} ...", body.geometry_file.string()));
  out->mesh = fem::BuildBodyMesh(body);
  out->seconds.mesh = SecondsSince(start);
  progress.Show(fmt::format("assembling {} DOF ...", out->mesh.num_dofs()));
  const auto assembly_start = std::chrono::steady_clock::now();
  out->system = fem::AssembleBodySystem(body, out->mesh);
  out->seconds.assembly = SecondsSince(assembly_start);
  progress.Show(fmt::format("reducing ({}) ...", reduction::MethodName(spec.method)));
  const auto reduction_start = std::chrono::steady_clock::now();
  out->conditions = reduction::ResolveConditions(spec, out->mesh.node_sets);
  const std::unique_ptr<eigensolvers::Eigensolver> solver = eigensolvers::MakeEigensolver(spec.eigensolver);
  out->basis = BuildBasis(spec, out->Model(), out->conditions, *solver);
  out->seconds.reduction = SecondsSince(reduction_start);
  return writer;
}

// Rank 0 meshes; the ranks assemble their element shares and solve together
// (SolveModesDistributed); rank 0 gets the modes and builds the basis, and later the SID data,
// from products and static solves with the distributed matrices, which stay distributed
// (DistributedModel): no rank assembles K and M whole. The other ranks serve those products
// until rank 0 is done, then return false.
bool ReduceDistributed(const fem::BodySpec& body, const reduction::ReductionSpec& spec,
                       std::chrono::steady_clock::time_point start, Progress& progress, Reduction* out) {
  const bool root = eigensolvers::SlepcSession::Rank() == 0;
  const bool free_free = spec.method == reduction::ReductionMethod::kFreeFree;
  std::vector<int> clamped;
  std::string error;
  if (root) {
    try {
      progress.Show(fmt::format("meshing {} ...", body.geometry_file.string()));
      out->mesh = fem::BuildBodyMesh(body);
      out->conditions = reduction::ResolveConditions(spec, out->mesh.node_sets);
      if (!free_free) {
        const std::optional<std::vector<int>> dofs = reduction::ClampedDofs(out->mesh.nodes, out->conditions);
        FLEXMBS_CHECK(dofs.has_value(), "RunsDistributed admits only conditions that clamp whole node DOF");
        clamped = *dofs;
      }
    } catch (const std::exception& e) {  // every rank must hear of it, or they wait forever
      error = e.what();
    }
  }
  reduction::ShareRootError(error);
  out->seconds.mesh = SecondsSince(start);

  // The options the basis builder passes to its eigensolver: FreeFreeModalBasis asks for the
  // six rigid-body modes on top of the elastic ones.
  eigensolvers::EigenOptions eigen = EigenOptionsOf(spec);
  if (free_free && spec.num_modes > 0) eigen.num_modes += 6;
  progress.Show(fmt::format("assembling and solving on {} ranks ...", eigensolvers::SlepcSession::Size()));
  reduction::DistributedSolveStats& stats = out->solve_stats;
  eigensolvers::EigenSolution solution;
  try {
    solution = reduction::SolveModesDistributed(out->mesh, body.mass_matrix, clamped, eigen, &stats, &out->distributed);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", body.file.string(), e.what()));
  }
  out->seconds.assembly = stats.partition_seconds + stats.assembly_seconds;
  if (!root) {
    out->distributed->Serve();
    return false;
  }

  progress.Show(fmt::format("building the basis ({}) ...", reduction::MethodName(spec.method)));
  const auto basis_start = std::chrono::steady_clock::now();
  const reduction::FeModel model = out->Model();
  if (free_free) {
    out->basis = reduction::FreeFreeModalBasis(model, FreeFreeOptionsOf(spec), solution);
  } else {
    out->basis = reduction::FixedInterfaceModalBasis(model, out->conditions, eigen, solution);
  }
  out->basis_seconds = SecondsSince(basis_start);
  out->seconds.reduction = stats.solve_seconds + stats.gather_seconds + out->basis_seconds;
  return true;
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
  std::optional<eigensolvers::SlepcSession> mpi;
  if (spec.eigensolver == "slepc") mpi.emplace();
  const bool writer = !mpi || eigensolvers::SlepcSession::Rank() == 0;

  Reduction r;
  const bool writes = RunsDistributed(spec) ? ReduceDistributed(body, spec, start, progress, &r)
                                            : ReduceOnEveryRank(body, spec, writer, start, progress, &r);
  if (!writes) {
    progress.Clear();
    return;
  }
  const auto corrections_start = std::chrono::steady_clock::now();
  const reduction::FeModel model = r.Model();
  if (!spec.corrections.empty()) {
    const std::vector<reduction::LoadSet> loads = reduction::ResolveLoadSets(spec, r.mesh.node_sets);
    r.basis = reduction::AddStaticCorrectionModes(model, r.basis, loads).basis;
  }
  if (spec.orthonormalize) r.basis = reduction::OrthonormalizeBasis(model, r.basis);
  r.seconds.reduction += SecondsSince(corrections_start);
  // The held body's factor serves the stiffening's static solves; without them, free it now.
  if (!sid_spec.geometric_stiffening) r.basis.held_factorization.reset();

  progress.Show("computing the SID invariants ...");
  const auto sid_start = std::chrono::steady_clock::now();
  sid::ReducedBody reduced = reduction::BuildReducedBody(r.mesh, model, body.mass_matrix, sid_spec, r.basis);
  reduced.name = body.name;
  reduced.provenance = reduction::ReductionProvenance(body, spec, sid_spec, r.mesh, r.basis);
  r.seconds.sid = SecondsSince(sid_start);
  std::optional<nlohmann::json> mpi_report;
  if (r.distributed) mpi_report = MpiJson(r.solve_stats, r.basis_seconds, r.distributed->Finish());
  progress.Clear();
  format.write(options.output, reduced);
  Report(options, r.basis, r.mesh, r.seconds, mpi_report);
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
