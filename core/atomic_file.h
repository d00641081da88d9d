#pragma once

#include <filesystem>
#include <functional>
#include <ostream>

namespace flexmbs {

/// Writes `path` through `write` into a temporary file beside it and renames it into place
/// only when writing succeeded, so an interrupted or failed write never leaves a partial file.
/// Throws InputError naming `path` if the file cannot be written.
void WriteFileAtomically(const std::filesystem::path& path,
                         const std::function<void(std::ostream&)>& write);

/// The temporary name WriteFileAtomically (and other atomic writers) use for `path`:
/// "<path>.tmp.<pid>" in the same folder, so the final rename is atomic.
std::filesystem::path TemporaryPathFor(const std::filesystem::path& path);

/// Renames `temporary` onto `path` atomically; throws InputError naming `path` on failure.
void CommitTemporaryFile(const std::filesystem::path& temporary, const std::filesystem::path& path);

}  // namespace flexmbs
