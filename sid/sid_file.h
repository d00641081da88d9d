#pragma once
// The `.sid.h5` file (layout in docs/sid.md): the writer used by `flexmbs reduce` and the
// reader that is the only door between preprocessing and simulation.

#include <filesystem>
#include <string>
#include <string_view>

#include "sid/reduced_body.h"

namespace flexmbs::sid {

/// The root attribute `format` of every `.sid.h5` file.
inline constexpr std::string_view kSidFormat = "flexmbs-sid";

/// The `.sid.h5` schema this code writes (bumped when the layout changes).
inline constexpr int kSidSchemaVersion = 3;

/// The oldest schema the reader still reads: schema 2 lacks only `/visual_surface`, which
/// reads as an empty sid::VisualSurface.
inline constexpr int kSidOldestReadableSchemaVersion = 2;

/// Writes `body` to `path` atomically (a temporary renamed into place only when complete).
/// Throws InputError naming `path` if it cannot be written; InternalError if the body is not
/// self-consistent (a per-mode list or a Taylor block of the wrong size).
void WriteReducedBody(const std::filesystem::path& path, const ReducedBody& body);

/// Reads a `.sid.h5` file of schema kSidOldestReadableSchemaVersion .. kSidSchemaVersion.
/// Throws InputError (one line, naming `path`) for a missing, foreign (not flexmbs), truncated
/// or wrong-version file, or a missing, mis-shaped or unit-less dataset.
ReducedBody ReadReducedBody(const std::filesystem::path& path);

/// The schema version of a readable `.sid.h5` file (the checks and errors of ReadReducedBody's
/// header).
int ReadSidSchemaVersion(const std::filesystem::path& path);

/// The first inconsistency of `body` (a per-mode list, Taylor block, node or surface of a size
/// its number of modes and nodes does not allow), or "" if there is none.
std::string FindInconsistency(const ReducedBody& body);

/// Throws InternalError unless every per-mode list, Taylor block, node and surface of `body`
/// has the size its number of modes and nodes require (the writer's precondition).
void CheckConsistent(const ReducedBody& body);

}  // namespace flexmbs::sid
