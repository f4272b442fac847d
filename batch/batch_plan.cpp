#include "batch/batch_plan.h"

#include "batch/batch_driver.h"
#include "io/archive_commit.h"
#include "io/options_difference.h"
#include "io/sha256.h"

#include <algorithm>
#include <set>

namespace xparam {

std::size_t BatchPlan::count(TargetAction action) const {
  return static_cast<std::size_t>(std::count_if(targets.begin(), targets.end(),
                                                [&](const PlannedTarget& t) { return t.action == action; }));
}

std::map<std::string, ArchiveTargetSummary> committed_targets(const std::filesystem::path& archive) {
  std::map<std::string, ArchiveTargetSummary> committed;
  if (std::filesystem::is_regular_file(archive)) {
    const ArchiveReader reader(archive);
    for (const ArchiveTargetSummary& target : reader.targets()) committed[target.name] = target;
  }
  // Every target part lies in one folder (io/archive_commit.h) as "<encoded name>.h5"; "*.tmp"
  // files there are writes that never finished.
  const std::filesystem::path parts = target_part_path(archive, "any").parent_path();
  if (std::filesystem::is_directory(parts)) {
    std::set<std::filesystem::path> files;  // sorted: the reading order does not depend on the file system
    for (const auto& entry : std::filesystem::directory_iterator(parts))
      if (entry.is_regular_file() && entry.path().extension() == ".h5") files.insert(entry.path());
    for (const std::filesystem::path& file : files) {
      const ArchiveReader part(file);
      for (const ArchiveTargetSummary& target : part.targets()) committed[target.name] = target;
    }
  }
  return committed;
}

namespace {

// Why the committed result of `spec` cannot be kept; empty when it can.
std::string stale_reason(const TargetSpec& spec, const ArchiveTargetSummary& recorded, const std::string& options_json) {
  if (sha256_file_hex_or_empty(spec.mesh) != recorded.mesh_sha256) return "its mesh " + spec.mesh.string() + " changed since it ran";
  if (sha256_file_hex_or_empty(spec.anchors) != recorded.anchors_sha256)
    return "its anchors " + spec.anchors.string() + " changed since they were used";
  if (options_json.empty() || recorded.options_json.empty()) return {};
  const std::string difference =
      options_difference(recorded.options_json, options_json, implied_options_json());
  if (!difference.empty()) return "it ran with other options: " + difference;
  return {};
}

}  // namespace

BatchPlan plan_batch(const std::vector<TargetSpec>& discovered, const Shard& shard,
                     const std::map<std::string, ArchiveTargetSummary>& committed, bool retry_failed,
                     const std::string& options_json) {
  BatchPlan plan;
  plan.discovered = discovered.size();
  plan.shard = shard;
  std::set<std::string> planned;
  for (TargetSpec& spec : select_shard(discovered, shard)) {
    PlannedTarget target{spec, TargetAction::Run, {}};
    const auto it = committed.find(spec.name);
    if (it != committed.end()) {
      target.reason = stale_reason(spec, it->second, options_json);
      if (!target.reason.empty()) target.action = TargetAction::Run;
      else if (it->second.ok) target.action = TargetAction::KeepDone;
      else if (!retry_failed) target.action = TargetAction::KeepFailed;
      else target.reason = "it failed and --retry-failed reruns it";
    }
    planned.insert(spec.name);
    plan.targets.push_back(std::move(target));
  }
  for (const auto& [name, summary] : committed)
    if (!planned.count(name)) plan.foreign.push_back(name);
  return plan;
}

}  // namespace xparam
