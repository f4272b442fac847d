// `xparam pair`: cross-parameterize one template against one target and write the results.
#include "batch/file_order.h"
#include "cli/commands.h"
#include "core/errors.h"
#include "cli/intake_options.h"
#include "cli/map_options.h"
#include "cli/pair_outputs.h"
#include "cli/text_format.h"
#include "io/anchor_reader.h"
#include "io/curve_reader.h"
#include "intake/scan_loader.h"
#include "io/mesh_loader.h"
#include "map/pair_mapping.h"

#include <cmath>
#include <iostream>
#include <memory>

namespace xparam::cli {
namespace {

struct PairOptions {
  std::string source;
  std::string source_anchors;
  std::string target;
  std::string target_anchors;
  std::string curves;
  std::string out;
  bool quiet = false;
  PairSettings map;  ///< --optimize, --merge, --no-stretch, --untangle
  IntakeSettings intake;  ///< --intake, --max-dropped-area, --max-hole (the target only)
};

// "4/11/345": whole degrees, slash-separated.
std::string degree_list(const std::vector<double>& degrees) {
  std::string list;
  for (double d : degrees) list += (list.empty() ? "" : "/") + std::to_string(std::lround(d));
  return list;
}

// Why folds gather at an anchor whose corners disagree (map/corner_report.h).
void print_mismatch(const CornerMismatch& corners) {
  std::cout << "corners at \"" << corners.name << "\" disagree: " << degree_list(corners.template_degrees)
            << " degrees on the template, " << degree_list(corners.target_degrees)
            << " on the target (a different patch wraps round it on each mesh); moving or releasing "
               "that landmark may help\n";
}

void run_pair(const PairOptions& options) {
  auto progress = [&](const std::string& stage) {
    if (!options.quiet) std::cerr << "xparam pair: " << stage << "\n";
  };
  progress("load");
  const LoadedMesh source = load_mesh(options.source);
  const AnchorSet target_file_anchors = read_anchors(options.target_anchors);
  const LoadedMesh target = load_scan(options.target, target_file_anchors, options.intake);
  for (const LoadedMesh* mesh : {&source, &target})
    if (const std::string repairs = describe_repairs(mesh->report); !repairs.empty())
      progress(mesh->path.string() + ": repaired: " + repairs);
  for (const std::string& step : target.intake.describe()) progress(target.path.string() + ": intake: " + step);
  // The layout needs equal genus; a target with handles is refused here, naming it.
  if (target.report.genus != source.report.genus)
    throw InputError(options.target + ": genus " +
                     (target.report.genus ? std::to_string(*target.report.genus) : std::string("undefined")) +
                     ", the template (" + options.source + ") genus " +
                     (source.report.genus ? std::to_string(*source.report.genus) : std::string("undefined")) +
                     ": close the handle (a tunnel where two surfaces touch) in a mesh editor");
  // Face + barycentric inputs are written against the files' corner order (and numbering).
  const AnchorSet source_anchors = anchors_in_mesh_order(read_anchors(options.source_anchors), source.file_order);
  const AnchorSet target_anchors = anchors_in_mesh_order(target_file_anchors, target.file_order);
  std::vector<FeatureCurve> curves;
  if (!options.curves.empty())
    curves = validate_curves(curves_in_mesh_order(read_curves(options.curves), source.file_order), source.mesh);

  const PairSettings& settings = options.map;
  const PairMapping mapping = map_pair(source.mesh, source_anchors, target.mesh, target_anchors, curves, settings, progress);
  progress("outputs");
  write_pair_outputs(options.out, source, target, mapping);
  for (const PlacedAnchors& placed : mapping.anchors) {
    for (const std::string& warning : placed.warnings) std::cerr << "xparam pair: warning: " << warning << "\n";
  }
  std::cout << "swaps " << mapping.optimization.swaps << "  merges " << mapping.optimization.merges << "  E_L2 "
            << figure(mapping.distortion.all.e_l2) << "  E_ang " << figure(mapping.distortion.all.e_ang)
            << "  flipped faces " << mapping.quality.flipped_faces.size();
  if (!mapping.folds_by_anchor.empty()) {
    const AnchorFolds& most = mapping.folds_by_anchor.front();
    std::cout << " (" << most.folded_faces << " nearest \"" << most.name << "\")";
  }
  std::cout << "  area ratio " << figure(mapping.quality.area_ratio) << "  (" << seconds_text(mapping.seconds.total)
            << ")\n";
  for (const AnchorFolds& folds : mapping.folds_by_anchor) {
    for (const CornerMismatch& corners : mapping.mismatched_corners) {
      if (corners.anchor == folds.anchor) print_mismatch(corners);
    }
  }
  if (!mapping.tip_anchors.empty()) {
    std::cout << "mapped through helper anchors behind";
    for (const TipAnchor& helper : mapping.tip_anchors) std::cout << " \"" << helper.tip << "\"";
    std::cout << " (the corners there disagreed; see tip_anchors in metrics.json)\n";
  }
  for (const ReleasedAnchor& anchor : mapping.released_anchors)
    std::cout << "released anchor \"" << anchor.name << "\" (" << anchor.folded_faces
              << " folded faces near it); the map lands " << figure(anchor.miss_distance) << " from its landmark\n";
  std::cout << "results in " << options.out << "\n";
}

}  // namespace

void add_pair_command(CLI::App& app) {
  auto options = std::make_shared<PairOptions>();
  CLI::App* command = app.add_subcommand("pair", "Cross-parameterize one template mesh onto one target mesh");
  command->add_option("--source,-s", options->source, "Template mesh (OBJ, PLY, OFF, STL)")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--source-anchors", options->source_anchors, "Template anchors (.json, .pp, .txt)")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--target,-t", options->target, "Target mesh")->required()->check(CLI::ExistingFile);
  command->add_option("--target-anchors", options->target_anchors, "Target anchors (same names)")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--curves", options->curves, "Feature curves on the template (.json) to carry over")
      ->check(CLI::ExistingFile);
  command->add_option("--out,-o", options->out, "Output directory")->required();
  command->add_flag("--quiet,-q", options->quiet, "No progress on stderr");
  add_map_options(*command, options->map);
  add_intake_options(*command, options->intake);
  command->footer(
      "Example: xparam pair -s tests/data/human_man.obj --source-anchors tests/data/human.anchors.json "
      "-t tests/data/sample_targets/woman.obj --target-anchors tests/data/sample_targets/woman.anchors.json "
      "--curves tests/data/human_man.curves.json -o pair_out");
  command->callback([options] {
    try {
      run_pair(*options);
    } catch (const InputError& e) {
      // A refused input is the job's verdict on the inputs (exit 2), not a failure of the program.
      std::cerr << "xparam: " << e.what() << "\n";
      throw CLI::RuntimeError(kExitSomeFailed);
    }
  });
}

}  // namespace xparam::cli
