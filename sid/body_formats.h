#pragma once
// The file formats a reduced body can be written in, by name: the choices of
// `flexmbs reduce --format` and `flexmbs export --format`.

#include <filesystem>
#include <span>
#include <string_view>

#include "sid/reduced_body.h"

namespace flexmbs::sid {

/// A file format of reduced bodies: its command-line name and its (atomic) writer.
struct BodyFormat {
  std::string_view name;         ///< "sid-h5", "sid-ascii"
  std::string_view description;  ///< for --help
  void (*write)(const std::filesystem::path& path, const ReducedBody& body);
};

/// All formats, the default (sid-h5, docs/sid.md) first; sid-ascii is SIMPACK FEMBS's ASCII
/// SID (docs/sid-ascii.md).
std::span<const BodyFormat> BodyFormats();

/// The format named `name`. Throws InputError "--format <name>: unknown format (known: ...)".
const BodyFormat& FindBodyFormat(std::string_view name);

}  // namespace flexmbs::sid
