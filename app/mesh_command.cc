// `flexmbs mesh`: the FE model of a body alone.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <map>
#include <nlohmann/json.hpp>
#include <string_view>

#include "app/command_support.h"
#include "app/commands.h"
#include "app/matrix_market.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "fem/assembly.h"
#include "fem/body_spec.h"
#include "fem/mass_properties.h"

namespace flexmbs::app {
namespace {

struct MeshOptions {
  std::string body_file;
  bool json = false;
  std::string matrix_prefix;
};

// Writes K and M as PREFIX_K.mtx and PREFIX_M.mtx: both files or neither.
void WriteMatrices(const std::string& prefix, const fem::SystemMatrices& system) {
  const std::filesystem::path K_path = prefix + "_K.mtx", M_path = prefix + "_M.mtx";
  const std::filesystem::path K_temporary = TemporaryPathFor(K_path);
  const std::filesystem::path M_temporary = TemporaryPathFor(M_path);
  auto remove = [](const std::filesystem::path& path) {
    std::error_code ec;
    std::filesystem::remove(path, ec);
  };
  try {
    WriteSymmetricMatrixMarket(K_temporary, system.stiffness);
    WriteSymmetricMatrixMarket(M_temporary, system.mass);
    CommitTemporaryFile(K_temporary, K_path);
  } catch (...) {
    remove(K_temporary);
    remove(M_temporary);
    throw;
  }
  try {
    CommitTemporaryFile(M_temporary, M_path);
  } catch (...) {
    remove(K_path);
    throw;
  }
}

void RunMesh(const MeshOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (!options.matrix_prefix.empty()) CheckOutputFolder("--matrix-market", options.matrix_prefix);
  Progress progress;
  const fem::BodySpec spec = fem::LoadBodySpec(options.body_file);
  progress.Show(fmt::format("meshing {} ...", spec.geometry_file.string()));
  const fem::Mesh mesh = fem::BuildBodyMesh(spec);
  const double mesh_seconds = SecondsSince(start);
  progress.Show(fmt::format("assembling {} DOF ...", mesh.num_dofs()));
  const auto assembly_start = std::chrono::steady_clock::now();
  const fem::SystemMatrices system = fem::AssembleBodySystem(spec, mesh);
  const double assembly_seconds = SecondsSince(assembly_start);
  const fem::MassProperties props = fem::MassPropertiesFromMassMatrix(system.mass, mesh.nodes);

  std::map<std::string, Eigen::Index> elements_by_type;
  for (const fem::ElementBlock& b : mesh.blocks) {
    elements_by_type[std::string(fem::Traits(b.type).name)] += b.num_elements();
  }

  if (!options.matrix_prefix.empty()) {
    progress.Show(fmt::format("writing {}_K.mtx and {}_M.mtx ...", options.matrix_prefix,
                              options.matrix_prefix));
    WriteMatrices(options.matrix_prefix, system);
  }
  progress.Clear();

  if (options.json) {
    nlohmann::json j;
    j["body"] = spec.name;
    j["geometry_file"] = spec.geometry_file.string();
    j["nodes"] = mesh.num_nodes();
    j["elements"] = elements_by_type;
    j["dofs"] = mesh.num_dofs();
    j["mass_matrix"] = spec.mass_matrix == fem::MassMatrixKind::kLumped ? "lumped" : "consistent";
    j["mass_kg"] = props.mass_kg;
    j["center_of_mass_m"] = ToJson(props.p_BoCm_B);
    j["inertia_about_com_kg_m2"] = ToJson(props.I_Cm_B);
    j["stiffness_nonzeros"] = system.stiffness.nonZeros();
    j["mass_nonzeros"] = system.mass.nonZeros();
    nlohmann::json sets = nlohmann::json::object();
    for (const auto& [name, nodes] : mesh.node_sets) sets[name] = nodes.size();
    j["node_sets"] = sets;
    j["seconds"] = {{"mesh", mesh_seconds}, {"assembly", assembly_seconds}};
    fmt::print("{}\n", j.dump(2));
    return;
  }
  fmt::print("body            {}\n", spec.name);
  fmt::print("geometry        {}\n", spec.geometry_file.string());
  fmt::print("nodes           {}\n", mesh.num_nodes());
  for (const auto& [type, count] : elements_by_type) fmt::print("elements        {} {}\n", count, type);
  fmt::print("DOF             {}\n", mesh.num_dofs());
  fmt::print("mass            {:.6g} kg\n", props.mass_kg);
  fmt::print("centre of mass  [{:.6g}, {:.6g}, {:.6g}] m\n", props.p_BoCm_B(0), props.p_BoCm_B(1),
             props.p_BoCm_B(2));
  fmt::print("inertia at CoM  [{:.6g}, {:.6g}, {:.6g}; {:.6g}, {:.6g}, {:.6g}; {:.6g}, {:.6g}, {:.6g}] kg m^2\n",
             props.I_Cm_B(0, 0), props.I_Cm_B(0, 1), props.I_Cm_B(0, 2), props.I_Cm_B(1, 0),
             props.I_Cm_B(1, 1), props.I_Cm_B(1, 2), props.I_Cm_B(2, 0), props.I_Cm_B(2, 1),
             props.I_Cm_B(2, 2));
  fmt::print("nonzeros        K {}, M {}\n", system.stiffness.nonZeros(), system.mass.nonZeros());
  for (const auto& [name, nodes] : mesh.node_sets) fmt::print("node set        {} ({} nodes)\n", name, nodes.size());
  fmt::print("time            mesh {:.3f} s, assembly {:.3f} s\n", mesh_seconds, assembly_seconds);
}

}  // namespace

void AddMeshCommand(CLI::App& app) {
  auto options = std::make_shared<MeshOptions>();
  CLI::App* cmd = app.add_subcommand("mesh", "Mesh a body and report its FE model (nodes, elements, DOF, mass properties)");
  cmd->add_option("body", options->body_file, "Body file (YAML)")->required();
  cmd->add_flag("--json", options->json, "Print the report as JSON (keys documented in docs/cli.md)");
  cmd->add_option("--matrix-market", options->matrix_prefix,
                  "Also write K and M as PREFIX_K.mtx and PREFIX_M.mtx (Matrix Market)");
  cmd->callback([options] { RunMesh(*options); });
}

}  // namespace flexmbs::app
