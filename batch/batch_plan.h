#pragma once
/// \file
/// What a batch run will do, decided before anything runs: the shard's targets, and for each
/// whether it runs or is kept from an earlier run of the same archive (--resume).

#include "batch/target_discovery.h"
#include "io/archive_reader.h"

#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace xparam {

/// What happens to one target.
enum class TargetAction {
  Run,         ///< not committed yet (or failed and retried): the pipeline runs
  KeepDone,    ///< committed as ok by an earlier run: kept as it is
  KeepFailed,  ///< committed as failed by an earlier run and not retried: kept as it is
};

/// One target of the plan.
struct PlannedTarget {
  TargetSpec spec;
  TargetAction action = TargetAction::Run;
  /// Why a target the archive holds runs again (its mesh or anchors changed, it ran with other
  /// options, it failed and is retried); empty otherwise.
  std::string reason;
};

/// The plan of one run over one shard.
struct BatchPlan {
  std::size_t discovered = 0;          ///< targets in the whole source, before sharding
  Shard shard;                         ///< which shard this run covers
  std::vector<PlannedTarget> targets;  ///< the shard's targets, sorted by name
  /// Targets already in the archive that are not among `targets` (another shard's, or removed
  /// from the source since): they stay in the archive untouched.
  std::vector<std::string> foreign;

  /// How many targets have `action`.
  std::size_t count(TargetAction action) const;
};

/// The targets an archive already holds, read without changing anything: the rows of
/// ARCHIVE.h5 and the committed parts beside it (a part wins over a row of the same name:
/// it is newer). Empty when neither exists.
/// \throw ArchiveError when an existing archive or part cannot be read
std::map<std::string, ArchiveTargetSummary> committed_targets(const std::filesystem::path& archive);

/// Plan a run: take shard `shard` of `discovered` (sorted by name), and mark targets found in
/// `committed` (from committed_targets; empty for a fresh run) as kept, except
///  - failed ones when `retry_failed`;
///  - those whose mesh or anchor file's SHA-256 now differs from the one recorded (the file
///    was edited since: its result is stale);
///  - those recorded with other options than `options_json` (batch_options_json), when it is
///    not empty and the record has options (a part records its own): kept rows are only ever
///    rows of this run's options (an option a record predates counts as implied_options_json's).
/// The reason of every rerun is in PlannedTarget::reason.
BatchPlan plan_batch(const std::vector<TargetSpec>& discovered, const Shard& shard,
                     const std::map<std::string, ArchiveTargetSummary>& committed, bool retry_failed,
                     const std::string& options_json = {});

}  // namespace xparam
