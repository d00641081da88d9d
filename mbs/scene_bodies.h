#pragma once
// The `bodies:` section of a scene file (docs/scene.md): rigid and flexible bodies and their
// initial states. Internal to scene.cc.

#include <filesystem>
#include <memory>
#include <string>

#include "core/yaml_node.h"
#include "mbs/body.h"

namespace flexmbs::mbs {

/// One body of the scene with its initial positions and velocities.
struct SceneBody {
  std::unique_ptr<Body> body;
  std::string kind;              ///< "rigid" or "flexible"
  std::filesystem::path file;    ///< the `.sid.h5` file of a flexible body
  Eigen::VectorXd x0, u0;        ///< initial x_b and u_b (body.h)
};

/// Reads the body `name` from its item (the value under `bodies.<name>`); `folder` resolves
/// relative `.sid.h5` paths.
SceneBody ReadSceneBody(const std::string& name, const YamlNode& node, const std::filesystem::path& folder);

}  // namespace flexmbs::mbs
