// `xparam export ARCHIVE --target NAME --out FILE`: one target's remesh as OBJ or PLY.
#include "cli/commands.h"

#include "cli/text_format.h"
#include "io/archive_export.h"
#include "io/archive_reader.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cctype>
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

// What the user asked for wrongly is a usage error (exit 1), found before anything is read in
// full: the output's extension, the target's name (listing those the archive holds).
void check_request(const ExportOptions& options) {
  std::string extension = std::filesystem::path(options.out).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension != ".obj" && extension != ".ply")
    usage_error("export", "--out " + options.out + ": the extension must be .obj or .ply");
  const ArchiveReader reader(options.archive);
  if (reader.find(options.target)) return;
  std::string names;
  for (const ArchiveTargetSummary& t : reader.targets()) names += (names.empty() ? "" : ", ") + t.name;
  usage_error("export", options.archive + ": no target \"" + options.target + "\"; it holds " +
                            (names.empty() ? std::string("none") : names) + " (xparam inspect lists them)");
}

}  // namespace

void add_export_command(CLI::App& app) {
  auto options = std::make_shared<ExportOptions>();
  CLI::App* command = app.add_subcommand(
      "export", "Write one target's remesh (template faces, remeshed target vertices) from an archive as OBJ, "
                "or as PLY with per-face patch, l2_stretch and angle_distortion.");
  command->add_option("archive", options->archive, "Archive (.h5)")->required()->check(CLI::ExistingFile);
  command->add_option("--target", options->target, "Name of the target (see xparam inspect)")->required();
  command->add_option("--out", options->out, "Output mesh file, .obj or .ply")->required();
  command->footer("Example: xparam export results.h5 --target woman --out woman_remesh.ply");
  command->callback([options] {
    check_request(*options);
    export_remesh(options->archive, options->target, options->out);
    std::cout << "wrote " << options->out << "\n";
  });
}

}  // namespace xparam::cli
