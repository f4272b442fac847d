#include "batch/summary_json.h"

#include "core/errors.h"
#include "core/version.h"

#include <cmath>
#include <fstream>

namespace xparam {
namespace {

nlohmann::ordered_json number_or_null(double value) {
  return std::isfinite(value) ? nlohmann::ordered_json(value) : nlohmann::ordered_json(nullptr);
}

nlohmann::ordered_json count_or_null(int value) {
  return value >= 0 ? nlohmann::ordered_json(value) : nlohmann::ordered_json(nullptr);
}

nlohmann::ordered_json target_json(const TargetOutcome& outcome) {
  nlohmann::ordered_json target;
  target["name"] = outcome.name;
  target["status"] = outcome.ok ? "ok" : "failed";
  target["error"] = outcome.error;
  target["ran"] = outcome.ran;
  target["seconds"] = number_or_null(outcome.seconds);
  const TargetMetrics& m = outcome.metrics;
  nlohmann::ordered_json metrics;
  metrics["e_l2"] = number_or_null(m.e_l2);
  metrics["e_ang"] = number_or_null(m.e_ang);
  metrics["stretch_max_sv"] = number_or_null(m.stretch_max_sv);
  metrics["flipped_faces"] = count_or_null(m.flipped_faces);
  metrics["area_ratio"] = number_or_null(m.area_ratio);
  metrics["gt_error"] = number_or_null(m.gt_error);
  metrics["swaps"] = count_or_null(m.swaps);
  metrics["merges"] = count_or_null(m.merges);
  metrics["released_anchors"] = count_or_null(m.released_anchors);
  target["metrics"] = metrics;
  return target;
}

}  // namespace

nlohmann::ordered_json summary_json(const BatchSummary& summary) {
  nlohmann::ordered_json json;
  json["xparam_version"] = kVersion;
  json["git_revision"] = kGitRevision;
  json["archive"] = summary.archive.string();
  json["shard"] = {{"index", summary.shard.index}, {"count", summary.shard.count}};
  json["threads"] = summary.threads;
  json["discovered"] = summary.discovered;
  json["targets_in_shard"] = summary.targets.size() + summary.not_run;
  json["ran"] = summary.ran;
  json["kept"] = summary.kept;
  json["succeeded"] = summary.succeeded;
  json["failed"] = summary.failed;
  json["archive_targets"] = summary.archive_targets;
  json["interrupted"] = summary.interrupted;
  json["not_run"] = summary.not_run;
  json["seconds"] = summary.seconds;
  json["targets_per_second"] = summary.targets_per_second();
  nlohmann::ordered_json targets = nlohmann::ordered_json::array();
  for (const TargetOutcome& outcome : summary.targets) targets.push_back(target_json(outcome));
  json["targets"] = targets;
  return json;
}

void write_summary(const BatchSummary& summary, const std::filesystem::path& path) {
  std::ofstream out(path);
  out << summary_json(summary).dump(2) << "\n";
  out.close();
  if (!out) throw InputError(path.string() + ": cannot write the summary");
}

}  // namespace xparam
