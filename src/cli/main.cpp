// The xparam program: one subcommand per job; every subcommand parses and calls the library.
#include "cli/command_line.h"
#include "cli/commands.h"
#include "core/errors.h"
#include "core/version.h"

#include <CLI/CLI.hpp>

#include <iostream>

int main(int argc, char** argv) {
  CLI::App app{"xparam: cross-parameterize a template mesh against many target meshes"};
  app.set_version_flag("--version", std::string("xparam ") + xparam::kVersion + " (" + xparam::kGitRevision + ")");
  app.formatter(xparam::cli::plain_formatter());  // before the subcommands: each copies it
  app.require_subcommand(1);
  app.footer("Example: xparam batch --template T.obj --template-anchors T.anchors.json --targets DIR --out "
             "results.h5\nEach command's --help ends with an example; the README has the full reference.");
  xparam::cli::add_check_command(app);
  xparam::cli::add_batch_command(app);
  xparam::cli::add_layout_command(app);
  xparam::cli::add_pair_command(app);
  xparam::cli::add_inspect_command(app);
  xparam::cli::add_export_command(app);
  xparam::cli::add_merge_command(app);
  xparam::cli::add_warp_command(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::RuntimeError& e) {
    return e.get_exit_code();  // a command's own verdict, already explained on stderr
  } catch (const CLI::ParseError& e) {
    const int help_or_error = app.exit(e);  // prints the help, the version or the usage error
    if (help_or_error == 0) return 0;
    if (const std::string hint = xparam::cli::did_you_mean(app, argc, argv); !hint.empty()) std::cerr << hint << "\n";
    return xparam::cli::kExitUsage;
  } catch (const xparam::Error& e) {
    std::cerr << "xparam: " << e.what() << "\n";
    return xparam::cli::kExitFatal;
  } catch (const std::exception& e) {
    // Not an xparam::Error: a system failure (memory, file system) rather than a bad input.
    std::cerr << "xparam: unexpected error: " << e.what() << "\n";
    return xparam::cli::kExitFatal;
  }
  return 0;
}
