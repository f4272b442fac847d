// The xparam program: one subcommand per job; every subcommand parses and calls the library.
#include "cli/commands.h"
#include "core/errors.h"
#include "core/version.h"

#include <CLI/CLI.hpp>

#include <iostream>

int main(int argc, char** argv) {
  CLI::App app{"xparam: cross-parameterize a template mesh against many target meshes"};
  app.set_version_flag("--version", std::string("xparam ") + xparam::kVersion + " (" + xparam::kGitRevision + ")");
  app.require_subcommand(1);


  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const xparam::Error& e) {
    std::cerr << "xparam: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
