// Batches through the library: a dry run checks every target without writing (the runs that
// compare archives -- thread counts, resume, shards: batch_driver_slow_test).
#include "batch/batch_driver.h"

#include "batch/target_job.h"
#include "batch_library_support.h"

#include <gtest/gtest.h>

#include <vector>

namespace xparam {
namespace {

using test::fs::path;
using test::man;

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
