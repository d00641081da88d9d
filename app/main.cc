// flexmbs: reduced flexible bodies and multibody simulation with contact.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <fmt/format.h>

#include "app/commands.h"
#include "core/error.h"
#include "core/version.h"

int main(int argc, char** argv) {
  CLI::App app("flexmbs: flexible multibody dynamics with contact", "flexmbs");
  app.set_version_flag("--version", std::string(flexmbs::Version()));
  app.require_subcommand(1);
  flexmbs::app::AddMeshCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const flexmbs::InputError& e) {
    fmt::print(stderr, "flexmbs: error: {}\n", e.what());
    return 2;
  } catch (const flexmbs::InternalError& e) {
    fmt::print(stderr, "flexmbs: internal error (please report): {}\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    fmt::print(stderr, "flexmbs: error: {}\n", e.what());
    return 1;
  }
  return 0;
}
