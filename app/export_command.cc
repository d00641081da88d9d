// `flexmbs export`: a reduced body in another program's file format.
#include <filesystem>
#include <fmt/format.h>
#include <memory>
#include <string>
#include <string_view>

#include "app/command_support.h"
#include "app/commands.h"
#include "core/error.h"
#include "sid/body_formats.h"
#include "sid/sid_file.h"

namespace flexmbs::app {
namespace {

struct ExportOptions {
  std::string body_file;
  std::string output;
  std::string format;
};

void RunExport(const ExportOptions& options) {
  const sid::BodyFormat& format = sid::FindBodyFormat(options.format);
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
  cmd->add_option("--format", options->format, FormatHelp())->required();
  cmd->callback([options] { RunExport(*options); });
}

}  // namespace flexmbs::app
