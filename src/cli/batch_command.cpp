// `xparam batch`: one template against a folder (or manifest) of targets, into one archive.
#include "cli/batch_progress.h"
#include "cli/command_line.h"
#include "cli/commands.h"
#include "cli/intake_options.h"
#include "cli/map_options.h"
#include "cli/stop_signals.h"
#include "cli/text_format.h"

#include "batch/batch_driver.h"
#include "batch/batch_plan.h"
#include "batch/common_anchors.h"
#include "batch/intake_totals.h"
#include "batch/summary_json.h"
#include "batch/target_discovery.h"
#include "batch/template_preparation.h"
#include "core/errors.h"
#include "io/anchor_reader.h"
#include "io/archive_commit.h"
#include "io/archive_lock.h"
#include "io/output_paths.h"

#include <CLI/CLI.hpp>
#include <tbb/info.h>

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace xparam::cli {
namespace {

struct BatchOptions {
  std::string template_mesh;
  std::string template_anchors;
  std::string curves;
  std::string measurements;  ///< --measurements: the template's measurement file
  std::string targets;
  AnchorLookup anchors;  ///< --anchors-dir, --anchors-pattern
  bool common_anchors = false;  ///< --common-anchors
  std::string out;
  int threads = tbb::info::default_concurrency();
  bool resume = false;
  bool force = false;
  bool retry_failed = false;
  std::string shard = "0/1";
  bool dry_run = false;
  std::string summary;
  bool keep_parts = false;
  bool quiet = false;  ///< no plan, no progress, no closing line (errors still)
  double checkpoint_seconds = 30.0;
  PairSettings map;  ///< --optimize, --merge, --no-stretch, --keep-corners, --second-layout, --untangle, --release-anchors
  QualityLimits limits;  ///< --max-folds, --max-e-l2, --max-area-deviation, --max-anchor-miss
  bool fail_on_suspect = false;  ///< exit 2 when a target is suspect, as when one failed
  IntakeSettings intake;  ///< --intake, --max-dropped-area, --max-hole
};

[[noreturn]] void exit_with(int code, const std::string& message) {
  std::cerr << "xparam batch: " << message << "\n";
  throw CLI::RuntimeError(code);
}

// --config FILE: CLI11's TOML/INI reader gives `key = value` items (top level or in a [batch]
// section); each fills the option of that name unless the command line gives it too. Items
// land before the command line is fully parsed, so options take the last value: a value typed
// after --config is added after it and wins; one typed before it already counts and the file
// leaves that option alone.
void apply_config(CLI::App& batch, const std::string& file) {
  for (const CLI::ConfigItem& item : CLI::ConfigTOML().from_file(file)) {
    if (item.name == "++" || item.name == "--") continue;  // section markers
    if (!item.parents.empty() && item.parents != std::vector<std::string>{"batch"})
      throw CLI::ConfigError(file + ": section [" + item.parents.front() + "] is not [batch]");
    std::string name = item.name;
    std::replace(name.begin(), name.end(), '_', '-');
    CLI::Option* option = batch.get_option_no_throw("--" + name);
    if (option == nullptr || name == "config")
      throw CLI::ConfigError(file + ": unknown option \"" + item.name + "\" for xparam batch");
    if (option->count() == 0) option->add_result(item.inputs);
  }
}

std::string plan_line(const PlannedTarget& target) {
  switch (target.action) {
    case TargetAction::Run:
      return "run   " + target.spec.name + "  " + target.spec.mesh.string() + "  " + target.spec.anchors.string() +
             (target.reason.empty() ? "" : "  (again: " + target.reason + ")");
    case TargetAction::KeepDone: return "keep  " + target.spec.name + "  (ok in the archive)";
    case TargetAction::KeepFailed:
      return "keep  " + target.spec.name + "  (failed in the archive; --retry-failed reruns it)";
  }
  return {};
}

void print_plan(const BatchPlan& plan, const BatchOptions& options, std::ostream& out) {
  out << "plan: " << plan.targets.size() << " of " << plan.discovered << " targets in " << options.targets
      << " (shard " << plan.shard.index << "/" << plan.shard.count << "): " << plan.count(TargetAction::Run)
      << " to run, " << plan.count(TargetAction::KeepDone) << " kept ok, " << plan.count(TargetAction::KeepFailed)
      << " kept failed; archive " << options.out << "\n";
  for (const PlannedTarget& target : plan.targets) out << "  " << plan_line(target) << "\n";
  if (!plan.foreign.empty())
    out << "  (" << plan.foreign.size() << " other targets already in the archive stay as they are)\n";
}

// --common-anchors: what is kept and what is left out, and why.
void print_common_anchors(const CommonAnchors& common, std::ostream& out) {
  out << "anchors: " << plural(common.names.size(), "name") << " shared by the template and every target";
  if (common.left_out.empty()) {
    out << "; none left out\n";
    return;
  }
  out << "; left out:\n";
  for (const LeftOutAnchor& name : common.left_out) {
    out << "  \"" << name.name << "\": ";
    if (name.missing_on == 0)
      out << "not on the template\n";
    else
      out << "missing on " << plural(name.missing_on, "target file") << " (e.g. " << name.example << ")\n";
  }
}

// What a run with these options would do, as the options it would record (and how targets find
// their anchors): a dry run's proof that the command line says what the user meant.
void print_effective_options(const BatchOptions& options, std::ostream& out) {
  out << "options: " << batch_options_json(options.map, options.limits, options.intake) << "\n"
      << "run: -j " << options.threads << ", shard " << options.shard
      << (options.fail_on_suspect ? ", --fail-on-suspect" : "") << "\n"
      << "anchor files: "
      << (options.anchors.is_default()
              ? std::string("beside each mesh as NAME.anchors.json, NAME.anchors.txt or NAME.pp")
              : "in " + (options.anchors.folder.empty() ? options.targets : options.anchors.folder.string()) + " as " +
                    (options.anchors.pattern.empty() ? std::string("NAME.anchors.json, NAME.anchors.txt or NAME.pp")
                                                     : options.anchors.pattern))
      << "\n";
}

int run_dry(const PreparedTemplate& prepared, const BatchPlan& plan, const BatchOptions& options) {
  print_effective_options(options, std::cout);
  print_plan(plan, options, std::cout);
  const std::vector<TargetOutcome> checked = check_batch(prepared, plan, options.threads, options.intake);
  std::size_t problems = 0;
  for (const TargetOutcome& outcome : checked) {
    std::cout << "  check " << outcome.name << ": " << (outcome.ok ? "ok" : "FAILS: " + outcome.error) << "\n";
    problems += !outcome.ok;
  }
  std::cout << "dry run: template ok (" << plural(prepared.anchors.anchors.size(), "anchor") << "), "
            << checked.size() - problems << " of " << plural(checked.size(), "target")
            << " to run pass the checks; nothing written\n";
  return problems > 0 ? kExitSomeFailed : 0;
}

// Before anything is written: every output can be written, and nothing of an earlier run is
// replaced unless --resume or --force says what to do with it.
void check_outputs(const BatchOptions& options) {
  try {
    check_archive_outputs(options.out);
    if (!options.summary.empty()) check_writable_file(options.summary, "--summary");
  } catch (const Error& e) {
    exit_with(kExitFatal, e.what());
  }
}

void refuse_to_replace(const BatchOptions& options) {
  if (options.resume || options.force) return;
  const std::vector<std::filesystem::path> existing = existing_archive_files(options.out);
  if (existing.empty()) return;
  std::string found;
  for (const std::filesystem::path& path : existing) found += (found.empty() ? "" : " and ") + path.string();
  exit_with(kExitUsage, found + " already exist" + (existing.size() == 1 ? "s" : "") +
                            " (an earlier run); nothing was changed. Add --resume to continue it (the targets it holds "
                            "are kept), or --force to start over (its results are deleted)");
}

// --resume of an archive another build of xparam started: the options may match and the maps
// still differ (a change of the method need not come with an option), and the archive's
// provenance keeps naming the build that started it. Said before anything runs.
void warn_if_started_by_another_build(const std::filesystem::path& archive) {
  const std::optional<ArchiveProvenance> recorded = recorded_provenance(archive);
  if (!recorded || written_by_this_build(*recorded)) return;
  std::cerr
      << "xparam batch: warning: " << archive.string() << " was started by xparam "
      << recorded->xparam_version << " (" << recorded->git_revision << "), this is xparam " << kVersion
      << " (" << kGitRevision
      << "): targets mapped now may differ from those it holds made with the same options, and its "
         "provenance keeps naming "
      << recorded->git_revision
      << "; for one build's maps, finish it with that build or start over with --force (or another --out)\n";
}

// The closing line on the scan intake, when it repaired a target: how many, what, and where each
// target's record is.
void print_intake_totals(const BatchSummary& summary) {
  const IntakeTotals totals = intake_totals(summary.targets);
  if (totals.repaired == 0) return;
  std::cerr << "xparam batch: the intake repaired " << totals.repaired << " of "
            << plural(summary.targets.size(), "target") << ": loose parts dropped from "
            << totals.with_parts_dropped << " (" << plural(totals.dropped_faces, "face")
            << "), holes filled in " << totals.with_holes_filled << " ("
            << plural(totals.holes_filled, "hole") << ", area " << figure(totals.filled_area) << "); "
            << totals.on_filled_vertices << " template vertices in all land on filled-in surface "
            << "(per target: --summary, or xparam inspect ARCHIVE --target NAME)\n";
}

void print_interrupted(const BatchSummary& summary) {
  std::cerr << "xparam batch: interrupted: " << plural(summary.ran, "target") << " ran and "
            << (summary.ran == 1 ? "is" : "are") << " committed, " << summary.not_run << " did not start; archive "
            << summary.archive.string() << " holds " << plural(summary.archive_targets, "target")
            << ". Run the same command with --resume to continue.\n";
}

int run_command(const BatchOptions& options) {
  Shard shard;
  std::vector<TargetSpec> discovered;
  try {
    shard = parse_shard(options.shard);
    discovered = discover_targets(options.targets, options.anchors);
  } catch (const Error& e) {
    exit_with(kExitUsage, e.what());
  }

  // One writer per archive: the lock comes before anything of the archive is looked at.
  std::optional<ArchiveLock> lock;
  if (!options.dry_run) {
    check_outputs(options);
    try {
      lock.emplace(options.out);
    } catch (const Error& e) {
      exit_with(kExitFatal, e.what());
    }
    refuse_to_replace(options);
  }

  const ProgressMode mode = progress_mode_for_stderr(options.quiet || options.dry_run);
  std::optional<BatchProgressView> view(std::in_place, mode, std::size_t{0});
  view->preparing("reading the template " + options.template_mesh);
  PreparedTemplate prepared;
  std::optional<CommonAnchors> common;  // --common-anchors
  try {
    TemplateInputs inputs{options.template_mesh, options.template_anchors, options.curves, {}, options.measurements};
    if (options.common_anchors) {
      common = common_anchor_names(read_anchors(options.template_anchors), discovered);
      inputs.only_anchors = common->names;
    }
    prepared = prepare_template(inputs);
  } catch (const std::exception& e) {
    exit_with(kExitFatal, std::string("template: ") + e.what());
  }

  try {
    const std::map<std::string, ArchiveTargetSummary> committed =
        options.resume ? committed_targets(options.out) : std::map<std::string, ArchiveTargetSummary>{};
    const BatchPlan plan =
        plan_batch(discovered, shard, committed, options.retry_failed,
                   batch_options_json(options.map, options.limits, options.intake));
    view.reset();  // the plan's count of targets to run is known now
    if (options.resume) warn_if_started_by_another_build(options.out);
    if (options.dry_run) {
      if (common) print_common_anchors(*common, std::cout);
      return run_dry(prepared, plan, options);
    }

    if (!options.quiet) {
      print_plan(plan, options, std::cerr);
      if (common) print_common_anchors(*common, std::cerr);
    }
    view.emplace(mode, plan.count(TargetAction::Run));
    const StopSignals signals;
    BatchSettings settings;
    settings.archive = options.out;
    settings.threads = options.threads;
    settings.resume = options.resume;
    settings.keep_parts = options.keep_parts;
    settings.checkpoint_seconds = options.checkpoint_seconds;
    settings.pair = options.map;
    settings.limits = options.limits;
    settings.intake = options.intake;
    settings.stop = &signals.requested();
    const BatchSummary summary =
        run_batch(prepared, plan, settings, [&](const BatchProgress& p) { view->finished(p); },
                  [&](const std::string& target, const std::string& stage) { view->stage(target, stage); });
    view.reset();
    if (!options.summary.empty()) write_summary(summary, options.summary);
    if (summary.interrupted) {
      print_interrupted(summary);
      return kExitInterrupted;
    }
    if (!options.quiet) {
      std::cerr << "xparam batch: " << plural(summary.targets.size(), "target") << ": "
              << summary.succeeded - summary.suspect << " ok, " << summary.suspect << " suspect, " << summary.failed
              << " failed (" << summary.ran << " run, " << summary.kept << " kept) in " << seconds_text(summary.seconds)
              << "; archive " << summary.archive.string() << " holds " << plural(summary.archive_targets, "target")
              << (summary.suspect > 0 ? "; xparam inspect ARCHIVE --target NAME says why a target is suspect" : "")
              << "\n";
      print_intake_totals(summary);
    }
    const bool suspect_fails = options.fail_on_suspect && summary.suspect > 0;
    return summary.failed > 0 || suspect_fails ? kExitSomeFailed : 0;
  } catch (const std::exception& e) {
    exit_with(kExitFatal, e.what());
  }
}

// The quality limits of the verdict (batch/target_verdict.h) and what a suspect target does to
// the exit status.
void add_quality_options(CLI::App& batch, BatchOptions& options) {
  QualityLimits& limits = options.limits;
  batch
      .add_option("--max-folds", limits.max_folds,
                  "A target is suspect when its remesh has more faces folded by the strict count than this")
      ->check(at_least(0))
      ->capture_default_str();
  batch
      .add_option("--max-e-l2", limits.max_e_l2,
                  "A target is suspect when the map's global L2 stretch E_L2 is above this (1: an isometry up "
                  "to scale; good maps are 1-7)")
      ->check(at_least(0, false))
      ->capture_default_str();
  batch
      .add_option("--max-area-deviation", limits.max_area_deviation,
                  "A target is suspect when its area ratio (remesh area / target area) is farther than this from 1")
      ->check(at_least(0))
      ->capture_default_str();
  batch
      .add_option("--max-anchor-miss", limits.max_anchor_miss,
                  "A target is suspect when the map misses a landmark (a released anchor, --anchor-slack) by more "
                  "than this fraction of the square root of the target's area")
      ->check(at_least(0))
      ->capture_default_str();
  batch.add_flag("--fail-on-suspect", options.fail_on_suspect,
                 "Exit with status 2 when a target is suspect, as when one failed (for scripts)");
}

}  // namespace

void add_batch_command(CLI::App& app) {
  auto options = std::make_shared<BatchOptions>();
  CLI::App* batch = app.add_subcommand(
      "batch",
      "Cross-parameterize one template against every target of a folder (NAME.obj|ply|off|stl with "
      "NAME.anchors.json|NAME.anchors.txt|NAME.pp beside it, optional NAME.gt.txt) or of a manifest "
      "(schemas/manifest.schema.json), into one HDF5 archive; each target ends ok, suspect (its map fails a "
      "quality limit below) or failed. Exit status: 0 no target failed, 2 some failed (each is recorded with its "
      "error) or, with --fail-on-suspect, some are suspect, 1 usage error (also: OUT exists and neither --resume nor --force was "
      "given), 3 fatal (bad template, unwritable output, full disk, OUT locked by another run), 130 interrupted "
      "(SIGINT/SIGTERM: the targets in flight finish and are committed; --resume continues).");
  batch->add_option("--template", options->template_mesh, "Template mesh (OBJ, PLY, OFF, STL)")
      ->required()
      ->check(CLI::ExistingFile);
  batch->add_option("--template-anchors", options->template_anchors, "Anchors of the template (.json, .pp, text)")
      ->required()
      ->check(CLI::ExistingFile);
  batch->add_option("--curves", options->curves, "Feature curves on the template (JSON) to transfer")
      ->check(CLI::ExistingFile);
  batch->add_option("--measurements", options->measurements,
                    "Measurements of the template (JSON, docs/measurements.md) to take on every target, e.g. "
                    "tests/data/human.measurements.json")
      ->check(CLI::ExistingFile);
  batch->add_option("--targets", options->targets, "Folder of targets, or a manifest JSON file")
      ->required()
      ->check(CLI::ExistingPath);
  batch->add_option("--anchors-dir", options->anchors.folder,
                    "Folder of the targets' anchor files, when they are not beside the meshes")
      ->check(CLI::ExistingDirectory);
  batch->add_option("--anchors-pattern", options->anchors.pattern,
                    "File name of a target's anchors, {stem} standing for the mesh's name without extension, e.g. "
                    "'{stem}_landmarks.json' (default: NAME.anchors.json, NAME.anchors.txt or NAME.pp)");
  batch->add_flag("--common-anchors", options->common_anchors,
                  "Map through the anchor names the template and every target share; the others are left out "
                  "everywhere and listed in the plan (default: every target must have the template's names)");
  batch->add_option("--out", options->out, "Output archive (HDF5); its parts go to OUT.parts while running")
      ->required();
  batch->add_option("-j,--threads", options->threads, "Worker threads for all targets together (default: the cores)")
      ->check(at_least(1))
      ->capture_default_str();
  CLI::Option* resume =
      batch->add_flag("--resume", options->resume,
                      "Continue OUT: run only the targets it does not hold yet, or whose mesh or anchors changed");
  batch->add_flag("--force", options->force, "Start over: replace OUT and OUT.parts of an earlier run")
      ->excludes(resume);
  batch->add_flag("--retry-failed", options->retry_failed, "With --resume, also rerun the targets that failed")
      ->needs("--resume");
  batch->add_option("--shard", options->shard, "Run shard i of N (i/N, 0-based) of the sorted target list")
      ->capture_default_str();
  batch->add_flag("--dry-run", options->dry_run, "Check every input and print the plan; write nothing");
  batch->add_option("--summary", options->summary, "Write a JSON summary (schemas/summary.schema.json)");
  add_map_options(*batch, options->map);
  add_quality_options(*batch, *options);
  add_intake_options(*batch, options->intake);
  batch->add_flag("--keep-parts", options->keep_parts, "Keep OUT.parts after the final assembly");
  batch->add_flag("-q,--quiet", options->quiet, "No plan, no progress and no closing line on stderr (errors still)");
  batch->add_option("--checkpoint-seconds", options->checkpoint_seconds,
                    "Re-assemble OUT from the committed targets at most this often while running (s)")
      ->check(at_least(0))
      ->capture_default_str();
  batch
      ->add_option_function<std::string>(
          "--config", [batch](const std::string& file) { apply_config(*batch, file); },
          "Read options from a TOML/INI file (key = value, keys named like the long options)")
      ->check(CLI::ExistingFile)
      ->trigger_on_parse()
      ->configurable(false);
  batch->footer(
      "Examples:\n  xparam batch --template tests/data/human_man.obj --template-anchors tests/data/human.anchors.json "
      "--targets tests/data/sample_targets --out results.h5\n"
      "  xparam batch --template T.ply --template-anchors T.json --targets scans --anchors-dir landmarks "
      "--anchors-pattern '{stem}_landmarks.json' --common-anchors --out scans.h5 --dry-run");
  for (CLI::Option* option : batch->get_options())
    option->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  batch->callback([options] {
    const int code = run_command(*options);
    if (code != 0) throw CLI::RuntimeError(code);
  });
}

}  // namespace xparam::cli
