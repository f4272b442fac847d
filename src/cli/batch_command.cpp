// `xparam batch`: one template against a folder (or manifest) of targets, into one archive.
#include "cli/commands.h"
#include "cli/intake_options.h"
#include "cli/map_options.h"
#include "cli/stop_signals.h"

#include "batch/batch_driver.h"
#include "batch/batch_plan.h"
#include "batch/summary_json.h"
#include "batch/target_discovery.h"
#include "batch/template_preparation.h"
#include "core/errors.h"
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
  std::string targets;
  std::string out;
  int threads = tbb::info::default_concurrency();
  bool resume = false;
  bool force = false;
  bool retry_failed = false;
  std::string shard = "0/1";
  bool dry_run = false;
  std::string summary;
  bool keep_parts = false;
  double checkpoint_seconds = 30.0;
  PairSettings map;  ///< --optimize, --merge, --no-stretch, --keep-corners, --second-layout, --untangle, --release-anchors
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

std::string clock_text(double seconds) {
  const long total = static_cast<long>(seconds + 0.5);
  char text[32];
  std::snprintf(text, sizeof(text), "%ld:%02ld:%02ld", total / 3600, total / 60 % 60, total % 60);
  return text;
}

// " (N anchors released)" for a target mapped without some of its anchors (--release-anchors).
std::string released_text(const TargetOutcome& outcome) {
  const int released = outcome.metrics.released_anchors;
  if (released <= 0) return "";
  return " (" + std::to_string(released) + (released == 1 ? " anchor" : " anchors") +
         " released: see anchor_miss in the archive)";
}

// Progress on stderr: a live line on a terminal, one plain line per target otherwise.
class ProgressPrinter {
 public:
  ProgressPrinter() : live_(isatty(STDERR_FILENO) == 1) {}

  void operator()(const BatchProgress& p) {
    const TargetOutcome& last = *p.last;
    std::ostringstream counter;
    counter << "[" << p.done << "/" << p.total << "]";
    if (!live_) {
      std::cerr << counter.str() << " " << (last.ok ? "ok " : "FAILED ") << last.name;
      if (last.ok) std::cerr << " " << last.seconds << " s" << released_text(last);
      else std::cerr << ": " << last.error;
      std::cerr << std::endl;
      return;
    }
    const double rate = p.elapsed_seconds > 0 ? static_cast<double>(p.done) / p.elapsed_seconds : 0.0;
    const double eta = rate > 0 ? static_cast<double>(p.total - p.done) / rate : 0.0;
    // A failure gets its own permanent line above the live one.
    if (!last.ok) std::cerr << "\r\033[KFAILED " << last.name << ": " << last.error << "\n";
    if (last.ok && last.metrics.released_anchors > 0)
      std::cerr << "\r\033[K" << last.name << released_text(last) << "\n";
    char rate_text[32];
    std::snprintf(rate_text, sizeof(rate_text), "%.2f", rate);
    std::cerr << "\r\033[K" << counter.str() << " " << rate_text << " targets/s, ETA " << clock_text(eta) << ", "
              << p.failed << " failed; last: " << last.name << (p.done == p.total ? "\n" : "") << std::flush;
  }

 private:
  bool live_;
};

int run_dry(const PreparedTemplate& prepared, const BatchPlan& plan, const BatchOptions& options) {
  print_plan(plan, options, std::cout);
  const std::vector<TargetOutcome> checked = check_batch(prepared, plan, options.threads, options.intake);
  std::size_t problems = 0;
  for (const TargetOutcome& outcome : checked) {
    std::cout << "  check " << outcome.name << ": " << (outcome.ok ? "ok" : "FAILS: " + outcome.error) << "\n";
    problems += !outcome.ok;
  }
  std::cout << "dry run: template ok, " << checked.size() - problems << " of " << checked.size()
            << " targets to run pass the checks; nothing written\n";
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

void print_interrupted(const BatchSummary& summary) {
  std::cerr << "xparam batch: interrupted: " << summary.ran << " targets ran and are committed, " << summary.not_run
            << " did not start; archive " << summary.archive.string() << " holds " << summary.archive_targets
            << " targets. Run the same command with --resume to continue.\n";
}

int run_command(const BatchOptions& options) {
  Shard shard;
  std::vector<TargetSpec> discovered;
  try {
    shard = parse_shard(options.shard);
    discovered = discover_targets(options.targets);
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

  PreparedTemplate prepared;
  try {
    prepared = prepare_template({options.template_mesh, options.template_anchors, options.curves});
  } catch (const std::exception& e) {
    exit_with(kExitFatal, std::string("template: ") + e.what());
  }

  try {
    const std::map<std::string, ArchiveTargetSummary> committed =
        options.resume ? committed_targets(options.out) : std::map<std::string, ArchiveTargetSummary>{};
    const BatchPlan plan =
        plan_batch(discovered, shard, committed, options.retry_failed, batch_options_json(options.map, options.intake));
    if (options.dry_run) return run_dry(prepared, plan, options);

    print_plan(plan, options, std::cerr);
    const StopSignals signals;
    BatchSettings settings;
    settings.archive = options.out;
    settings.threads = options.threads;
    settings.resume = options.resume;
    settings.keep_parts = options.keep_parts;
    settings.checkpoint_seconds = options.checkpoint_seconds;
    settings.pair = options.map;
    settings.intake = options.intake;
    settings.stop = &signals.requested();
    ProgressPrinter printer;
    const BatchSummary summary = run_batch(prepared, plan, settings, [&](const BatchProgress& p) { printer(p); });
    if (!options.summary.empty()) write_summary(summary, options.summary);
    if (summary.interrupted) {
      print_interrupted(summary);
      return kExitInterrupted;
    }
    std::cerr << "xparam batch: " << summary.targets.size() << " targets: " << summary.succeeded << " ok, "
              << summary.failed << " failed (" << summary.ran << " run, " << summary.kept << " kept) in "
              << summary.seconds << " s; archive " << summary.archive.string() << " holds "
              << summary.archive_targets << " targets\n";
    return summary.failed > 0 ? kExitSomeFailed : 0;
  } catch (const std::exception& e) {
    exit_with(kExitFatal, e.what());
  }
}

}  // namespace

void add_batch_command(CLI::App& app) {
  auto options = std::make_shared<BatchOptions>();
  CLI::App* batch = app.add_subcommand(
      "batch",
      "Cross-parameterize one template against every target of a folder (NAME.obj|ply|off|stl with "
      "NAME.anchors.json|NAME.anchors.txt|NAME.pp beside it, optional NAME.gt.txt) or of a manifest "
      "(schemas/manifest.schema.json), into one HDF5 archive. Exit status: 0 all targets ok, 2 some failed "
      "(each is recorded with its error), 1 usage error (also: OUT exists and neither --resume nor --force was "
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
  batch->add_option("--targets", options->targets, "Folder of targets, or a manifest JSON file")
      ->required()
      ->check(CLI::ExistingPath);
  batch->add_option("--out", options->out, "Output archive (HDF5); its parts go to OUT.parts while running")
      ->required();
  batch->add_option("-j,--threads", options->threads, "Worker threads for all targets together")
      ->check(CLI::PositiveNumber)
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
  add_intake_options(*batch, options->intake);
  batch->add_flag("--keep-parts", options->keep_parts, "Keep OUT.parts after the final assembly");
  batch->add_option("--checkpoint-seconds", options->checkpoint_seconds,
                    "Re-assemble OUT from the committed targets at most this often while running (s)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  batch
      ->add_option_function<std::string>(
          "--config", [batch](const std::string& file) { apply_config(*batch, file); },
          "Read options from a TOML/INI file (key = value, keys named like the long options)")
      ->check(CLI::ExistingFile)
      ->trigger_on_parse()
      ->configurable(false);
  for (CLI::Option* option : batch->get_options())
    option->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  batch->callback([options] {
    const int code = run_command(*options);
    if (code != 0) throw CLI::RuntimeError(code);
  });
}

}  // namespace xparam::cli
