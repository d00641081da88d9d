// Reads `.sid.h5` into a ReducedBody (layout: docs/sid.md, names and units: sid_layout.h).
// Every numeric dataset's units are checked, and the assembled body's sizes must agree.
#include <fmt/format.h>

#include <limits>

#include "core/error.h"
#include "core/h5_file.h"
#include "sid/sid_digest.h"
#include "sid/sid_file.h"
#include "sid/sid_layout.h"

namespace flexmbs::sid {
namespace {

/// Reads `name` after checking its units.
Eigen::MatrixXd ReadMatrixIn(const h5::Group& group, std::string_view name, std::string_view units) {
  group.RequireUnits(name, units);
  return group.ReadMatrix(name);
}

/// Splits a dataset of stacked blocks (rows x cols each) into `count` blocks.
std::vector<Eigen::MatrixXd> Unstack(const std::filesystem::path& path, const h5::Group& group,
                                     std::string_view name, std::string_view units, std::size_t count,
                                     Eigen::Index rows, Eigen::Index cols) {
  const Eigen::MatrixXd stacked = ReadMatrixIn(group, name, units);
  if (stacked.rows() != static_cast<Eigen::Index>(count) * rows || stacked.cols() != cols) {
    throw InputError(fmt::format("{}: {}/{}: {} x {}, expected {} blocks of {} x {}", path.string(), group.path(),
                                 name, stacked.rows(), stacked.cols(), count, rows, cols));
  }
  std::vector<Eigen::MatrixXd> blocks(count);
  for (std::size_t j = 0; j < count; ++j) blocks[j] = stacked.middleRows(static_cast<Eigen::Index>(j) * rows, rows);
  return blocks;
}

TaylorMatrix ReadTaylor(const std::filesystem::path& path, const h5::Group& parent, std::string_view name,
                        const layout::TaylorUnits& units) {
  const h5::Group group = parent.OpenGroup(name);
  TaylorMatrix block;
  block.m0 = ReadMatrixIn(group, "m0", units.m0);
  const std::int64_t order = group.GetIntegerAttribute("order");
  const std::int64_t modes = group.GetIntegerAttribute("modes");
  if (order < 0 || order > 2 || modes < 0 || (order > 0 && units.m1.empty()) || (order > 1 && units.m2.empty())) {
    throw InputError(fmt::format("{}: {}: order {} with {} modes is not allowed here", path.string(), group.path(),
                                 order, modes));
  }
  const auto n = static_cast<std::size_t>(modes);
  if (order >= 1) block.m1 = Unstack(path, group, "m1", units.m1, n, block.m0.rows(), block.m0.cols());
  if (order >= 2) block.m2 = Unstack(path, group, "m2", units.m2, n * n, block.m0.rows(), block.m0.cols());
  return block;
}

GeometricStiffening ReadStiffening(const h5::Group& root) {
  const h5::Group group = root.OpenGroup("stiffening");
  GeometricStiffening stiffening;
  for (std::size_t a = 0; a < 3; ++a) {
    stiffening.K0t[a] = ReadMatrixIn(group, fmt::format("K0t_{}", layout::kAxes[a]), layout::kK0tUnits);
    stiffening.K0r[a] = ReadMatrixIn(group, fmt::format("K0r_{}", layout::kAxes[a]), layout::kK0rUnits);
  }
  for (std::size_t l = 0; l < 6; ++l) {
    stiffening.K0omega[l] =
        ReadMatrixIn(group, fmt::format("K0omega_{}", layout::kOmegaProducts[l]), layout::kK0omegaUnits);
  }
  return stiffening;
}

std::vector<int> ReadIndices(const h5::Group& group, std::string_view name) {
  group.RequireUnits(name, "1");
  const std::vector<std::int64_t> values = group.ReadIntegers(name);
  std::vector<int> indices;
  indices.reserve(values.size());
  for (std::int64_t v : values) {
    indices.push_back(v < 0 || v > std::numeric_limits<int>::max() ? -1 : static_cast<int>(v));
  }
  return indices;
}

std::vector<Node> ReadNodes(const std::filesystem::path& path, const h5::Group& root) {
  const h5::Group group = root.OpenGroup("nodes");
  std::vector<Node> nodes;
  for (const std::string& name : group.ChildNames()) {
    const h5::Group g = group.OpenGroup(name);
    Node node;
    node.name = name;
    node.coupling = g.GetStringAttribute("coupling");
    node.fe_nodes = ReadIndices(g, "fe_nodes");
    for (const layout::NodeField& field : layout::kNodeFields) {
      node.*field.member = ReadTaylor(path, g, field.name, field.units);
    }
    nodes.push_back(std::move(node));
  }
  return nodes;
}

std::vector<ContactSurface> ReadSurfaces(const h5::Group& root) {
  const h5::Group group = root.OpenGroup("surfaces");
  std::vector<ContactSurface> surfaces;
  for (const std::string& name : group.ChildNames()) {
    const h5::Group g = group.OpenGroup(name);
    ContactSurface surface;
    surface.name = name;
    surface.fe_nodes = ReadIndices(g, "fe_nodes");
    surface.vertices = ReadMatrixIn(g, "vertices", "m");
    surface.face_sizes = ReadIndices(g, "face_sizes");
    surface.face_vertices = ReadIndices(g, "face_vertices");
    surface.face_normals = ReadMatrixIn(g, "face_normals", "1");
    surface.phi = ReadMatrixIn(g, "phi", "m/q");
    surfaces.push_back(std::move(surface));
  }
  return surfaces;
}

// The schema version of the open file's root, checked to be flexmbs-sid and readable. The
// version (an integer) is read before the format (a string), so that a file of an earlier
// schema, whose strings are of a kind this reader refuses, gets the command that regenerates it.
int CheckedSchemaVersion(const std::filesystem::path& path, const h5::Group& root) {
  if (!root.HasAttribute("format")) {
    throw InputError(fmt::format("{}: not a flexmbs reduced body (no format '{}')", path.string(), kSidFormat));
  }
  const std::int64_t version = root.HasAttribute("schema_version") ? root.GetIntegerAttribute("schema_version") : 0;
  if (version > 0 && version < kSidOldestReadableSchemaVersion) {
    throw InputError(fmt::format("{}: schema_version {} was written by an earlier flexmbs, without checksums or "
                                 "content digest; regenerate it with `flexmbs reduce BODY.yaml -o {}`",
                                 path.string(), version, path.string()));
  }
  if (root.GetStringAttribute("format") != kSidFormat) {
    throw InputError(fmt::format("{}: not a flexmbs reduced body (no format '{}')", path.string(), kSidFormat));
  }
  if (version > kSidSchemaVersion || version == 0) {
    throw InputError(fmt::format("{}: schema_version {} is not supported (this flexmbs reads {} to {}; "
                                 "run `flexmbs reduce` again)",
                                 path.string(), version, kSidOldestReadableSchemaVersion, kSidSchemaVersion));
  }
  return static_cast<int>(version);
}

/// Throws InputError unless `body`'s content digest is the one the writer of a file of
/// `schema_version` stored (sid_layout.h: the attribute and hash of that schema).
void CheckDigest(const std::filesystem::path& path, const h5::Group& root, const ReducedBody& body,
                 int schema_version) {
  const layout::ContentDigestField field = layout::ContentDigestOf(schema_version);
  const std::string stored = root.GetStringAttribute(field.attribute);
  const std::string computed = ContentDigest(body, field.algorithm);
  if (stored != computed) {
    throw InputError(fmt::format("{}: content digest mismatch: the body was damaged or edited after `flexmbs "
                                 "reduce` wrote it (stored {:.16}..., computed {:.16}...)",
                                 path.string(), stored, computed));
  }
}

}  // namespace

int ReadSidSchemaVersion(const std::filesystem::path& path) {
  const h5::File file = h5::File::Open(path);
  return CheckedSchemaVersion(path, file.root());
}

ReducedBody ReadReducedBody(const std::filesystem::path& path) {
  const h5::File file = h5::File::Open(path);
  const h5::Group root = file.root();
  const int schema_version = CheckedSchemaVersion(path, root);
  ReducedBody body;
  body.name = root.GetStringAttribute("name");
  const h5::Group refmod = root.OpenGroup("refmod");
  refmod.RequireUnits("mass", "kg");
  body.mass = refmod.ReadScalar("mass");
  refmod.RequireUnits("center_of_mass", "m");
  const Eigen::VectorXd center = refmod.ReadVector("center_of_mass");
  const Eigen::MatrixXd inertia = ReadMatrixIn(refmod, "inertia_about_center_of_mass", "kg m^2");
  if (center.size() != 3 || inertia.rows() != 3 || inertia.cols() != 3) {
    throw InputError(fmt::format("{}: /refmod: centre of mass of size {} or inertia {} x {} (expected 3, 3 x 3)",
                                 path.string(), center.size(), inertia.rows(), inertia.cols()));
  }
  body.center_of_mass = center;
  body.inertia_about_center_of_mass = inertia;
  body.mode_names = refmod.ReadStrings("mode_names");
  body.mode_kinds = refmod.ReadStrings("mode_kinds");
  refmod.RequireUnits("frequency_hz", "Hz");
  body.frequency_hz = refmod.ReadVector("frequency_hz");
  refmod.RequireUnits("relative_residuals", "1");
  body.relative_residuals = refmod.ReadVector("relative_residuals");
  body.damping = refmod.GetStringAttribute("damping");

  const h5::Group invariants = root.OpenGroup("invariants");
  for (const layout::InvariantField& field : layout::kInvariants) {
    body.*field.member = ReadTaylor(path, invariants, field.name, field.units);
  }
  if (root.HasGroup("stiffening")) body.stiffening = ReadStiffening(root);

  body.phi = ReadMatrixIn(root.OpenGroup("modes"), "phi", "m/q");
  const h5::Group mesh = root.OpenGroup("mesh");
  body.node_positions = ReadMatrixIn(mesh, "node_positions", "m").transpose();
  const h5::Group sets = mesh.OpenGroup("node_sets");
  for (const std::string& name : sets.ChildNames()) body.node_sets[name] = ReadIndices(sets, name);
  body.nodes = ReadNodes(path, root);
  body.surfaces = ReadSurfaces(root);
  if (root.HasGroup("visual_surface")) {
    const h5::Group visual = root.OpenGroup("visual_surface");
    body.visual_surface.face_sizes = ReadIndices(visual, "face_sizes");
    body.visual_surface.face_nodes = ReadIndices(visual, "face_nodes");
  }

  const h5::Group provenance = root.OpenGroup("provenance");
  const std::vector<std::string> keys = provenance.ReadStrings("keys");
  const std::vector<std::string> values = provenance.ReadStrings("values");
  if (keys.size() != values.size()) {
    throw InputError(fmt::format("{}: /provenance: {} keys but {} values", path.string(), keys.size(), values.size()));
  }
  for (std::size_t i = 0; i < keys.size(); ++i) body.provenance[keys[i]] = values[i];
  const std::string problem = FindInconsistency(body);
  if (!problem.empty()) throw InputError(fmt::format("{}: inconsistent body: {}", path.string(), problem));
  CheckDigest(path, root, body, schema_version);
  return body;
}

h5::VerifyReport VerifyReducedBodyFile(const std::filesystem::path& path) {
  ReadReducedBody(path);
  return h5::File::Open(path).root().VerifyAll();
}

}  // namespace flexmbs::sid
