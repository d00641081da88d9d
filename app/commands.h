#pragma once

#include <CLI/CLI.hpp>

namespace flexmbs::app {

/// Registers `flexmbs mesh body.yaml [--json] [--matrix-market PREFIX]`: mesh and assemble a
/// body and report its FE model.
void AddMeshCommand(CLI::App& app);

/// Registers `flexmbs reduce body.yaml -o body.sid.h5 [--json]`: mesh, assemble and reduce a
/// body as its `reduction` section says, and write the reduced body file.
void AddReduceCommand(CLI::App& app);

/// Registers `flexmbs compare A.sid.h5 B.sid.h5|body.yaml [--json] [--modes N]`: frequency
/// errors, MAC matrix and effective modal mass of two bases of one body, or of a reduced body's
/// system modes against its full FE model.
void AddCompareCommand(CLI::App& app);

/// Registers `flexmbs info FILE [--json]`: a summary of a flexmbs file (a reduced body .sid.h5),
/// chosen by the file's `format` attribute.
void AddInfoCommand(CLI::App& app);

/// Registers `flexmbs export BODY.sid.h5 -o OUT --format sid-ascii`: a reduced body in another
/// program's file format.
void AddExportCommand(CLI::App& app);

/// Registers `flexmbs simulate scene.yaml -o results.h5 [--json]`: integrate a scene and write
/// its results file.
void AddSimulateCommand(CLI::App& app);

}  // namespace flexmbs::app
