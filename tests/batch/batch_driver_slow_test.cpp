// Whole batches run through the library more than once to compare the archives: at 1 and 2
// threads, resumed after an interruption, and in shards merged against one run. Long under the sanitizers (which cannot see a
// race anyway), so they run in the Release pass only (label `slow`).
#include "batch/batch_driver.h"

#include "batch_library_support.h"
#include "core/errors.h"
#include "io/archive_commit.h"
#include "io/archive_merge.h"
#include "io/archive_reader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace xparam {
namespace {

using test::fs::path;

using test::man;
using test::outcome;
using test::quick;
using test::resume;
using test::run;

TEST(BatchDriver, FailuresAreRecordedAndThreadCountDoesNotChangeTheDatasets) {
  const path dir = test::fresh_temp_dir("driver_threads");
  test::copy_sample_targets(dir / "targets", {"woman", "woman_turned", "man_flipped", "man_bent"});
  test::add_broken_targets(dir / "targets");

  // The map's own thread independence, optimization on the target included, is
  // PairMapping.UntanglingIsTheSameAtOneAndTwoThreads; this is the batch's.
  std::vector<std::size_t> done;
  const BatchSummary one = run(dir / "targets", dir / "one.h5", 1, {}, [&](const BatchProgress& p) {
    EXPECT_EQ(p.total, 8u);
    ASSERT_NE(p.last, nullptr);
    EXPECT_LE(p.failed, p.done);
    done.push_back(p.done);
  }, quick());
  EXPECT_EQ(done, (std::vector<std::size_t>{1, 2, 3, 4, 5, 6, 7, 8}));
  EXPECT_EQ(one.ran, 8u);
  EXPECT_EQ(one.succeeded, 4u);
  EXPECT_EQ(one.failed, 4u);
  EXPECT_EQ(one.archive_targets, 8u);
  for (const char* name : {"woman", "woman_turned", "man_flipped", "man_bent"}) {
    const TargetOutcome& o = outcome(one, name);
    EXPECT_TRUE(o.ok) << name << ": " << o.error;
    // Same vertex order on every sample target: the ground truth is the identity. A mix-up of
    // targets or vertex orders would put the mean error near half a body height.
    EXPECT_LT(o.metrics.gt_error, 0.1) << name;
  }
  EXPECT_NE(outcome(one, "torus").error.find("--max-handle"), std::string::npos);
  EXPECT_NE(outcome(one, "no_anchors").error.find("no anchors"), std::string::npos);
  EXPECT_NE(outcome(one, "unknown_name").error.find("NOT_A_LANDMARK"), std::string::npos);
  EXPECT_NE(outcome(one, "truncated").error.find("truncated.obj"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(parts_directory(dir / "one.h5")));

  const ArchiveReader reader(dir / "one.h5");
  ASSERT_EQ(reader.targets().size(), 8u);
  for (std::size_t i = 0; i < reader.targets().size(); ++i) {
    const ArchiveTargetSummary& row = reader.targets()[i];
    EXPECT_EQ(row.ok, outcome(one, row.name).ok);
    EXPECT_EQ(row.error, outcome(one, row.name).error);
    EXPECT_TRUE(std::isfinite(row.seconds.back())) << row.name;
  }

  const BatchSummary two = run(dir / "targets", dir / "two.h5", 2, {}, {}, quick());
  EXPECT_EQ(two.threads, 2);
  EXPECT_EQ(two.failed, 4u);
  test::expect_same_datasets(dir / "one.h5", dir / "two.h5");
}

TEST(BatchDriver, ShardsMergeIntoTheDatasetsOfOneRun) {
  const path dir = test::fresh_temp_dir("driver_shards");
  test::copy_sample_targets(dir / "targets", {"woman_turned", "man_bent"});
  test::add_broken_targets(dir / "targets");
  run(dir / "targets", dir / "single.h5", 2, {}, {}, quick());
  std::vector<path> shards;
  for (int i = 0; i < 3; ++i) {
    shards.push_back(dir / ("shard_" + std::to_string(i) + ".h5"));
    const BatchSummary summary = run(dir / "targets", shards.back(), 1, {i, 3}, {}, quick());
    EXPECT_EQ(summary.discovered, 6u);
    EXPECT_EQ(summary.targets.size(), 2u);
  }
  merge_archives(shards, dir / "merged.h5");
  test::expect_same_datasets(dir / "single.h5", dir / "merged.h5");
}

TEST(BatchDriver, ResumeCompletesOnlyWhatIsMissing) {
  const path dir = test::fresh_temp_dir("driver_resume");
  test::copy_sample_targets(dir / "targets", {"woman", "man_bent"});
  test::add_broken_targets(dir / "targets");
  std::filesystem::remove(dir / "targets" / "truncated.obj");
  std::filesystem::remove(dir / "targets" / "truncated.anchors.json");
  run(dir / "targets", dir / "full.h5", 2, {}, {}, quick());

  // An interrupted run: one target committed as a part, no final assembly (as after SIGKILL).
  {
    const ArchiveProvenance provenance = current_provenance(batch_options_json(quick()));
    BatchArchive archive = BatchArchive::create(dir / "resumed.h5", man().record, provenance);
    const std::vector<TargetSpec> targets = discover_targets(dir / "targets");
    for (const TargetSpec& t : targets)
      if (t.name == "man_bent" || t.name == "torus") archive.commit(run_target(man(), t, quick()));
  }
  EXPECT_EQ(ArchiveReader(dir / "resumed.h5").targets().size(), 0u);  // opens: the initial assembly

  const BatchSummary resumed = resume(dir / "targets", dir / "resumed.h5", false, quick());
  EXPECT_EQ(resumed.ran, 3u);  // woman, no_anchors, unknown_name
  EXPECT_EQ(resumed.kept, 2u);
  EXPECT_FALSE(outcome(resumed, "man_bent").ran);
  EXPECT_TRUE(outcome(resumed, "man_bent").ok);
  EXPECT_FALSE(outcome(resumed, "torus").ok);
  EXPECT_TRUE(outcome(resumed, "woman").ran);
  test::expect_same_datasets(dir / "full.h5", dir / "resumed.h5");

  // Everything is committed now: only the failed ones rerun, and only when asked.
  EXPECT_EQ(resume(dir / "targets", dir / "resumed.h5", false, quick()).ran, 0u);
  const BatchSummary retried = resume(dir / "targets", dir / "resumed.h5", true, quick());
  EXPECT_EQ(retried.ran, 3u);
  EXPECT_EQ(retried.failed, 3u);
  test::expect_same_datasets(dir / "full.h5", dir / "resumed.h5");

  // Other method options than the archive was started with: refused, nothing changes.
  PairSettings other = quick();
  other.layout.greedy_diagonals = false;
  EXPECT_THROW(resume(dir / "targets", dir / "resumed.h5", true, other), ArchiveError);
}

}  // namespace
}  // namespace xparam
