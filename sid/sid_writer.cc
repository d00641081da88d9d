// Writes a ReducedBody to `.sid.h5` (layout: docs/sid.md, names and units: sid_layout.h).
#include <fmt/format.h>

#include <future>
#include <string>

#include "core/error.h"
#include "core/h5_file.h"
#include "core/version.h"
#include "sid/sid_digest.h"
#include "sid/sid_file.h"
#include "sid/sid_layout.h"

namespace flexmbs::sid {
namespace {

/// The blocks stacked vertically: block j is rows j r .. j r + r - 1 (r rows per block).
Eigen::MatrixXd Stack(const std::vector<Eigen::MatrixXd>& blocks, Eigen::Index rows, Eigen::Index cols) {
  Eigen::MatrixXd stacked(static_cast<Eigen::Index>(blocks.size()) * rows, cols);
  for (std::size_t j = 0; j < blocks.size(); ++j) {
    stacked.middleRows(static_cast<Eigen::Index>(j) * rows, rows) = blocks[j];
  }
  return stacked;
}

void WriteTaylor(h5::Group& parent, std::string_view name, const TaylorMatrix& block,
                 const layout::TaylorUnits& units) {
  h5::Group group = parent.CreateGroup(name);
  group.SetIntegerAttribute("order", block.order());
  group.SetIntegerAttribute("rows", block.m0.rows());
  group.SetIntegerAttribute("cols", block.m0.cols());
  group.SetIntegerAttribute("modes", static_cast<std::int64_t>(block.m1.size()));
  group.WriteMatrix("m0", block.m0, units.m0);
  if (block.order() >= 1) group.WriteMatrix("m1", Stack(block.m1, block.m0.rows(), block.m0.cols()), units.m1);
  if (block.order() >= 2) group.WriteMatrix("m2", Stack(block.m2, block.m0.rows(), block.m0.cols()), units.m2);
}

void WriteStiffening(h5::Group& root, const GeometricStiffening& stiffening) {
  h5::Group group = root.CreateGroup("stiffening");
  for (std::size_t a = 0; a < 3; ++a) {
    group.WriteMatrix(fmt::format("K0t_{}", layout::kAxes[a]), stiffening.K0t[a], layout::kK0tUnits);
    group.WriteMatrix(fmt::format("K0r_{}", layout::kAxes[a]), stiffening.K0r[a], layout::kK0rUnits);
  }
  for (std::size_t l = 0; l < 6; ++l) {
    group.WriteMatrix(fmt::format("K0omega_{}", layout::kOmegaProducts[l]), stiffening.K0omega[l],
                      layout::kK0omegaUnits);
  }
}

void WriteNodes(h5::Group& root, const std::vector<Node>& nodes) {
  h5::Group group = root.CreateGroup("nodes");
  for (const Node& node : nodes) {
    h5::Group g = group.CreateGroup(node.name);
    g.SetStringAttribute("coupling", node.coupling);
    g.WriteIntegers("fe_nodes", node.fe_nodes, "1");
    for (const layout::NodeField& field : layout::kNodeFields) {
      WriteTaylor(g, field.name, node.*field.member, field.units);
    }
  }
}

void WriteSurfaces(h5::Group& root, const std::vector<ContactSurface>& surfaces) {
  h5::Group group = root.CreateGroup("surfaces");
  for (const ContactSurface& surface : surfaces) {
    h5::Group g = group.CreateGroup(surface.name);
    g.WriteIntegers("fe_nodes", surface.fe_nodes, "1");
    g.WriteMatrix("vertices", surface.vertices, "m");
    g.WriteIntegers("face_sizes", surface.face_sizes, "1");
    g.WriteIntegers("face_vertices", surface.face_vertices, "1");
    g.WriteMatrix("face_normals", surface.face_normals, "1");
    g.WriteMatrix("phi", surface.phi, "m/q");
  }
}

void WriteVisualSurface(h5::Group& root, const VisualSurface& surface) {
  h5::Group group = root.CreateGroup("visual_surface");
  group.WriteIntegers("face_sizes", surface.face_sizes, "1");
  group.WriteIntegers("face_nodes", surface.face_nodes, "1");
}

}  // namespace

void WriteReducedBody(const std::filesystem::path& path, const ReducedBody& body, int schema_version) {
  FLEXMBS_CHECK(schema_version >= kSidOldestReadableSchemaVersion && schema_version <= kSidSchemaVersion,
                fmt::format("a body of schema {} cannot be written", schema_version));
  CheckConsistent(body);
  // The content digest runs on a thread of its own beside the HDF5 writes (docs/h5.md, "Cost of
  // the checksums"); it only reads `body`, and HDF5 stays on this thread.
  const layout::ContentDigestField digest_field = layout::ContentDigestOf(schema_version);
  std::future<std::string> digest =
      std::async(std::launch::async, [&body, &digest_field] { return ContentDigest(body, digest_field.algorithm); });
  h5::File file = h5::File::Create(path);
  h5::Group root = file.root();
  root.SetStringAttribute("format", kSidFormat);
  root.SetIntegerAttribute("schema_version", schema_version);
  root.SetStringAttribute("name", body.name);

  h5::Group refmod = root.CreateGroup("refmod");
  refmod.WriteScalar("mass", body.mass, "kg");
  refmod.WriteVector("center_of_mass", body.center_of_mass, "m");
  refmod.WriteMatrix("inertia_about_center_of_mass", body.inertia_about_center_of_mass, "kg m^2");
  refmod.WriteStrings("mode_names", body.mode_names);
  refmod.WriteStrings("mode_kinds", body.mode_kinds);
  refmod.WriteVector("frequency_hz", body.frequency_hz, "Hz");
  refmod.WriteVector("relative_residuals", body.relative_residuals, "1");
  refmod.SetStringAttribute("damping", body.damping);

  h5::Group invariants = root.CreateGroup("invariants");
  for (const layout::InvariantField& field : layout::kInvariants) {
    WriteTaylor(invariants, field.name, body.*field.member, field.units);
  }
  if (!body.stiffening.empty()) WriteStiffening(root, body.stiffening);

  root.CreateGroup("modes").WriteMatrix("phi", body.phi, "m/q");
  h5::Group mesh = root.CreateGroup("mesh");
  mesh.WriteMatrix("node_positions", body.node_positions.transpose(), "m");
  h5::Group sets = mesh.CreateGroup("node_sets");
  for (const auto& [name, nodes] : body.node_sets) sets.WriteIntegers(name, nodes, "1");
  WriteNodes(root, body.nodes);
  WriteSurfaces(root, body.surfaces);
  if (!body.visual_surface.empty()) WriteVisualSurface(root, body.visual_surface);

  // Provenance as two parallel string lists, so that any key round-trips.
  root.SetStringAttribute(digest_field.attribute, digest.get());
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

void WriteReducedBody(const std::filesystem::path& path, const ReducedBody& body) {
  WriteReducedBody(path, body, kSidSchemaVersion);
}

}  // namespace flexmbs::sid
