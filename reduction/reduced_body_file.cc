#include "reduction/reduced_body_file.h"

#include <fmt/format.h>

#include "core/error.h"
#include "core/h5_file.h"
#include "core/version.h"

namespace flexmbs::reduction {
namespace {

constexpr char kFormat[] = "flexmbs-sid";

}  // namespace

void WriteReducedBody(const std::filesystem::path& path, const ReducedBody& body) {
  const auto n = body.phi.cols();
  FLEXMBS_CHECK(static_cast<Eigen::Index>(body.mode_names.size()) == n &&
                    static_cast<Eigen::Index>(body.mode_kinds.size()) == n &&
                    body.frequency_hz.size() == n && body.relative_residuals.size() == n &&
                    body.stiffness_reduced.rows() == n && body.mass_reduced.rows() == n &&
                    body.participation.rows() == n && body.participation.cols() == 6,
                "every mode needs a name, a kind, a frequency, a residual and reduced matrices");
  FLEXMBS_CHECK(body.phi.rows() == 3 * body.node_positions.cols(), "Phi must have 3 rows per node");
  h5::File file = h5::File::Create(path);
  h5::Group root = file.root();
  root.SetStringAttribute("format", kFormat);
  root.SetIntegerAttribute("schema_version", kSidSchemaVersion);
  root.SetStringAttribute("name", body.name);

  h5::Group refmod = root.CreateGroup("refmod");
  refmod.WriteScalar("mass", body.mass_properties.mass_kg, "kg");
  refmod.WriteVector("center_of_mass", body.mass_properties.p_BoCm_B, "m");
  refmod.WriteMatrix("inertia_about_center_of_mass", body.mass_properties.I_Cm_B, "kg m^2");
  refmod.WriteStrings("mode_names", body.mode_names);
  refmod.WriteStrings("mode_kinds", body.mode_kinds);
  refmod.WriteVector("frequency_hz", body.frequency_hz, "Hz");
  refmod.WriteVector("relative_residuals", body.relative_residuals, "1");

  h5::Group modes = root.CreateGroup("modes");
  modes.WriteMatrix("phi", body.phi, "m/q");
  modes.WriteMatrix("stiffness_reduced", body.stiffness_reduced, "N/m/q^2");
  modes.WriteMatrix("mass_reduced", body.mass_reduced, "kg/q^2");
  modes.WriteMatrix("participation", body.participation, "kg/q (columns 0-2), kg m/q (3-5)");

  h5::Group mesh = root.CreateGroup("mesh");
  mesh.WriteMatrix("node_positions", body.node_positions.transpose(), "m");
  h5::Group sets = mesh.CreateGroup("node_sets");
  for (const auto& [name, nodes] : body.node_sets) sets.WriteIntegers(name, nodes, "1");

  // Provenance as two parallel string lists, so that any key round-trips.
  std::map<std::string, std::string> provenance_entries = body.provenance;
  provenance_entries["tool_version"] = std::string(Version());
  std::vector<std::string> keys, values;
  for (const auto& [key, value] : provenance_entries) {
    keys.push_back(key);
    values.push_back(value);
  }
  h5::Group provenance = root.CreateGroup("provenance");
  provenance.WriteStrings("keys", keys);
  provenance.WriteStrings("values", values);
  file.Commit();
}

ReducedBody ReadReducedBody(const std::filesystem::path& path) {
  const h5::File file = h5::File::Open(path);
  const h5::Group root = file.root();
  if (!root.HasAttribute("format") || root.GetStringAttribute("format") != kFormat) {
    throw InputError(fmt::format("{}: not a flexmbs reduced body (no format '{}')", path.string(), kFormat));
  }
  const std::int64_t version = root.GetIntegerAttribute("schema_version");
  if (version != kSidSchemaVersion) {
    throw InputError(fmt::format("{}: schema_version {} is not supported (this flexmbs reads {})",
                                 path.string(), version, kSidSchemaVersion));
  }
  ReducedBody body;
  body.name = root.GetStringAttribute("name");
  const h5::Group refmod = root.OpenGroup("refmod");
  refmod.RequireUnits("mass", "kg");
  body.mass_properties.mass_kg = refmod.ReadScalar("mass");
  body.mass_properties.p_BoCm_B = refmod.ReadVector("center_of_mass");
  body.mass_properties.I_Cm_B = refmod.ReadMatrix("inertia_about_center_of_mass");
  body.mode_names = refmod.ReadStrings("mode_names");
  body.mode_kinds = refmod.ReadStrings("mode_kinds");
  body.frequency_hz = refmod.ReadVector("frequency_hz");
  body.relative_residuals = refmod.ReadVector("relative_residuals");
  const h5::Group modes = root.OpenGroup("modes");
  body.phi = modes.ReadMatrix("phi");
  body.stiffness_reduced = modes.ReadMatrix("stiffness_reduced");
  body.mass_reduced = modes.ReadMatrix("mass_reduced");
  body.participation = modes.ReadMatrix("participation");
  const h5::Group mesh = root.OpenGroup("mesh");
  mesh.RequireUnits("node_positions", "m");
  body.node_positions = mesh.ReadMatrix("node_positions").transpose();
  const h5::Group sets = mesh.OpenGroup("node_sets");
  for (const std::string& name : sets.ChildNames()) {
    const std::vector<std::int64_t> nodes = sets.ReadIntegers(name);
    body.node_sets[name].assign(nodes.begin(), nodes.end());
  }
  const h5::Group provenance = root.OpenGroup("provenance");
  const std::vector<std::string> keys = provenance.ReadStrings("keys");
  const std::vector<std::string> values = provenance.ReadStrings("values");
  if (keys.size() != values.size()) {
    throw InputError(fmt::format("{}: /provenance: {} keys but {} values", path.string(), keys.size(), values.size()));
  }
  for (std::size_t i = 0; i < keys.size(); ++i) body.provenance[keys[i]] = values[i];
  const auto n = static_cast<std::size_t>(body.phi.cols());
  if (body.mode_names.size() != n || body.mode_kinds.size() != n ||
      static_cast<std::size_t>(body.frequency_hz.size()) != n ||
      static_cast<std::size_t>(body.participation.rows()) != n || body.participation.cols() != 6 ||
      body.phi.rows() != 3 * body.node_positions.cols()) {
    throw InputError(fmt::format("{}: inconsistent body: {} modes in /modes/phi, {} names, {} kinds, "
                                 "{} frequencies, {} rows for {} nodes",
                                 path.string(), n, body.mode_names.size(), body.mode_kinds.size(),
                                 body.frequency_hz.size(), body.phi.rows(), body.node_positions.cols()));
  }
  return body;
}

}  // namespace flexmbs::reduction
