#include "batch/summary_json.h"

#include "batch/intake_totals.h"
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

// Entry `key` of the diagnosis JSON, or `absent` (a failed target has no diagnosis).
nlohmann::ordered_json diagnosis_entry(const TargetOutcome& outcome, const char* key,
                                       const nlohmann::ordered_json& absent) {
  if (outcome.diagnosis.empty()) return absent;
  const nlohmann::ordered_json diagnosis = nlohmann::ordered_json::parse(outcome.diagnosis, nullptr, false);
  if (diagnosis.is_discarded() || !diagnosis.contains(key)) return absent;
  return diagnosis[key];
}

nlohmann::ordered_json intake_totals_json(const std::vector<TargetOutcome>& targets) {
  const IntakeTotals totals = intake_totals(targets);
  nlohmann::ordered_json json;
  json["repaired"] = totals.repaired;
  json["with_parts_dropped"] = totals.with_parts_dropped;
  json["with_holes_filled"] = totals.with_holes_filled;
  json["dropped_faces"] = totals.dropped_faces;
  json["dropped_area"] = totals.dropped_area;
  json["holes_filled"] = totals.holes_filled;
  json["filled_area"] = totals.filled_area;
  json["on_filled_vertices"] = totals.on_filled_vertices;
  return json;
}

}  // namespace

nlohmann::ordered_json target_json(const TargetOutcome& outcome, bool with_ran,
                                   const std::vector<std::string>& measurement_names) {
  nlohmann::ordered_json target;
  target["name"] = outcome.name;
  target["status"] = !outcome.ok ? "failed" : outcome.suspect ? "suspect" : "ok";
  target["error"] = outcome.error;
  target["reasons"] = diagnosis_entry(outcome, "reasons", nlohmann::ordered_json::array());
  if (with_ran) target["ran"] = outcome.ran;
  target["mesh_file"] = outcome.mesh_file;
  target["anchors_file"] = outcome.anchors_file;
  target["mesh_sha256"] = outcome.mesh_sha256;
  target["anchors_sha256"] = outcome.anchors_sha256;
  // Column names of /targets/metrics (io/archive_layout.cpp).
  const TargetMetrics& m = outcome.metrics;
  nlohmann::ordered_json metrics;
  metrics["E_L2"] = number_or_null(m.e_l2);
  metrics["E_ang"] = number_or_null(m.e_ang);
  metrics["stretch_max_sv"] = number_or_null(m.stretch_max_sv);
  metrics["flipped_faces"] = count_or_null(m.flipped_faces);
  metrics["strictly_folded_faces"] = count_or_null(m.strictly_folded_faces);
  metrics["area_ratio"] = number_or_null(m.area_ratio);
  metrics["gt_error"] = number_or_null(m.gt_error);
  metrics["swaps"] = count_or_null(m.swaps);
  metrics["merges"] = count_or_null(m.merges);
  metrics["released_anchors"] = count_or_null(m.released_anchors);
  metrics["dropped_faces"] = count_or_null(m.dropped_faces);
  metrics["dropped_area"] = number_or_null(m.dropped_area);
  metrics["holes_filled"] = count_or_null(m.holes_filled);
  metrics["filled_area"] = number_or_null(m.filled_area);
  metrics["on_filled_vertices"] = count_or_null(m.on_filled_vertices);
  metrics["max_distance_to_scan"] = number_or_null(m.max_distance_to_scan);
  metrics["file_faces"] = count_or_null(m.file_faces);
  target["metrics"] = metrics;
  nlohmann::ordered_json seconds;
  for (std::size_t s = 0; s < kTimingStages.size(); ++s) seconds[kTimingStages[s]] = number_or_null(outcome.stage_seconds[s]);
  target["seconds"] = seconds;
  if (!measurement_names.empty()) {
    // A failed target of this run was never measured: every value is null, as in the archive.
    nlohmann::ordered_json measurements;
    for (std::size_t i = 0; i < measurement_names.size(); ++i)
      measurements[measurement_names[i]] =
          number_or_null(i < outcome.measurements.size() ? outcome.measurements[i] : TargetMetrics::kNaN);
    target["measurements"] = measurements;
  }
  // What the intake repaired (metrics.json's `intake`), only for a target it repaired.
  if (const nlohmann::ordered_json intake = diagnosis_entry(outcome, "intake", nullptr); !intake.is_null())
    target["intake"] = intake;
  return target;
}

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
  json["suspect"] = summary.suspect;
  json["failed"] = summary.failed;
  json["archive_targets"] = summary.archive_targets;
  json["interrupted"] = summary.interrupted;
  json["not_run"] = summary.not_run;
  json["seconds"] = summary.seconds;
  json["targets_per_second"] = summary.targets_per_second();
  json["intake"] = intake_totals_json(summary.targets);
  nlohmann::ordered_json targets = nlohmann::ordered_json::array();
  for (const TargetOutcome& outcome : summary.targets)
    targets.push_back(target_json(outcome, true, summary.measurement_names));
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
