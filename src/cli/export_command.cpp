// `xparam export ARCHIVE --target NAME --out FILE`: one target's remesh as OBJ or PLY.
#include "cli/commands.h"

#include "io/archive_export.h"

#include <CLI/CLI.hpp>

#include <iostream>
#include <memory>
#include <string>

namespace xparam::cli {
namespace {

struct ExportOptions {
  std::string archive;
  std::string target;
  std::string out;
};

}  // namespace

void add_export_command(CLI::App& app) {
  auto options = std::make_shared<ExportOptions>();
  CLI::App* command = app.add_subcommand(
      "export", "Write one target's remesh (template faces, remeshed target vertices) from an archive as OBJ, "
                "or as PLY with per-face patch, l2_stretch and angle_distortion.");
  command->add_option("archive", options->archive, "Archive (.h5)")->required()->check(CLI::ExistingFile);
  command->add_option("--target", options->target, "Name of the target (see xparam inspect)")->required();
  command->add_option("--out", options->out, "Output mesh file, .obj or .ply")->required();
  command->callback([options] {
    export_remesh(options->archive, options->target, options->out);
    std::cout << "wrote " << options->out << "\n";
  });
}

}  // namespace xparam::cli
