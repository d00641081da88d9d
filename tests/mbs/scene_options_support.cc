#include "tests/mbs/scene_options_support.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "mbs/scene.h"

namespace flexmbs::testing {

mbs::OdeOptions LoadImplicitIntegratorOptions(const std::string& extra_lines) {
  const std::filesystem::path directory =
      std::filesystem::temp_directory_path() / ("flexmbs_scene_options_" + std::to_string(getpid()));
  std::filesystem::create_directories(directory);
  const std::filesystem::path file = directory / "scene.yaml";
  std::ofstream(file) << "bodies:\n  box:\n    rigid: {mass: 1.0, inertia: [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}\n"
                      << "simulation:\n  end_time: 1.0\n  method: implicit\n"
                      << extra_lines;
  struct RemoveDirectory {
    std::filesystem::path path;
    ~RemoveDirectory() { std::filesystem::remove_all(path); }
  } cleanup{directory};
  return mbs::LoadScene(file).options.integrator;
}

}  // namespace flexmbs::testing
