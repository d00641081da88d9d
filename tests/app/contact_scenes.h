#pragma once
// What the contact tests of the command line share: the example scenes of docs/scene.md and the
// reduced steel cube of tests/data/cube.geo with a contact surface.

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/app/flexmbs_process.h"

namespace flexmbs::testing {

/// The first ```yaml block after `heading` in docs/scene.md ("" if there is none).
inline std::string SceneOfSection(const std::string& heading) {
  std::ifstream in(std::filesystem::path(FLEXMBS_SOURCE_DIR) / "docs" / "scene.md");
  std::stringstream text;
  text << in.rdbuf();
  const std::string page = text.str();
  const std::size_t section = page.find(heading);
  if (section == std::string::npos) return "";
  const std::size_t start = page.find("```yaml\n", section);
  const std::size_t end = page.find("```\n", start + 8);
  if (start == std::string::npos || end == std::string::npos) return "";
  return page.substr(start + 8, end - start - 8);
}

/// Reduces tests/data/cube.geo (a 0.1 m steel cube, tet4 of 0.05 m) by `reduction` (the body
/// file's reduction entries, e.g. "method: free_free, modes: 2") with the contact surface
/// `surface` (node set bottom, z = 0, or top, z = 0.1 m) to cube.sid.h5 in `dir`.
inline Outcome ReduceCube(const std::filesystem::path& dir, const std::string& reduction, const std::string& surface) {
  const std::filesystem::path geometry = std::filesystem::path(FLEXMBS_SOURCE_DIR) / "tests" / "data" / "cube.geo";
  std::ofstream(dir / "cube.yaml") << "name: cube\ngeometry: {file: " << geometry.string()
                                   << ", mesh_size: 0.05, element_order: 1}\nmaterials: {steel: {youngs_modulus: "
                                      "2.1e11, poisson_ratio: 0.3, density: 7850}}\nmaterial: steel\n"
                                      "node_sets: [bottom, top]\nreduction: {"
                                   << reduction << "}\nsid: {contact_surfaces: [" << surface << "]}\n";
  return RunFlexmbs({"reduce", (dir / "cube.yaml").string(), "-o", (dir / "cube.sid.h5").string()}, dir);
}

}  // namespace flexmbs::testing
