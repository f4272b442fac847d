#pragma once
// Helpers of the tests that run batches and target jobs through the library (not the program):
// the prepared template, the quick settings of the bookkeeping tests, a run, a resume.

#include "batch/batch_driver.h"
#include "batch/target_discovery.h"
#include "batch/target_job.h"
#include "batch_test_support.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace xparam::test {

// The README's template, prepared once for the whole test program.
inline const PreparedTemplate& man() {
  static const PreparedTemplate prepared = prepare_template(man_template());
  return prepared;
}

// The map without its optimization on the target nor the map through protrusion tips, for the
// tests of the archive's bookkeeping (resume, shards): a few times faster, and what they check
// does not depend on the map.
inline PairSettings quick() {
  PairSettings settings;
  settings.optimize_map = false;
  settings.extremity_anchors = false;
  return settings;
}

inline BatchSummary run(const fs::path& targets, const fs::path& archive, int threads, const Shard& shard = {},
                        const BatchProgressCallback& progress = {}, const PairSettings& pair = {}) {
  BatchSettings settings;
  settings.archive = archive;
  settings.threads = threads;
  settings.pair = pair;
  return run_batch(man(), plan_batch(discover_targets(targets), shard, {}, false), settings, progress);
}

inline BatchSummary resume(const fs::path& targets, const fs::path& archive, bool retry_failed,
                           const PairSettings& pair = {}) {
  BatchSettings settings;
  settings.archive = archive;
  settings.threads = 2;
  settings.resume = true;
  settings.pair = pair;
  return run_batch(man(), plan_batch(discover_targets(targets), {}, committed_targets(archive), retry_failed),
                   settings);
}

inline const TargetOutcome& outcome(const BatchSummary& summary, const std::string& name) {
  for (const TargetOutcome& o : summary.targets)
    if (o.name == name) return o;
  throw std::runtime_error("no outcome " + name);
}

inline const TargetSpec& spec(const std::vector<TargetSpec>& targets, const std::string& name) {
  for (const TargetSpec& t : targets)
    if (t.name == name) return t;
  throw std::runtime_error("no target " + name);
}

}  // namespace xparam::test
