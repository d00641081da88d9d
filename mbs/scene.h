#pragma once
// A scene file (YAML, docs/scene.md): bodies (rigid, or reduced flexible bodies from `.sid.h5`
// files with the modes the scene keeps), their initial state, joints and drivers, force
// elements, gravity, the integrator and the outputs, turned into a MultibodySystem ready to
// simulate.

#include <Eigen/Core>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "mbs/multibody_system.h"
#include "mbs/scene_hooks.h"
#include "mbs/simulation.h"

namespace flexmbs::mbs {

/// A marker whose position the results record, by body and marker index.
struct RecordedMarker {
  int body = 0;
  int marker = 0;
  std::string name;  ///< the marker's name on its body
};

/// `output.paraview` (docs/scene.md): whether ParaView files are written beside the results
/// file (ParaviewWriter), and of every how many output samples.
struct ParaviewOutput {
  bool enabled = false;
  int every = 1;  ///< >= 1
};

/// A loaded scene.
struct Scene {
  std::filesystem::path file;
  std::unique_ptr<MultibodySystem> system;
  Eigen::VectorXd initial_state;  ///< y0 = [x; u] as the file gives it (Simulate checks consistency)
  SimulationOptions options;
  std::vector<RecordedMarker> recorded_markers;
  ParaviewOutput paraview;
  /// Per body: "rigid" or "flexible", and the `.sid.h5` file of flexible bodies.
  std::vector<std::string> body_kinds;
  std::vector<std::filesystem::path> body_files;
};

/// Reads and builds the scene in `file` (relative `.sid.h5` paths are resolved against its
/// folder). Throws InputError "<file>:<line>:<col>: <item>: <problem>" for malformed YAML, an
/// unknown or missing key, a non-finite number, an unknown body, marker, mode or joint type, a
/// joint or element from a body to itself, a body file that cannot be read or has the wrong
/// schema, a wrong number of initial modal coordinates, and bad simulation or output settings.
/// `hooks`: computations of stages mbs/ does not link (app/'s FE tooth for `teeth: fe`); without
/// them the entries that need one are refused.
Scene LoadScene(const std::filesystem::path& file, const SceneHooks& hooks = {});

}  // namespace flexmbs::mbs
