#pragma once
/// \file
/// The `--summary` file of a batch run (schemas/summary.schema.json): counts, throughput and
/// one entry per target of the shard, for scripts that decide what to do next.

#include "batch/batch_driver.h"

#include <nlohmann/json.hpp>

#include <filesystem>

namespace xparam {

/// The summary as JSON (schemas/summary.schema.json). Metrics that are NaN (not available)
/// become null.
nlohmann::ordered_json summary_json(const BatchSummary& summary);

/// Write summary_json(summary) to `path` (pretty-printed).
/// \throw InputError naming the file when it cannot be written
void write_summary(const BatchSummary& summary, const std::filesystem::path& path);

}  // namespace xparam
