#pragma once
// The `.sid.h5` file (layout in docs/sid.md): the writer used by `flexmbs reduce` and the
// reader that is the only door between preprocessing and simulation.

#include <filesystem>
#include <string>
#include <string_view>

#include "core/h5_file.h"
#include "sid/reduced_body.h"

namespace flexmbs::sid {

/// The root attribute `format` of every `.sid.h5` file.
inline constexpr std::string_view kSidFormat = "flexmbs-sid";

/// The `.sid.h5` schema this code writes (bumped when the layout changes). Schema 4: every
/// dataset checksummed (Fletcher32), fixed-length strings, the root attribute `content_sha256`
/// (SHA-256). Schema 5: the same with the content digest `content_xxh3_128` (XXH3-128), about
/// ten times cheaper to compute (docs/h5.md, "Cost of the checksums").
inline constexpr int kSidSchemaVersion = 5;

/// The oldest schema the reader reads: older files (variable-length strings, no checksums, no
/// content digest) are refused with the command that regenerates them. Schema 4 files are read
/// and their SHA-256 digest checked.
inline constexpr int kSidOldestReadableSchemaVersion = 4;

/// Writes `body` to `path` atomically (a temporary renamed into place only when complete), with
/// its content digest (sid_digest.h), in schema kSidSchemaVersion.
/// Throws InputError naming `path` if it cannot be written; InternalError if the body is not
/// self-consistent (a per-mode list or a Taylor block of the wrong size).
void WriteReducedBody(const std::filesystem::path& path, const ReducedBody& body);

/// WriteReducedBody in schema `schema_version` (kSidOldestReadableSchemaVersion ..
/// kSidSchemaVersion, else InternalError), whose hash the content digest takes: for tests and
/// benchmarks that need a file of the previous schema.
void WriteReducedBody(const std::filesystem::path& path, const ReducedBody& body, int schema_version);

/// Reads a `.sid.h5` file of schema kSidOldestReadableSchemaVersion .. kSidSchemaVersion.
/// Throws InputError (one line, naming `path`) for a missing, foreign (not flexmbs), truncated
/// or wrong-version file, a missing, mis-shaped, mistyped or unit-less dataset, a checksum
/// mismatch, and a body whose content digest differs from the one `reduce` wrote.
ReducedBody ReadReducedBody(const std::filesystem::path& path);

/// Reads the body (ReadReducedBody) and then every object of the file in full
/// (h5::Group::VerifyAll): what `flexmbs info --verify` checks. Throws the first problem.
h5::VerifyReport VerifyReducedBodyFile(const std::filesystem::path& path);

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
