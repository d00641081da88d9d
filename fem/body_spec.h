#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "fem/assembly.h"
#include "fem/element_integrator.h"
#include "fem/gmsh_import.h"
#include "fem/material.h"
#include "fem/mesh.h"

namespace flexmbs::fem {

/// The FE part of a body file (YAML):
///
///     name: cantilever
///     geometry:
///       file: ../meshes/beam.geo   # .geo, .step/.stp or .msh, relative to this file
///       mesh_size: 0.005           # m, optional
///       element_order: 2           # 1 or 2, default 2
///     materials:
///       steel: {youngs_modulus: 2.1e11, poisson_ratio: 0.3, density: 7850}
///     material: steel              # for every region, or per physical volume:
///     regions: {beam: steel}
///     node_sets: [clamp, tip]      # physical groups to keep as named node sets
///     mass_matrix: consistent      # or lumped
///
/// The sections `reduction` (reduction/reduction_spec.h) and `sid` (reduction/sid_spec.h) belong
/// to later stages and are read there.
struct BodySpec {
  std::filesystem::path file;  ///< the body file itself, for messages
  std::string name;
  std::filesystem::path geometry_file;  ///< resolved against the body file's folder
  MeshingOptions meshing;
  std::map<std::string, IsotropicMaterial> materials;
  std::string default_material;                      ///< empty if every region is mapped
  std::map<std::string, std::string> region_materials;  ///< physical volume -> material
  std::vector<std::string> node_sets;
  MassMatrixKind mass_matrix = MassMatrixKind::kConsistent;
};

/// Reads and validates a body file. Throws InputError "<file>: <item>: <problem>" for an
/// unreadable file, malformed YAML (with line and column), a missing, unknown or mistyped
/// key, a geometry file that does not exist, an unknown material, or invalid material
/// constants.
BodySpec LoadBodySpec(const std::filesystem::path& file);

/// Meshes the body's geometry and assigns each region its material. Throws InputError for a
/// region without a material, or any import error ("<body file>: <geometry file>: ...").
Mesh BuildBodyMesh(const BodySpec& spec);

/// Assembles K and M of the body's mesh with the body's mass matrix kind. An element error
/// names the body file and the mesh file: "<body>: <mesh>: region 'r': tet10 element 7 ...".
SystemMatrices AssembleBodySystem(const BodySpec& spec, const Mesh& mesh);

}  // namespace flexmbs::fem
