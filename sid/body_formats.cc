#include "sid/body_formats.h"

#include <array>
#include <fmt/format.h>

#include "core/error.h"
#include "sid/sid_ascii.h"
#include "sid/sid_file.h"

namespace flexmbs::sid {
namespace {

constexpr std::array<BodyFormat, 2> kFormats{{
    {"sid-h5", "flexmbs reduced body in HDF5 (docs/sid.md)", &WriteReducedBody},
    {"sid-ascii", "SIMPACK FEMBS ASCII SID (docs/sid-ascii.md)", &WriteSidAscii},
}};

}  // namespace

std::span<const BodyFormat> BodyFormats() { return kFormats; }

const BodyFormat& FindBodyFormat(std::string_view name) {
  std::string known;
  for (const BodyFormat& format : kFormats) {
    if (format.name == name) return format;
    known += fmt::format("{}{}", known.empty() ? "" : ", ", format.name);
  }
  throw InputError(fmt::format("--format {}: unknown format (known: {})", name, known));
}

}  // namespace flexmbs::sid
