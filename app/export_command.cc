// `flexmbs export`: a reduced body in another program's file format.
#include <array>
#include <filesystem>
#include <fmt/format.h>
#include <memory>
#include <string>
#include <string_view>

#include "app/command_support.h"
#include "app/commands.h"
#include "core/error.h"
#include "sid/sid_ascii.h"
#include "sid/sid_file.h"

namespace flexmbs::app {
namespace {

struct ExportOptions {
  std::string body_file;
  std::string output;
  std::string format;
};

/// A format `flexmbs export` writes: its name on the command line and its writer (atomic).
struct ExportFormat {
  std::string_view name;
  void (*write)(const std::filesystem::path& path, const sid::ReducedBody& body);
};

/// sid-ascii: the ASCII SID file of SIMPACK's FEMBS (docs/sid-ascii.md).
constexpr std::array<ExportFormat, 1> kFormats{{{"sid-ascii", &sid::WriteSidAscii}}};

/// The format named `name`; InputError listing the known ones otherwise.
const ExportFormat& FindFormat(std::string_view name) {
  std::string known;
  for (const ExportFormat& format : kFormats) {
    if (format.name == name) return format;
    known += fmt::format("{}{}", known.empty() ? "" : ", ", format.name);
  }
  throw InputError(fmt::format("--format {}: unknown export format (known: {})", name, known));
}

void RunExport(const ExportOptions& options) {
  const ExportFormat& format = FindFormat(options.format);
  CheckOutputFolder("-o", options.output);
  const sid::ReducedBody body = sid::ReadReducedBody(options.body_file);
  format.write(options.output, body);
  fmt::print("wrote           {} ({}: {} modes, {} nodes)\n", options.output, format.name, body.num_modes(),
             body.nodes.size());
}

}  // namespace

void AddExportCommand(CLI::App& app) {
  auto options = std::make_shared<ExportOptions>();
  CLI::App* cmd = app.add_subcommand("export", "Write a reduced body in another program's format (sid-ascii)");
  cmd->add_option("body", options->body_file, "The reduced body (.sid.h5)")->required();
  cmd->add_option("-o,--output", options->output, "The file to write")->required();
  cmd->add_option("--format", options->format, "The format to write: sid-ascii (SIMPACK FEMBS ASCII SID)")
      ->required();
  cmd->callback([options] { RunExport(*options); });
}

}  // namespace flexmbs::app
