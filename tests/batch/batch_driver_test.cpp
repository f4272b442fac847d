// Whole batch runs through the library: resume completes only what is missing, a dry run writes
// nothing (thread counts and shards: batch_driver_slow_test).
#include "batch/batch_driver.h"

#include "batch/target_job.h"
#include "batch_library_support.h"
#include "core/errors.h"
#include "io/archive_commit.h"

#include <gtest/gtest.h>

#include <cmath>

namespace xparam {
namespace {

using test::fs::path;

using test::man;
using test::outcome;
using test::quick;
using test::resume;
using test::run;

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

TEST(BatchDriver, DryRunChecksEveryTargetWithoutWriting) {
  const path dir = test::fresh_temp_dir("driver_dry");
  test::copy_sample_targets(dir / "targets", {"woman_turned"});
  test::add_broken_targets(dir / "targets");
  const BatchPlan plan = plan_batch(discover_targets(dir / "targets"), {}, {}, false);
  const std::vector<TargetOutcome> checked = check_batch(man(), plan, 2);
  ASSERT_EQ(checked.size(), 5u);
  for (const TargetOutcome& o : checked) EXPECT_EQ(o.ok, o.name == "woman_turned") << o.name << ": " << o.error;
}

}  // namespace
}  // namespace xparam
