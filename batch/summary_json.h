#pragma once
/// \file
/// The JSON a person's scripts read: the `--summary` file of a batch run
/// (schemas/summary.schema.json) and one object per target, the same in the summary and in
/// `xparam inspect --json` (schemas/target.schema.json): its keys are the archive's own
/// column names (schemas/archive.md), so a script reads E_L2 under one name everywhere.

#include "batch/batch_driver.h"

#include <nlohmann/json.hpp>

#include <filesystem>

namespace xparam {

/// One target as JSON (schemas/target.schema.json): name, status (ok, suspect, failed), error,
/// reasons (why suspect), files and their SHA-256, metrics by archive column name, seconds by
/// stage, measurements by name (`measurement_names`, the template's; only when it has
/// some), and `intake` (its diagnosis's: what the scan intake repaired; only for a target it
/// repaired). Numbers that are NaN (not available) and counts of -1 become null. `ran` is added
/// only when `with_ran` (the summary: whether this run executed it).
nlohmann::ordered_json target_json(const TargetOutcome& outcome, bool with_ran,
                                   const std::vector<std::string>& measurement_names = {});

/// The summary as JSON (schemas/summary.schema.json), with the intake's totals over its targets
/// (batch/intake_totals.h).
nlohmann::ordered_json summary_json(const BatchSummary& summary);

/// Write summary_json(summary) to `path` (pretty-printed).
/// \throw InputError naming the file when it cannot be written
void write_summary(const BatchSummary& summary, const std::filesystem::path& path);

}  // namespace xparam
