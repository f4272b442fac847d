#pragma once
/// \file
/// A batch run: one prepared template against the targets of a plan, in parallel, every
/// finished target committed to the archive on its own (io/archive_commit.h).
///
/// Parallelism: one tbb::task_arena of `threads` workers runs the targets (parallel_for,
/// one target per task) and the parallel loops inside each target; a tbb::global_control
/// caps TBB at the same count. Targets are independent and each is deterministic, and the
/// archive is assembled in name order, so its datasets do not depend on `threads` or on the
/// order in which targets finish (only /targets/timings does). Commits and checkpoints are
/// serialized by one lock: a single writer for the archive.

#include "batch/batch_plan.h"
#include "batch/target_verdict.h"
#include "batch/template_preparation.h"
#include "io/archive_reader.h"
#include "intake/scan_intake.h"
#include "io/archive_records.h"
#include "io/archive_writer.h"
#include "map/pair_mapping.h"

#include <atomic>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace xparam {

/// Options of run_batch.
struct BatchSettings {
  std::filesystem::path archive;  ///< the output ARCHIVE.h5 (its parts go to ARCHIVE.h5.parts)
  int threads = 1;                ///< worker threads for all targets together, >= 1
  /// Continue the archive (keep what it holds) instead of replacing it. Must match how the
  /// plan was made (committed_targets for a resumed run).
  bool resume = false;
  /// Re-assemble ARCHIVE.h5 from the committed parts when this many seconds passed since the
  /// last assembly (checked after each commit); a run killed later loses nothing committed,
  /// and ARCHIVE.h5 is at most this stale. Seconds.
  double checkpoint_seconds = 30.0;
  /// Keep ARCHIVE.h5.parts after the final assembly (resume works either way).
  bool keep_parts = false;
  PairSettings pair;                       ///< the per-target pipeline's options
  QualityLimits limits;                    ///< past which a finished map is `suspect`
  IntakeSettings intake;                   ///< what the scan intake may do to each target
  ArchiveWriteSettings archive_settings;   ///< compression, XDMF sidecar
  /// When set and it becomes true (a signal handler sets it), no further target starts: the
  /// targets in flight finish and are committed, the archive is assembled, and the summary
  /// says `interrupted`. Not owned.
  const std::atomic<bool>* stop = nullptr;
};

/// What became of one target of the plan.
struct TargetOutcome {
  std::string name;
  bool ok = false;         ///< the pipeline finished (the verdict is ok or suspect)
  bool suspect = false;    ///< ok, but a quality limit failed (see diagnosis)
  std::string error;       ///< why it failed; empty when ok
  std::string diagnosis;   ///< the diagnosis JSON (batch/target_verdict.h); empty when failed
  bool ran = false;        ///< false: kept from an earlier run of the archive (resume)
  std::string mesh_file;       ///< its mesh file (as given)
  std::string anchors_file;    ///< its anchor file
  std::string mesh_sha256;     ///< SHA-256 of the mesh file, empty when unreadable
  std::string anchors_sha256;  ///< SHA-256 of the anchor file, empty when unreadable
  TargetMetrics metrics;   ///< the metrics row
  double seconds = TargetMetrics::kNaN;  ///< wall-clock seconds of its job (total column); NaN when not run now
  StageSeconds stage_seconds = TargetRecord::filled_seconds();  ///< the timings row (NaN where a stage did not run)
  /// The measurements row (#M, the template's measurement order; NaN when not available);
  /// empty for a failed target of a run, which never measured
  std::vector<double> measurements;
};

/// The outcome an archive row records (`ran` false; seconds NaN, its stage seconds kept).
TargetOutcome outcome_of(const ArchiveTargetSummary& row);

/// Progress after each finished target (called under the driver's lock, so calls never overlap).
struct BatchProgress {
  std::size_t done = 0;        ///< targets finished in this run so far
  std::size_t total = 0;       ///< targets this run executes (the plan's Run actions)
  std::size_t failed = 0;      ///< of `done`, how many failed
  std::size_t suspect = 0;     ///< of `done`, how many are suspect
  double elapsed_seconds = 0;  ///< since the first target started
  const TargetOutcome* last = nullptr;  ///< the target that just finished
};

/// Receives progress; must not throw.
using BatchProgressCallback = std::function<void(const BatchProgress&)>;

/// Hears each stage of a running target as it starts (`target` the target's name; the first
/// stage is "load"). Called from the worker threads, so calls may overlap; must not throw.
using TargetStageCallback = std::function<void(const std::string& target, const std::string& stage)>;

/// The result of a run.
struct BatchSummary {
  std::filesystem::path archive;      ///< the archive written
  Shard shard;                        ///< the shard covered
  int threads = 1;                    ///< worker threads used
  std::size_t discovered = 0;         ///< targets in the whole source
  std::size_t ran = 0;                ///< targets executed by this run
  std::size_t kept = 0;               ///< targets kept from an earlier run
  std::size_t succeeded = 0;          ///< of the shard's targets (run or kept), how many are ok (suspect included)
  std::size_t suspect = 0;            ///< of `succeeded`, how many are suspect
  std::size_t failed = 0;             ///< of the shard's targets (run or kept), how many failed
  std::size_t archive_targets = 0;    ///< rows of the final archive (other shards' kept rows included)
  bool interrupted = false;           ///< settings.stop was raised during the run
  std::size_t not_run = 0;            ///< targets of the plan left unstarted by the interruption
  double seconds = 0.0;               ///< wall-clock seconds of the run
  std::vector<std::string> measurement_names;  ///< the template's measurements, naming TargetOutcome::measurements
  /// The shard's targets that ran or were kept, by name (those left unstarted by an
  /// interruption are not among them: see not_run).
  std::vector<TargetOutcome> targets;

  /// Targets per second over the targets executed (0 when none ran).
  double targets_per_second() const;
};

/// The method options recorded in the archive's provenance (a resumed run must use the same):
/// the PairSettings fields, the quality limits (key "quality") and the scan intake's settings as a
/// JSON object. Thread count and sharding are not in it.
std::string batch_options_json(const PairSettings& settings, const QualityLimits& limits = {},
                               const IntakeSettings& intake = {});

/// What an archive's options imply for an option they do not record (written before the option
/// existed): the behaviour then. A stage that came with its own switch, on by default, did not
/// run before it (the relaxation, the second layout, helper anchors behind and at tips, the
/// untangling, anchor releases, the map optimization, the working copy: off, 0 releases, no
/// copy), and before the intake every target was taken as it was (strict); every other option
/// had its default. A resumed run compares against it (io/options_difference.h).
std::string implied_options_json();

/// The intake settings of a run from before the intake existed: strict, the other limits at their
/// defaults (recorded_intake of options without "intake").
IntakeSettings intake_before_it_existed();

/// The scan intake's settings back from batch_options_json's object (a target's recorded
/// options); IntakeMode::Strict when it has no "intake" (archives from before the intake loaded
/// every target as it was). \throw ArchiveError when "intake" is there but not as written
IntakeSettings recorded_intake(const std::string& options_json);

/// Run `plan` against `prepared`: create (or, with settings.resume, continue) the archive,
/// run every target whose action is Run, commit each as it finishes, checkpoint, and assemble
/// the final archive. Once settings.stop is raised, no further target starts (see there).
/// \throw ArchiveError (or std::filesystem::filesystem_error) when the archive cannot be
///   written (a full disk, an I/O error) or a resumed archive was started with another template
///   or options: fatal, no further target starts, the targets committed before stay for a later
///   --resume and the failing one leaves nothing. Target failures never throw: they are outcomes.
BatchSummary run_batch(const PreparedTemplate& prepared, const BatchPlan& plan, const BatchSettings& settings,
                       const BatchProgressCallback& progress = {}, const TargetStageCallback& on_stage = {});

/// What --dry-run does: check_target (batch/target_job.h) on every target the plan would run,
/// in parallel on `threads` workers, without writing anything. Outcomes by name; `ran` false.
std::vector<TargetOutcome> check_batch(const PreparedTemplate& prepared, const BatchPlan& plan, int threads,
                                       const IntakeSettings& intake = {});

}  // namespace xparam
