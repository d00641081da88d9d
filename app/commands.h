#pragma once

#include <CLI/CLI.hpp>

namespace flexmbs::app {

/// Registers `flexmbs mesh body.yaml [--json] [--matrix-market PREFIX]`: mesh and assemble a
/// body and report its FE model.
void AddMeshCommand(CLI::App& app);

/// Registers `flexmbs reduce body.yaml -o body.sid.h5 [--json]`: mesh, assemble and reduce a
/// body as its `reduction` section says, and write the reduced body file.
void AddReduceCommand(CLI::App& app);

/// Registers `flexmbs compare A.sid.h5 B.sid.h5 [--json]`: frequency errors, MAC matrix and
/// effective modal mass of two bases of one body.
void AddCompareCommand(CLI::App& app);

}  // namespace flexmbs::app
