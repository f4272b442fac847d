// `xparam batch` as a program: exit codes, --summary, --dry-run, verdicts and an independent h5py
// reader (--config, SIGKILL + --resume and the parallel and Slurm scripts: batch_command_slow_test).
#include "batch_test_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace xparam {
namespace {

using test::fs::path;
using test::quoted;

using test::batch;
using test::kQuick;
using test::python_or_skip;
using test::template_options;

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
        {"torus", {{"ok", false}, {"error_contains", {"genus mismatch", "torus.ply", "genus 1"}}}},
        {"unknown_name", {{"ok", false}, {"error_contains", {"NOT_A_LANDMARK", "unknown_name.anchors.json"}}}}}}};
  test::write_file(dir / "expected.json", expected.dump());
  const std::string python = python_or_skip();
  const path checker = path(XPARAM_SOURCE_DIR) / "tests" / "batch" / "batch_archive_check.py";
  EXPECT_EQ(test::run_status(python + " " + quoted(checker) + " " + quoted(dir / "out.h5") + " " +
                             quoted(dir / "expected.json")),
            0);
  EXPECT_EQ(test::run_status(python + " " + quoted(test::read_back_script()) + " --open " + quoted(dir / "out.h5")), 0);
}

// The woman's anchors with LEFT_NIPPLE and RIGHT_NIPPLE traded: a left/right mix-up in a
// landmark file.
void add_swapped_woman(const path& dir) {
  std::filesystem::create_directories(dir);
  std::filesystem::copy_file(test::sample_targets() / "woman.obj", dir / "swapped.obj");
  std::string anchors = test::read_file(test::sample_targets() / "woman.anchors.json");
  const auto replace = [&](const std::string& from, const std::string& to) {
    const std::size_t at = anchors.find("\"" + from + "\"");
    ASSERT_NE(at, std::string::npos) << from;
    anchors.replace(at, from.size() + 2, "\"" + to + "\"");
  };
  replace("LEFT_NIPPLE", "SWAP_PLACEHOLDER");
  replace("RIGHT_NIPPLE", "LEFT_NIPPLE");
  replace("SWAP_PLACEHOLDER", "RIGHT_NIPPLE");
  test::write_file(dir / "swapped.anchors.json", anchors);
}

TEST(BatchCommand, SwappedLandmarksMakeTheTargetSuspectAndFailOnSuspectExitsTwo) {
  const path dir = test::fresh_temp_dir("command_suspect");
  add_swapped_woman(dir / "targets");
  // One map without relaxation: the swap is found from the landmarks, whatever the map.
  const std::string run = template_options() + kQuick + " --max-maps 1 --no-relax --targets " + quoted(dir / "targets") + " --out " +
                          quoted(dir / "out.h5") + " --summary " + quoted(dir / "summary.json");
  // Without --fail-on-suspect a suspect target is a result like any other: exit 0.
  ASSERT_EQ(batch(dir, run), 0) << test::read_file(dir / "stderr.txt");
  const std::string log = test::read_file(dir / "stderr.txt");
  EXPECT_NE(log.find("] suspect swapped "), std::string::npos) << log;
  EXPECT_NE(log.find("1 target: 0 ok, 1 suspect, 0 failed"), std::string::npos) << log;

  const nlohmann::json summary = nlohmann::json::parse(test::read_file(dir / "summary.json"));
  EXPECT_EQ(summary["suspect"], 1);
  EXPECT_EQ(summary["succeeded"], 1);
  ASSERT_EQ(summary["targets"].size(), 1u);
  EXPECT_EQ(summary["targets"][0]["status"], "suspect");
  bool named = false;
  for (const auto& reason : summary["targets"][0]["reasons"]) {
    const std::string text = reason.get<std::string>();
    named = named || (text.find("\"LEFT_NIPPLE\"") != std::string::npos &&
                      text.find("\"RIGHT_NIPPLE\"") != std::string::npos && text.find("swapped") != std::string::npos);
  }
  EXPECT_TRUE(named) << summary["targets"][0]["reasons"].dump();

  // The archive keeps the verdict and the diagnosis: inspect --target names the pair.
  ASSERT_EQ(test::run_status(quoted(test::xparam_binary()) + " inspect " + quoted(dir / "out.h5") +
                             " --target swapped > " + quoted(dir / "inspect.txt")),
            0);
  const std::string inspect = test::read_file(dir / "inspect.txt");
  EXPECT_NE(inspect.find("swapped: suspect"), std::string::npos) << inspect;
  EXPECT_NE(inspect.find("look swapped on the target"), std::string::npos) << inspect;

  // --fail-on-suspect: exit 2 for scripts, also for a suspect target kept by --resume.
  EXPECT_EQ(batch(dir, run + " --resume --fail-on-suspect"), 2) << test::read_file(dir / "stderr.txt");
}

TEST(BatchCommand, UsageAndFatalErrorsHaveTheirExitCodes) {
  const path dir = test::fresh_temp_dir("command_exit_codes");
  test::copy_sample_targets(dir / "targets", {"woman"});
  const std::string targets = " --targets " + quoted(dir / "targets");

  EXPECT_EQ(batch(dir, template_options() + targets + " --out " + quoted(dir / "a.h5") + " --shard 2/2"), 1);
  EXPECT_NE(test::read_file(dir / "stderr.txt").find("--shard 2/2"), std::string::npos);

  test::write_file(dir / "manifest.json", "{\"not\": \"a list\"}");
  EXPECT_EQ(batch(dir, template_options() + " --targets " + quoted(dir / "manifest.json") + " --out " +
                           quoted(dir / "a.h5")),
            1);

  // A genus-1 template is fatal, whatever the targets.
  EXPECT_EQ(batch(dir, " --template " + quoted(test::data_path("bob_small.ply")) + " --template-anchors " +
                           quoted(test::data_path("human.anchors.json")) + targets + " --out " +
                           quoted(dir / "a.h5")),
            3);
  EXPECT_NE(test::read_file(dir / "stderr.txt").find("template"), std::string::npos);

  // An output below a regular file cannot be written.
  test::write_file(dir / "file.txt", "x");
  EXPECT_EQ(batch(dir, template_options() + targets + " --out " + quoted(dir / "file.txt" / "a.h5")), 3);
  EXPECT_FALSE(std::filesystem::exists(dir / "a.h5"));
}

}  // namespace
}  // namespace xparam
