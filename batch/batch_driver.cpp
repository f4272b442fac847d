#include "batch/batch_driver.h"

#include "batch/target_job.h"
#include "core/errors.h"
#include "io/archive_commit.h"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>

namespace xparam {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The fields a TargetRecord and an archive row (ArchiveTargetSummary) have alike.
template <typename Row>
TargetOutcome outcome_from(const Row& row) {
  TargetOutcome outcome;
  outcome.name = row.name;
  outcome.ok = row.ok;
  outcome.suspect = row.suspect;
  outcome.error = row.error;
  outcome.diagnosis = row.diagnosis;
  outcome.mesh_file = row.mesh_file;
  outcome.anchors_file = row.anchors_file;
  outcome.mesh_sha256 = row.mesh_sha256;
  outcome.anchors_sha256 = row.anchors_sha256;
  outcome.metrics = row.metrics;
  outcome.stage_seconds = row.seconds;
  outcome.measurements.assign(row.measurements.data(), row.measurements.data() + row.measurements.size());
  return outcome;
}

TargetOutcome outcome_of(const TargetRecord& record) {
  TargetOutcome outcome = outcome_from(record);
  outcome.ran = true;
  outcome.seconds = record.seconds.back();  // the "total" column
  return outcome;
}

// Indices into plan.targets of the targets to run.
std::vector<std::size_t> runnable(const BatchPlan& plan) {
  std::vector<std::size_t> indices;
  for (std::size_t i = 0; i < plan.targets.size(); ++i)
    if (plan.targets[i].action == TargetAction::Run) indices.push_back(i);
  return indices;
}

// Run `body(k)` for k in [0, n) on `threads` workers, one index per task.
template <typename Body>
void run_parallel(int threads, std::size_t n, const Body& body) {
  XP_ASSERT(threads >= 1);
  const tbb::global_control cap(tbb::global_control::max_allowed_parallelism,
                                static_cast<std::size_t>(threads));
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, n, 1),
        [&](const tbb::blocked_range<std::size_t>& range) {
          for (std::size_t k = range.begin(); k != range.end(); ++k) body(k);
        },
        tbb::simple_partitioner());
  });
}

// The archive and the run's shared state behind one lock: commits, checkpoints and progress.
class Committer {
 public:
  Committer(BatchArchive& archive, const BatchSettings& settings, std::size_t total,
            const BatchProgressCallback& progress)
      : archive_(archive), settings_(settings), progress_(progress) {
    state_.total = total;
  }

  // Whether no further target may start: a stop was asked for, or a commit failed (the disk is
  // full or failing: the run is over, and what is committed stays).
  bool stopping() const {
    if (settings_.stop != nullptr && settings_.stop->load()) interrupted_ = true;
    return interrupted_ || broken_;
  }
  bool interrupted() const {
    stopping();
    return interrupted_.load();
  }

  void commit(const TargetRecord& record, TargetOutcome& slot) {
    const std::lock_guard lock(mutex_);
    if (broken_) return;  // an earlier commit failed: its exception ends the run
    guarded([&] { archive_.commit(record); }, "target \"" + record.name + "\" was not committed");
    slot = outcome_of(record);
    if (seconds_since(last_checkpoint_) >= settings_.checkpoint_seconds) {
      guarded([&] { archive_.assemble(); }, "the archive could not be re-assembled (checkpoint)");
      last_checkpoint_ = Clock::now();
    }
    ++state_.done;
    if (!slot.ok) ++state_.failed;
    if (slot.suspect) ++state_.suspect;
    state_.elapsed_seconds = seconds_since(start_);
    state_.last = &slot;
    if (progress_) progress_(state_);
  }

 private:
  // Run a write; when it fails (a full disk, an I/O error) no further target starts, and the
  // error says what was lost and what stays.
  template <typename Write>
  void guarded(const Write& write, const std::string& lost) {
    try {
      write();
    } catch (const std::exception& e) {
      broken_ = true;
      throw ArchiveError(std::string(e.what()) + "\n" + lost + "; the targets committed before stay in " +
                         parts_directory(archive_.path()).string() +
                         ": once the cause is fixed (space freed), run the same command with --resume");
    }
  }

  BatchArchive& archive_;
  const BatchSettings& settings_;
  const BatchProgressCallback& progress_;
  std::mutex mutex_;
  mutable std::atomic<bool> interrupted_{false};
  std::atomic<bool> broken_{false};
  BatchProgress state_;
  Clock::time_point start_ = Clock::now();
  Clock::time_point last_checkpoint_ = Clock::now();
};

}  // namespace

TargetOutcome outcome_of(const ArchiveTargetSummary& row) { return outcome_from(row); }

double BatchSummary::targets_per_second() const {
  return ran > 0 && seconds > 0.0 ? static_cast<double>(ran) / seconds : 0.0;
}

std::string batch_options_json(const PairSettings& settings, const QualityLimits& limits, const IntakeSettings& intake) {
  nlohmann::ordered_json options;
  options["intake"]["mode"] = intake.mode == IntakeMode::Strict ? "strict" : "repair";
  options["intake"]["max_dropped_area"] = intake.max_dropped_area;
  options["intake"]["max_hole"] = intake.max_hole;
  options["intake"]["max_hole_relative"] = intake.max_hole_relative;
  options["intake"]["max_handle"] = intake.max_handle;
  options["intake"]["max_handle_relative"] = intake.max_handle_relative;
  options["placement"]["snap_tolerance"] = settings.placement.snap_tolerance;
  options["placement"]["warn_snap_distance"] = settings.placement.warn_snap_distance;
  options["layout"]["greedy_diagonals"] = settings.layout.greedy_diagonals;
  options["optimization"]["stretch"] = settings.optimization.stretch;
  options["optimization"]["metric"] = std::string(to_string(settings.optimization.metric));
  options["optimization"]["merge"] = settings.optimization.merge;
  options["optimization"]["contact_clearance"] = settings.optimization.stretching.contact_clearance;
  options["optimization"]["keep_corners"] = settings.optimization.stretching.keep_corners;
  options["optimization"]["swap_winding_curves"] = settings.optimization.swap_winding_curves;
  options["relax"] = settings.cross_map.relax;
  options["second_layout"] = settings.retry_keeping_corners;
  options["tip_anchors"] = settings.tip_anchors;
  options["extremity_anchors"] = settings.extremity_anchors;
  options["tip_rounds"] = settings.tip_rounds;
  options["tip_rows"] = settings.tip_rows;
  options["fitted_tip_rows"] = settings.fitted_tip_rows;
  options["map_carried_tips"] = settings.map_carried_tips;
  options["pull_carried_tips"] = settings.pull_carried_tips;
  options["whole_map_up_to"] = settings.whole_map_up_to;
  options["retry_doubtful_tips"] = settings.retry_doubtful_tips;
  options["untangle"] = settings.untangle;
  options["release_anchors"] = settings.max_released_anchors;
  options["optimize_map"] = settings.optimize_map;
  options["map_sweeps"] = settings.map_optimization.max_sweeps;
  options["map_coverage"] = settings.map_optimization.coverage_weight;
  options["anchor_slack"] = settings.anchor_slack;
  options["max_maps"] = settings.max_maps;
  options["work_vertices"] = settings.work_vertices;
  options["quality"] = limits_json(limits);
  return options.dump();
}

IntakeSettings intake_before_it_existed() {
  IntakeSettings intake;
  intake.mode = IntakeMode::Strict;
  // Handles came later still: before them, every handle was refused (--max-handle 0).
  intake.max_handle = 0.0;
  intake.max_handle_relative = 0.0;
  return intake;
}

std::string implied_options_json() {
  PairSettings before;
  before.cross_map.relax = false;
  before.retry_keeping_corners = false;
  before.tip_anchors = false;
  before.extremity_anchors = false;
  before.tip_rounds = 1;
  before.tip_rows = false;
  before.fitted_tip_rows = false;
  before.retry_doubtful_tips = false;
  before.pull_carried_tips = false;
  before.untangle = false;
  before.max_released_anchors = 0;
  before.optimize_map = false;
  before.optimization.swap_winding_curves = false;
  before.work_vertices = 0;
  return batch_options_json(before, {}, intake_before_it_existed());
}

IntakeSettings recorded_intake(const std::string& options_json) {
  IntakeSettings intake;
  const nlohmann::json options = nlohmann::json::parse(options_json, nullptr, false);
  if (options.is_discarded() || !options.is_object() || !options.contains("intake"))
    return intake_before_it_existed();
  try {
    const nlohmann::json& recorded = options.at("intake");
    intake.mode = recorded.at("mode").get<std::string>() == "strict" ? IntakeMode::Strict : IntakeMode::Repair;
    intake.max_dropped_area = recorded.at("max_dropped_area").get<double>();
    intake.max_hole = recorded.at("max_hole").get<double>();
    intake.max_hole_relative = recorded.at("max_hole_relative").get<double>();
    const IntakeSettings before = intake_before_it_existed();
    intake.max_handle = recorded.value("max_handle", before.max_handle);
    intake.max_handle_relative = recorded.value("max_handle_relative", before.max_handle_relative);
  } catch (const nlohmann::json::exception& e) {
    throw ArchiveError("the recorded options' \"intake\" is not as xparam batch writes it (" + std::string(e.what()) +
                       "): " + options_json);
  }
  return intake;
}

BatchSummary run_batch(const PreparedTemplate& prepared, const BatchPlan& plan, const BatchSettings& settings,
                       const BatchProgressCallback& progress, const TargetStageCallback& on_stage) {
  const Clock::time_point start = Clock::now();
  const ArchiveProvenance provenance =
      current_provenance(batch_options_json(settings.pair, settings.limits, settings.intake));
  BatchArchive archive =
      settings.resume
          ? BatchArchive::resume(settings.archive, prepared.record, provenance, implied_options_json(),
                                 settings.archive_settings)
          : BatchArchive::create(settings.archive, prepared.record, provenance, settings.archive_settings);

  BatchSummary summary;
  summary.archive = settings.archive;
  summary.measurement_names = prepared.record.measurement_names;
  summary.shard = plan.shard;
  summary.threads = settings.threads;
  summary.discovered = plan.discovered;
  summary.targets.resize(plan.targets.size());

  // Kept targets: their outcome is what the archive holds (resume turned it into parts).
  for (std::size_t i = 0; i < plan.targets.size(); ++i) {
    if (plan.targets[i].action == TargetAction::Run) continue;
    const std::string& name = plan.targets[i].spec.name;
    if (!archive.is_committed(name))
      throw ArchiveError(settings.archive.string() + ": target \"" + name +
                         "\" was planned as kept but the archive does not hold it");
    summary.targets[i] =
        outcome_of(ArchiveReader(target_part_path(settings.archive, name)).targets().front());
    ++summary.kept;
  }

  const std::vector<std::size_t> to_run = runnable(plan);
  Committer committer(archive, settings, to_run.size(), progress);
  run_parallel(settings.threads, to_run.size(), [&](std::size_t k) {
    if (committer.stopping()) return;
    const std::size_t i = to_run[k];
    const TargetSpec& spec = plan.targets[i].spec;
    StageCallback stage;
    if (on_stage) stage = [&](const std::string& name) { on_stage(spec.name, name); };
    const TargetRecord record = run_target(prepared, spec, settings.pair, settings.limits, settings.intake, stage);
    committer.commit(record, summary.targets[i]);
  });
  summary.interrupted = committer.interrupted();
  // Targets a stop left unstarted have no outcome: they are counted, not listed.
  const auto unstarted = std::remove_if(summary.targets.begin(), summary.targets.end(),
                                        [](const TargetOutcome& outcome) { return outcome.name.empty(); });
  summary.not_run = static_cast<std::size_t>(summary.targets.end() - unstarted);
  summary.targets.erase(unstarted, summary.targets.end());
  summary.ran = to_run.size() - summary.not_run;

  archive.finish(!settings.keep_parts);
  summary.archive_targets = archive.committed().size();
  for (const TargetOutcome& outcome : summary.targets) {
    ++(outcome.ok ? summary.succeeded : summary.failed);
    if (outcome.suspect) ++summary.suspect;
  }
  summary.seconds = seconds_since(start);
  return summary;
}

std::vector<TargetOutcome> check_batch(const PreparedTemplate& prepared, const BatchPlan& plan, int threads,
                                       const IntakeSettings& intake) {
  const std::vector<std::size_t> to_check = runnable(plan);
  std::vector<TargetOutcome> outcomes(to_check.size());
  run_parallel(threads, to_check.size(), [&](std::size_t k) {
    const TargetSpec& spec = plan.targets[to_check[k]].spec;
    TargetOutcome& outcome = outcomes[k];
    outcome.name = spec.name;
    outcome.error = check_target(prepared, spec, intake);
    outcome.ok = outcome.error.empty();
  });
  return outcomes;
}

}  // namespace xparam
