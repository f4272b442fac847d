// `xparam export ARCHIVE --target NAME --out FILE`: one target's remesh as OBJ or PLY;
// `xparam export ARCHIVE --measurements --out FILE.csv`: every target's measurements.
#include "cli/commands.h"

#include "cli/text_format.h"
#include "cli/unknown_target.h"
#include "io/archive_export.h"
#include "io/archive_reader.h"
#include "io/measurement_table.h"

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
  bool measurements = false;  ///< --measurements: the measurement table instead of a remesh
  bool curves = false;        ///< --curves: the target's transferred curves instead of its remesh
  std::string out;
};

std::string lowercase_extension(const std::string& file) {
  std::string extension = std::filesystem::path(file).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

// What the user asked for wrongly is a usage error (exit 1), found before anything is read in
// full: the output's extension, the target's name (listing those the archive holds).
void check_request(const ExportOptions& options) {
  if (options.measurements == !options.target.empty())
    usage_error("export", "give either --target NAME (a remesh, or its curves with --curves) or --measurements "
                          "(the measurement table)");
  if (options.measurements && options.curves)
    usage_error("export", "--curves exports one target's curves: give it with --target NAME, not --measurements");
  if (options.measurements) {
    if (std::filesystem::path(options.out).extension() != ".csv")
      usage_error("export", "--out " + options.out + ": the measurement table is written as .csv");
    if (ArchiveReader(options.archive).n_measurements() == 0)
      usage_error("export", options.archive + ": the archive holds no measurements; run the batch with "
                                              "--measurements FILE to take them");
    return;
  }
  const std::string extension = lowercase_extension(options.out);
  if (options.curves && extension != ".obj")
    usage_error("export", "--out " + options.out + ": curves are written as OBJ polylines, the extension must be .obj");
  if (extension != ".obj" && extension != ".ply")
    usage_error("export", "--out " + options.out + ": the extension must be .obj or .ply");
  const ArchiveReader reader(options.archive);
  if (!reader.find(options.target)) refuse_unknown_target("export", reader, options.target, true);
}

}  // namespace

void add_export_command(CLI::App& app) {
  auto options = std::make_shared<ExportOptions>();
  CLI::App* command = app.add_subcommand(
      "export", "Write one target's remesh (template faces, remeshed target vertices) from an archive as OBJ, "
                "or as PLY with per-face patch, l2_stretch and angle_distortion; or, with --measurements, every "
                "target's measurements as CSV.");
  command->add_option("archive", options->archive, "Archive (.h5)")->required()->check(CLI::ExistingFile);
  command->add_option("--target", options->target, "Name of the target (see xparam inspect)");
  command->add_flag("--measurements", options->measurements,
                    "Write the measurement table (one row for the template, one per target) instead");
  command->add_flag("--curves", options->curves,
                    "With --target: write the target's transferred feature curves as OBJ polylines instead");
  command->add_option("--out", options->out, "Output file: .obj or .ply (a remesh), .csv (--measurements)")->required();
  command->footer("Examples: xparam export results.h5 --target woman --out woman_remesh.ply    "
                  "xparam export results.h5 --target woman --curves --out woman_curves.obj    "
                  "xparam export results.h5 --measurements --out measurements.csv");
  command->callback([options] {
    check_request(*options);
    if (options->measurements)
      export_measurements(options->archive, options->out);
    else if (options->curves)
      export_curves(options->archive, options->target, options->out);
    else
      export_remesh(options->archive, options->target, options->out);
    std::cout << "wrote " << options->out << "\n";
    const bool remesh_ply =
        !options->measurements && !options->curves && lowercase_extension(options->out) == ".ply";
    if (remesh_ply && !ArchiveReader(options->archive).records_distance_to_scan())
      std::cerr << "note: " << options->archive
                << " was written before archives recorded each image's distance to "
                << "the scan (schema 4): distance_to_scan is NaN where on_filled is 1; map the target again "
                   "for it\n";
  });
}

}  // namespace xparam::cli
