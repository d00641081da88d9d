#pragma once

#include <CLI/CLI.hpp>

namespace flexmbs::app {

/// Registers `flexmbs mesh body.yaml [--json] [--matrix-market PREFIX]`: mesh and assemble a
/// body and report its FE model.
void AddMeshCommand(CLI::App& app);

}  // namespace flexmbs::app
