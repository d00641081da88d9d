#include "fem/body_spec.h"

#include <algorithm>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <set>
#include <system_error>

#include "core/error.h"
#include "core/yaml_node.h"

namespace flexmbs::fem {
namespace {

IsotropicMaterial ReadMaterial(const std::string& name, const YamlNode& node) {
  node.RejectUnknownKeys({"youngs_modulus", "poisson_ratio", "density"});
  IsotropicMaterial m;
  m.name = name;
  m.youngs_modulus_pa = node.Required("youngs_modulus").AsDouble();
  m.poisson_ratio = node.Required("poisson_ratio").AsDouble();
  m.density_kg_m3 = node.Required("density").AsDouble();
  ValidateMaterial(m, node.file().string());
  return m;
}

// The geometry section: the geometry file (resolved against the body file's folder; it must
// exist and not be a folder) and the meshing settings.
void ReadGeometry(const YamlNode& root, const std::filesystem::path& file, BodySpec* spec) {
  const YamlNode geometry = root.Required("geometry");
  geometry.RejectUnknownKeys({"file", "mesh_size", "element_order"});
  const YamlNode geometry_file = geometry.Required("file");
  const std::string geometry_name = geometry_file.AsString();
  if (geometry_name.empty()) geometry_file.Fail("the file name is empty");
  spec->geometry_file = (file.parent_path() / geometry_name).lexically_normal();
  {
    std::error_code ec;
    const std::string resolved =
        spec->geometry_file == std::filesystem::path(geometry_name)
            ? std::string()
            : fmt::format(" (resolved to '{}')", spec->geometry_file.string());
    if (!std::filesystem::exists(spec->geometry_file, ec)) {
      geometry_file.Fail(fmt::format("'{}' does not exist{}", geometry_name, resolved));
    }
    if (std::filesystem::is_directory(spec->geometry_file, ec)) {
      geometry_file.Fail(fmt::format("'{}' is a directory{}", geometry_name, resolved));
    }
  }
  if (geometry.Has("mesh_size")) {
    const YamlNode size = geometry.Required("mesh_size");
    spec->meshing.mesh_size_m = size.AsDouble();
    if (spec->meshing.mesh_size_m <= 0.0) {
      size.Fail(fmt::format("mesh size {:g} m must be > 0", spec->meshing.mesh_size_m));
    }
  }
  if (geometry.Has("element_order")) {
    const YamlNode order = geometry.Required("element_order");
    spec->meshing.element_order = order.AsInt();
    if (spec->meshing.element_order != 1 && spec->meshing.element_order != 2) {
      order.Fail(fmt::format("element order {} must be 1 or 2", spec->meshing.element_order));
    }
  }
}

// The materials and which regions use them: the body's one material unless named.
void ReadMaterials(const YamlNode& root, BodySpec* spec) {
  const YamlNode materials = root.Required("materials");
  for (const auto& [name, node] : materials.AsMap()) {
    spec->materials[name] = ReadMaterial(name, node);
  }
  if (spec->materials.empty()) materials.Fail("define at least one material");
  auto check_material = [&](const YamlNode& node) {
    const std::string name = node.AsString();
    if (!spec->materials.contains(name)) {
      std::vector<std::string> known;
      for (const auto& [known_name, m] : spec->materials) known.push_back(known_name);
      node.Fail(fmt::format("unknown material '{}' (defined: {})", name, fmt::join(known, ", ")));
    }
    return name;
  };
  if (root.Has("material")) spec->default_material = check_material(root.Required("material"));
  if (root.Has("regions")) {
    for (const auto& [region, node] : root.Required("regions").AsMap()) {
      spec->region_materials[region] = check_material(node);
    }
  }
  if (spec->default_material.empty() && spec->region_materials.empty()) {
    if (spec->materials.size() != 1) {
      root.Fail("name the material of each region ('regions') or of the whole body ('material')");
    }
    spec->default_material = spec->materials.begin()->first;
  }
}

// mass_matrix: consistent (the default) or lumped.
void ReadMassMatrixKind(const YamlNode& root, BodySpec* spec) {
  if (!root.Has("mass_matrix")) return;
  const YamlNode kind = root.Required("mass_matrix");
  const std::string value = kind.AsString();
  if (value == "consistent") {
    spec->mass_matrix = MassMatrixKind::kConsistent;
  } else if (value == "lumped") {
    spec->mass_matrix = MassMatrixKind::kLumped;
  } else {
    kind.Fail(fmt::format("'{}' must be 'consistent' or 'lumped'", value));
  }
}

}  // namespace

BodySpec LoadBodySpec(const std::filesystem::path& file) {
  const YamlNode root = YamlNode::LoadFile(file);
  root.RejectUnknownKeys({"name", "geometry", "materials", "material", "regions", "node_sets",
                          "mass_matrix", "reduction", "sid"});
  BodySpec spec;
  spec.file = file;
  spec.name = root.Has("name") ? root.Required("name").AsString() : file.stem().string();
  ReadGeometry(root, file, &spec);
  ReadMaterials(root, &spec);
  if (root.Has("node_sets")) spec.node_sets = root.Required("node_sets").AsStringList();
  ReadMassMatrixKind(root, &spec);
  return spec;
}

Mesh BuildBodyMesh(const BodySpec& spec) {
  Mesh mesh;
  try {
    mesh = ImportMesh(spec.geometry_file, spec.meshing, spec.node_sets);
  } catch (const InputError& e) {
    // "<geometry>: <problem>" from the import; say which body file asked for it.
    throw InputError(fmt::format("{}: {}", spec.file.string(), e.what()));
  }
  for (const auto& [region, material] : spec.region_materials) {
    const bool found = std::any_of(mesh.blocks.begin(), mesh.blocks.end(),
                                   [&wanted = region](const ElementBlock& b) { return b.region == wanted; });
    if (!found) {
      std::set<std::string> available;
      for (const ElementBlock& b : mesh.blocks) available.insert(b.region);
      throw InputError(fmt::format("{}: regions: '{}' is not a physical volume of {} (it has: {})",
                                   spec.file.string(), region, spec.geometry_file.string(),
                                   fmt::join(available, ", ")));
    }
  }
  for (ElementBlock& block : mesh.blocks) {
    const auto it = spec.region_materials.find(block.region);
    const std::string& material = it != spec.region_materials.end() ? it->second : spec.default_material;
    if (material.empty()) {
      throw InputError(fmt::format("{}: regions: region '{}' of {} has no material",
                                   spec.file.string(), block.region, spec.geometry_file.string()));
    }
    block.material = spec.materials.at(material);
  }
  return mesh;
}

SystemMatrices AssembleBodySystem(const BodySpec& spec, const Mesh& mesh) {
  try {
    return AssembleSystem(mesh, spec.mass_matrix);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}: {}", spec.file.string(), spec.geometry_file.string(), e.what()));
  }
}

}  // namespace flexmbs::fem
