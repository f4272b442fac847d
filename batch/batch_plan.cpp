#include "batch/batch_plan.h"

#include "io/archive_commit.h"

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

BatchPlan plan_batch(const std::vector<TargetSpec>& discovered, const Shard& shard,
                     const std::map<std::string, ArchiveTargetSummary>& committed, bool retry_failed) {
  BatchPlan plan;
  plan.discovered = discovered.size();
  plan.shard = shard;
  std::set<std::string> planned;
  for (TargetSpec& spec : select_shard(discovered, shard)) {
    TargetAction action = TargetAction::Run;
    const auto it = committed.find(spec.name);
    if (it != committed.end()) {
      if (it->second.ok) action = TargetAction::KeepDone;
      else if (!retry_failed) action = TargetAction::KeepFailed;
    }
    planned.insert(spec.name);
    plan.targets.push_back({std::move(spec), action});
  }
  for (const auto& [name, summary] : committed)
    if (!planned.count(name)) plan.foreign.push_back(name);
  return plan;
}

}  // namespace xparam
