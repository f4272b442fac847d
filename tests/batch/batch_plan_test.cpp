// Planning a run: sharding, what an archive already holds, resume and retry decisions.
#include "batch/batch_plan.h"

#include "batch/batch_driver.h"
#include "batch_test_support.h"
#include "io/archive_commit.h"

#include <gtest/gtest.h>

namespace xparam {
namespace {

using test::fs::path;

std::vector<TargetSpec> specs(const std::vector<std::string>& names) {
  std::vector<TargetSpec> targets;
  for (const std::string& name : names) targets.push_back({name, name + ".obj", name + ".pp", {}, {}});
  return targets;
}

ArchiveTargetSummary committed(const std::string& name, bool ok) {
  ArchiveTargetSummary summary;
  summary.name = name;
  summary.ok = ok;
  return summary;
}

std::vector<TargetAction> actions(const BatchPlan& plan) {
  std::vector<TargetAction> out;
  for (const PlannedTarget& t : plan.targets) out.push_back(t.action);
  return out;
}

TEST(BatchPlan, FreshRunRunsTheWholeShard) {
  const BatchPlan plan = plan_batch(specs({"a", "b", "c", "d", "e"}), {1, 2}, {}, false);
  EXPECT_EQ(plan.discovered, 5u);
  ASSERT_EQ(plan.targets.size(), 2u);
  EXPECT_EQ(plan.targets[0].spec.name, "b");
  EXPECT_EQ(plan.targets[1].spec.name, "d");
  EXPECT_EQ(plan.count(TargetAction::Run), 2u);
  EXPECT_TRUE(plan.foreign.empty());
}

TEST(BatchPlan, ResumeKeepsCommittedTargetsAndRetriesFailedOnlyWhenAsked) {
  const std::map<std::string, ArchiveTargetSummary> archive = {
      {"a", committed("a", true)}, {"b", committed("b", false)}, {"gone", committed("gone", true)}};
  const BatchPlan keep = plan_batch(specs({"a", "b", "c"}), {}, archive, false);
  EXPECT_EQ(actions(keep),
            (std::vector<TargetAction>{TargetAction::KeepDone, TargetAction::KeepFailed, TargetAction::Run}));
  EXPECT_EQ(keep.foreign, std::vector<std::string>{"gone"});
  const BatchPlan retry = plan_batch(specs({"a", "b", "c"}), {}, archive, true);
  EXPECT_EQ(actions(retry), (std::vector<TargetAction>{TargetAction::KeepDone, TargetAction::Run, TargetAction::Run}));
}

// A kept row is only ever a row of this run's options: a part recorded with other options (two
// writers once mixed them) runs again, and the plan says which option and both values. A record
// without options (a part of an older xparam) is judged by the archive's options alone.
TEST(BatchPlan, TargetsOfOtherOptionsRunAgainNamingTheOption) {
  std::map<std::string, ArchiveTargetSummary> archive = {
      {"a", committed("a", true)}, {"b", committed("b", true)}, {"c", committed("c", true)}};
  archive["a"].options_json = R"({"relax":true,"optimization":{"merge":true}})";
  archive["b"].options_json = R"({"relax":true,"optimization":{"merge":false}})";
  const BatchPlan plan = plan_batch(specs({"a", "b", "c"}), {}, archive, false,
                                    R"({"relax":true,"optimization":{"merge":false}})");
  EXPECT_EQ(actions(plan),
            (std::vector<TargetAction>{TargetAction::Run, TargetAction::KeepDone, TargetAction::KeepDone}));
  EXPECT_EQ(plan.targets[0].reason, "it ran with other options: option \"optimization.merge\" was true, now false");
  EXPECT_TRUE(plan.targets[1].reason.empty());
}

// committed_targets reads rows of ARCHIVE.h5 and parts beside it, a part overriding a row.
TEST(BatchPlan, CommittedTargetsReadsArchiveRowsAndParts) {
  const path dir = test::fresh_temp_dir("plan_committed");
  const path archive_path = dir / "out.h5";
  EXPECT_TRUE(committed_targets(archive_path).empty());

  const PreparedTemplate prepared = prepare_template(test::man_template());
  const ArchiveProvenance provenance = current_provenance(batch_options_json({}));
  const auto failed = [](const std::string& name, const std::string& error) {
    TargetRecord record;
    record.name = name;
    record.error = error;
    record.mesh_file = name + ".obj";
    return record;
  };
  {
    BatchArchive archive = BatchArchive::create(archive_path, prepared.record, provenance);
    archive.commit(failed("x", "first error"));
    archive.commit(failed("y", "y error"));
    archive.finish(true);  // parts removed: the rows are all that is left
  }
  ASSERT_FALSE(std::filesystem::exists(parts_directory(archive_path)));
  std::map<std::string, ArchiveTargetSummary> found = committed_targets(archive_path);
  ASSERT_EQ(found.size(), 2u);
  EXPECT_EQ(found.at("x").error, "first error");

  {
    BatchArchive archive = BatchArchive::resume(archive_path, prepared.record, provenance);
    archive.commit(failed("x", "second error"));
    archive.commit(failed("z", "z error"));
    // No assembly: the new records exist only as parts, as after a SIGKILL.
  }
  // A write killed half-way leaves a temporary file, which is not a commit.
  test::write_file(target_part_path(archive_path, "w").string() + ".tmp", "partial");
  found = committed_targets(archive_path);
  ASSERT_EQ(found.size(), 3u);
  EXPECT_EQ(found.at("x").error, "second error");
  EXPECT_EQ(found.at("y").error, "y error");
  EXPECT_EQ(found.at("z").error, "z error");
  EXPECT_FALSE(found.at("z").ok);
}

}  // namespace
}  // namespace xparam
