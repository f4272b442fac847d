// `xparam batch` as a program on whole batches: failures exit 2 and read back by h5py, --config
// against the command line, a run killed with SIGKILL and resumed, and the GNU parallel and Slurm scripts
// merged against one run. Long under the sanitizers, so they run in the Release pass only
// (label `slow`).
#include "batch_test_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <signal.h>
#include <sys/wait.h>

#include <chrono>
#include <string>
#include <thread>

namespace xparam {
namespace {

using test::fs::path;
using test::quoted;

using test::batch;
using test::compare_with_h5py;
using test::kQuick;
using test::python_or_skip;
using test::template_options;

// A script of scripts/, quoted for the shell.
std::string script(const std::string& name) { return quoted(path(XPARAM_SOURCE_DIR) / "scripts" / name); }

TEST(BatchCommand, ConfigFileGivesOptionsAndTheCommandLineWins) {
  const path dir = test::fresh_temp_dir("command_config");
  test::copy_sample_targets(dir / "targets", {"woman"});
  test::write_file(dir / "run.toml", "# xparam batch options\ntemplate = \"" + test::data_path("human_man.obj").string() +
                                         "\"\ntemplate-anchors = \"" +
                                         test::data_path("human.anchors.json").string() + "\"\ntargets = \"" +
                                         (dir / "targets").string() + "\"\nthreads = 1\nout = \"" +
                                         (dir / "from_config.h5").string() + "\"\n");
  ASSERT_EQ(batch(dir, " -j 2 --config " + quoted(dir / "run.toml") + " --out " + quoted(dir / "out.h5") +
                           " --summary " + quoted(dir / "summary.json")),
            0)
      << test::read_file(dir / "stderr.txt");
  EXPECT_TRUE(std::filesystem::exists(dir / "out.h5"));
  EXPECT_FALSE(std::filesystem::exists(dir / "from_config.h5"));
  const nlohmann::json summary = nlohmann::json::parse(test::read_file(dir / "summary.json"));
  EXPECT_EQ(summary["threads"], 2);
  EXPECT_EQ(summary["succeeded"], 1);
  EXPECT_EQ(summary["failed"], 0);

  test::write_file(dir / "bad.toml", "tempalte = \"x\"\n");
  EXPECT_NE(batch(dir, " --config " + quoted(dir / "bad.toml") + template_options() + " --targets " +
                           quoted(dir / "targets") + " --out " + quoted(dir / "x.h5")),
            0);
  EXPECT_NE(test::read_file(dir / "stderr.txt").find("tempalte"), std::string::npos);
}

TEST(BatchCommand, KilledRunResumesToTheDatasetsOfAnUninterruptedRun) {
  const path dir = test::fresh_temp_dir("command_kill");
  test::copy_sample_targets(dir / "targets", {"woman", "man_bent"});
  const std::string common = template_options() + kQuick + " --targets " + quoted(dir / "targets") + " -j 1";
  ASSERT_EQ(batch(dir, common + " --out " + quoted(dir / "full.h5")), 0) << test::read_file(dir / "stderr.txt");

  const path archive = dir / "killed.h5";
  const pid_t child = test::spawn_batch({"--template", test::data_path("human_man.obj").string(), "--template-anchors",
                                   test::data_path("human.anchors.json").string(), "--curves",
                                   test::data_path("human_man.curves.json").string(), "--targets",
                                   (dir / "targets").string(), "-j", "1", "--checkpoint-seconds", "0",
                                   "--no-optimize-map", "--no-extremity-anchors", "--out", archive.string()},
                                  dir / "killed.log");
  ASSERT_GT(child, 0);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (!test::has_committed_part(archive) && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ASSERT_EQ(kill(child, SIGKILL), 0);
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the run ended before it could be killed";

  // The archive on disk opens (an earlier assembly), for xparam and for h5py.
  EXPECT_LT(ArchiveReader(archive).targets().size(), 2u);
  const std::string python = python_or_skip();
  EXPECT_EQ(test::run_status(python + " " + quoted(test::read_back_script()) + " --open " + quoted(archive)), 0);

  ASSERT_EQ(batch(dir, common + " --out " + quoted(archive) + " --resume --summary " + quoted(dir / "summary.json")), 0)
      << test::read_file(dir / "stderr.txt");
  const nlohmann::json summary = nlohmann::json::parse(test::read_file(dir / "summary.json"));
  EXPECT_GE(summary["kept"].get<int>(), 1);
  EXPECT_EQ(summary["kept"].get<int>() + summary["ran"].get<int>(), 2);
  test::expect_same_datasets(dir / "full.h5", archive);
  EXPECT_EQ(compare_with_h5py(dir / "full.h5", archive), 0);
}

// The GNU parallel runner for real, and the Slurm script's body with SLURM_ARRAY_TASK_ID set;
// both must merge into the datasets of a single run.
TEST(BatchCommand, ParallelAndSlurmScriptsMergeIntoOneRunsDatasets) {
  const path dir = test::fresh_temp_dir("command_scripts");
  test::copy_sample_targets(dir / "targets", {"man_bent"});
  test::add_broken_targets(dir / "targets");
  const std::string targets = " --targets " + quoted(dir / "targets");
  ASSERT_EQ(batch(dir, template_options() + kQuick + targets + " -j 2 --out " + quoted(dir / "single.h5")), 2);

  const std::string env = "XPARAM=" + quoted(test::xparam_binary()) + " ";
  // The program named by --xparam (XPARAM, set wrong here, is only the fallback).
  EXPECT_EQ(test::run_status("XPARAM=/nonexistent " + script("run_parallel.sh") + " --xparam " +
                             quoted(test::xparam_binary()) + " 3 " + quoted(dir / "parallel.h5") + template_options() +
                             kQuick + targets + " -j 1 > " + quoted(dir / "parallel.log") + " 2>&1"),
            2)
      << test::read_file(dir / "parallel.log");
  test::expect_same_datasets(dir / "single.h5", dir / "parallel.h5");
  EXPECT_EQ(compare_with_h5py(dir / "single.h5", dir / "parallel.h5"), 0);

  const std::string slurm_env = env + "XPARAM_TEMPLATE=" + quoted(test::data_path("human_man.obj")) +
                                " XPARAM_TEMPLATE_ANCHORS=" + quoted(test::data_path("human.anchors.json")) +
                                " XPARAM_CURVES=" + quoted(test::data_path("human_man.curves.json")) +
                                " XPARAM_TARGETS=" + quoted(dir / "targets") + " XPARAM_OUT=" +
                                quoted(dir / "slurm.h5") + " XPARAM_SHARDS=2 SLURM_CPUS_PER_TASK=1 XPARAM_OPTIONS=" +
                                "'--no-optimize-map --no-extremity-anchors' ";
  for (int task = 0; task < 2; ++task)
    EXPECT_EQ(test::run_status(slurm_env + "SLURM_ARRAY_TASK_ID=" + std::to_string(task) + " SLURM_ARRAY_TASK_COUNT=2 " +
                               script("slurm_batch.sh") + " 2> " + quoted(dir / "slurm.log")),
              2)
        << test::read_file(dir / "slurm.log");
  const nlohmann::json shard_summary =
      nlohmann::json::parse(test::read_file(dir / "slurm.h5.shards" / "shard_1.summary.json"));
  EXPECT_EQ(shard_summary["shard"]["index"], 1);
  EXPECT_EQ(shard_summary["targets_in_shard"], 2);  // 5 targets: shard 1 of 2 holds rows 1 and 3
  ASSERT_EQ(test::run_status(slurm_env + script("slurm_batch.sh") + " merge 2> " + quoted(dir / "slurm.log")), 0)
      << test::read_file(dir / "slurm.log");
  test::expect_same_datasets(dir / "single.h5", dir / "slurm.h5");

  // `submit` with a stand-in sbatch: the array of N tasks, then a merge depending on it.
  std::filesystem::create_directories(dir / "bin");
  test::write_file(dir / "bin" / "sbatch", "#!/bin/sh\necho \"$@\" >> \"$SBATCH_LOG\"\necho 4242\n");
  std::filesystem::permissions(dir / "bin" / "sbatch", std::filesystem::perms::owner_all);
  ASSERT_EQ(test::run_status("PATH=" + quoted(dir / "bin") + ":\"$PATH\" SBATCH_LOG=" + quoted(dir / "sbatch.log") +
                             " " + slurm_env + script("slurm_batch.sh") + " submit 2> /dev/null"),
            0);
  const std::string calls = test::read_file(dir / "sbatch.log");
  const std::size_t newline = calls.find('\n');
  ASSERT_NE(newline, std::string::npos) << calls;
  EXPECT_NE(calls.substr(0, newline).find("--array=0-1"), std::string::npos) << calls;
  EXPECT_NE(calls.substr(newline).find("--dependency=afterany:4242"), std::string::npos) << calls;
  EXPECT_NE(calls.substr(newline).find("slurm_batch.sh merge"), std::string::npos) << calls;
}

TEST(BatchCommand, FailuresExitTwoAndAreReadBackByH5py) {
  const path dir = test::fresh_temp_dir("command_failures");
  test::copy_sample_targets(dir / "targets", {"woman", "woman_turned", "man_flipped", "man_bent"});
  test::add_broken_targets(dir / "targets");

  // --dry-run: every input checked, the plan printed, nothing written.
  EXPECT_EQ(batch(dir, template_options() + " --targets " + quoted(dir / "targets") + " --out " +
                           quoted(dir / "out.h5") + " --dry-run"),
            2);
  const std::string plan = test::read_file(dir / "stdout.txt");
  EXPECT_NE(plan.find("8 of 8 targets"), std::string::npos) << plan;
  EXPECT_NE(plan.find("check torus: FAILS"), std::string::npos) << plan;
  EXPECT_NE(plan.find("check woman: ok"), std::string::npos) << plan;
  EXPECT_NE(plan.find("4 of 8 targets to run pass"), std::string::npos) << plan;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.h5"));

  ASSERT_EQ(batch(dir, template_options() + kQuick + " --targets " + quoted(dir / "targets") + " --out " +
                           quoted(dir / "out.h5") + " -j 2 --summary " + quoted(dir / "summary.json")),
            2)
      << test::read_file(dir / "stderr.txt");
  // Not a terminal: one plain line per target.
  const std::string log = test::read_file(dir / "stderr.txt");
  EXPECT_NE(log.find("] FAILED torus: "), std::string::npos) << log;
  EXPECT_NE(log.find("] ok woman "), std::string::npos) << log;

  const nlohmann::json summary = nlohmann::json::parse(test::read_file(dir / "summary.json"));
  EXPECT_EQ(summary["failed"], 4);
  EXPECT_EQ(summary["succeeded"], 4);
  EXPECT_EQ(summary["threads"], 2);
  EXPECT_EQ(summary["targets"].size(), 8u);
  EXPECT_EQ(summary["targets"][0]["name"], "man_bent");
  EXPECT_TRUE(summary["targets"][0]["metrics"]["gt_error"].is_number());
  EXPECT_EQ(summary["targets"][3]["name"], "torus");
  EXPECT_EQ(summary["targets"][3]["status"], "failed");
  EXPECT_TRUE(summary["targets"][3]["metrics"]["E_L2"].is_null());

  const nlohmann::json expected = {
      {"targets",
       {{"woman", {{"ok", true}}},
        {"woman_turned", {{"ok", true}}},
        {"man_flipped", {{"ok", true}}},
        {"man_bent", {{"ok", true}}},
        {"truncated", {{"ok", false}, {"error_contains", {"truncated.obj"}}}},
        {"no_anchors", {{"ok", false}, {"error_contains", {"no anchors", "no_anchors.obj"}}}},
        {"torus", {{"ok", false}, {"error_contains", {"torus.ply", "handle (genus 1)", "--max-handle"}}}},
        {"unknown_name", {{"ok", false}, {"error_contains", {"NOT_A_LANDMARK", "unknown_name.anchors.json"}}}}}}};
  test::write_file(dir / "expected.json", expected.dump());
  const std::string python = python_or_skip();
  const path checker = path(XPARAM_SOURCE_DIR) / "tests" / "batch" / "batch_archive_check.py";
  EXPECT_EQ(test::run_status(python + " " + quoted(checker) + " " + quoted(dir / "out.h5") + " " +
                             quoted(dir / "expected.json")),
            0);
  EXPECT_EQ(test::run_status(python + " " + quoted(test::read_back_script()) + " --open " + quoted(dir / "out.h5")), 0);
}

}  // namespace
}  // namespace xparam
