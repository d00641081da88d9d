// flexmbs: reduced flexible bodies and multibody simulation with contact.
//
// Exit status (docs/cli.md): 0 success, 1 any other error, 2 bad input (files, values or the
// command line), 3 internal error. Every error is one line on stderr.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <fmt/format.h>
#include <string>

#include "app/commands.h"
#include "core/error.h"
#include "core/version.h"

namespace {

constexpr int kExitOtherError = 1;
constexpr int kExitInputError = 2;
constexpr int kExitInternalError = 3;

// Prints "flexmbs: <prefix><message>" as exactly one line, whatever the message holds.
int Report(int status, std::string_view prefix, std::string message) {
  std::replace(message.begin(), message.end(), '\n', ' ');
  std::replace(message.begin(), message.end(), '\r', ' ');
  std::fflush(stdout);
  fmt::print(stderr, "flexmbs: {}{}\n", prefix, message);
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("flexmbs: flexible multibody dynamics with contact", "flexmbs");
  app.set_version_flag("--version", std::string(flexmbs::Version()));
  app.require_subcommand(1);
  flexmbs::app::AddMeshCommand(app);
  flexmbs::app::AddReduceCommand(app);
  flexmbs::app::AddCompareCommand(app);
  flexmbs::app::AddInfoCommand(app);
  flexmbs::app::AddExportCommand(app);
  flexmbs::app::AddSimulateCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    return Report(kExitInputError, "error: ", fmt::format("{} (see 'flexmbs --help')", e.what()));
  } catch (const flexmbs::InputError& e) {
    return Report(kExitInputError, "error: ", e.what());
  } catch (const flexmbs::InternalError& e) {
    return Report(kExitInternalError, "internal error (please report): ", e.what());
  } catch (const std::exception& e) {
    return Report(kExitOtherError, "error: ", e.what());
  } catch (...) {
    return Report(kExitOtherError, "error: ", "unknown exception");
  }
  return 0;
}
