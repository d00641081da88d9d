#pragma once
// The small reduced body of the end-to-end reduce tests: a tet10 steel block of unequal sides
// (distinct frequencies) with a node set "root" on its x = 0 face.

#include <filesystem>
#include <fstream>
#include <string>

namespace flexmbs::testing {

/// Writes block.geo into `dir` and returns a body file's text for it with the given
/// `reduction:` value (a YAML flow map, e.g. "{method: free_free, modes: 6}").
inline std::string BlockBody(const std::filesystem::path& dir, const std::string& reduction) {
  std::ofstream(dir / "block.geo")
      << "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 0.1, 0.07, 0.04};\n"
      << "Physical Volume(\"block\") = {1};\n"
      << "Physical Surface(\"root\") = Surface In BoundingBox{-1e-6, -1, -1, 1e-6, 1, 1};\n";
  return "geometry: {file: block.geo, mesh_size: 0.02, element_order: 2}\n"
         "materials: {steel: {youngs_modulus: 2.1e11, poisson_ratio: 0.3, density: 7850}}\n"
         "node_sets: [root]\n"
         "reduction: " + reduction + "\n";
}

}  // namespace flexmbs::testing
