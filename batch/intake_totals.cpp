#include "batch/intake_totals.h"

#include <nlohmann/json.hpp>

namespace xparam {
namespace {

bool diagnosis_has_intake(const std::string& diagnosis) {
  if (diagnosis.empty()) return false;
  const nlohmann::json parsed = nlohmann::json::parse(diagnosis, nullptr, false);
  return !parsed.is_discarded() && parsed.contains("intake");
}

}  // namespace

IntakeTotals intake_totals(const std::vector<TargetOutcome>& targets) {
  IntakeTotals totals;
  for (const TargetOutcome& target : targets) {
    if (!target.ok) continue;
    const TargetMetrics& m = target.metrics;
    const bool dropped = m.dropped_faces > 0;
    const bool filled = m.holes_filled > 0;
    if (!dropped && !filled && !diagnosis_has_intake(target.diagnosis)) continue;
    ++totals.repaired;
    if (dropped) {
      ++totals.with_parts_dropped;
      totals.dropped_faces += static_cast<std::size_t>(m.dropped_faces);
      totals.dropped_area += m.dropped_area;
    }
    if (filled) {
      ++totals.with_holes_filled;
      totals.holes_filled += static_cast<std::size_t>(m.holes_filled);
      totals.filled_area += m.filled_area;
      totals.on_filled_vertices += static_cast<std::size_t>(m.on_filled_vertices);
    }
  }
  return totals;
}

}  // namespace xparam
