// `xparam batch` as a program: verdicts and --fail-on-suspect, usage and fatal errors' exit codes
// (whole batches read back by h5py, --config, SIGKILL + --resume and the parallel and Slurm
// scripts: batch_command_slow_test).
#include "batch_test_support.h"

#include "batch/batch_driver.h"
#include "io/archive_commit.h"
#include "io/sha256.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace xparam {
namespace {

using test::fs::path;
using test::quoted;

using test::batch;
using test::kQuick;
using test::template_options;

// The options of test::man_template(): the README's template with its curves and measurements.
std::string man_template_options() {
  return template_options() + " --measurements " + quoted(test::data_path("human.measurements.json"));
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

// An archive of the man template with `provenance`. Its one target, the woman, is committed as
// failed with her files' digests, so a resume keeps it and maps nothing.
void write_archive_with(const ArchiveProvenance& provenance, const path& archive, const path& targets) {
  const PreparedTemplate prepared = prepare_template(test::man_template());
  BatchArchive batch = BatchArchive::create(archive, prepared.record, provenance);
  TargetRecord woman;
  woman.name = "woman";
  woman.error = "woman.obj: mapped by an older xparam";
  woman.mesh_file = (targets / "woman.obj").string();
  woman.anchors_file = (targets / "woman.anchors.json").string();
  woman.mesh_sha256 = sha256_file_hex(targets / "woman.obj");
  woman.anchors_sha256 = sha256_file_hex(targets / "woman.anchors.json");
  batch.commit(woman);
  batch.finish();
}

// An archive written before `option` existed: its options do not have it.
void write_archive_predating(const std::string& option, const path& archive, const path& targets) {
  nlohmann::ordered_json options = nlohmann::ordered_json::parse(batch_options_json({}));
  ASSERT_EQ(options.erase(option), 1u);
  write_archive_with(current_provenance(options.dump()), archive, targets);
}

// The command resuming an archive in `dir` from the woman's folder.
std::string resume_command(const path& dir, const path& archive) {
  return man_template_options() + " --targets " + quoted(dir / "targets") + " --out " + quoted(archive) +
         " --resume";
}

// Resuming `archive` with `run` continues it: its failed target is kept, nothing refused.
void expect_continued(const path& dir, const path& archive, const std::string& run) {
  EXPECT_EQ(batch(dir, run), 2) << test::read_file(dir / "stderr.txt");
  const std::string log = test::read_file(dir / "stderr.txt");
  EXPECT_EQ(log.find("cannot resume"), std::string::npos) << log;
  const ArchiveReader resumed(archive);
  ASSERT_EQ(resumed.targets().size(), 1u);
  EXPECT_EQ(resumed.targets()[0].error, "woman.obj: mapped by an older xparam");
}

// Resuming `archive` with `run` is refused with `message`, the archive left byte-identical.
void expect_refused(const path& dir, const path& archive, const std::string& run, const std::string& message) {
  const std::string before = test::read_file(archive);
  EXPECT_EQ(batch(dir, run), 3);
  const std::string refusal = test::read_file(dir / "stderr.txt");
  EXPECT_NE(refusal.find(message), std::string::npos) << refusal;
  EXPECT_EQ(test::read_file(archive), before);
}

// An archive written before `option` was recorded: resuming it with `refused` added is refused
// with `message` (the archive byte-identical), with `continued` added it goes on.
void expect_resumed_as_it_was_only(const std::string& option, const std::string& refused,
                                   const std::string& message, const std::string& continued) {
  const path dir = test::fresh_temp_dir("command_resume_older_" + option);
  test::copy_sample_targets(dir / "targets", {"woman"});
  const path archive = dir / "old.h5";
  write_archive_predating(option, archive, dir / "targets");
  const std::string run = resume_command(dir, archive);
  expect_refused(dir, archive, run + refused, message);
  expect_continued(dir, archive, run + continued);
}

TEST(BatchCommand, AnArchiveOlderThanAnOptionResumesAtItsDefaultOnly) {
  expect_resumed_as_it_was_only("max_maps", " --max-maps 4",
                                "option \"max_maps\" is not recorded (the archive predates it: 7), now 4",
                                "");
}

// A stage that came with its own switch, on by default, did not run before it: such an archive
// continues with the stage off only.
TEST(BatchCommand, AnArchiveOlderThanAStagesSwitchResumesWithTheStageOffOnly) {
  expect_resumed_as_it_was_only(
      "work_vertices", "",
      "option \"work_vertices\" is not recorded (the archive predates it: 0), now 100000",
      " --work-vertices 0");
}

// Likewise a retry made by default: archives from before the map without a doubtful tip continue
// without it only.
TEST(BatchCommand, AnArchiveOlderThanTheDoubtfulTipRetryResumesWithoutItOnly) {
  expect_resumed_as_it_was_only(
      "retry_doubtful_tips", "",
      "option \"retry_doubtful_tips\" is not recorded (the archive predates it: false), now true",
      " --no-retry-doubtful-tips");
}

// An archive another build started, with this run's options: resuming it goes on, with a
// warning naming both builds (the maps may differ without an option saying so), and the archive
// keeps naming the build that started it. This build's own archive resumes without a word.
TEST(BatchCommand, ResumingAnArchiveAnotherBuildStartedWarnsAndGoesOn) {
  const path dir = test::fresh_temp_dir("command_resume_other_build");
  test::copy_sample_targets(dir / "targets", {"woman"});
  const std::string this_run = batch_options_json({});
  ArchiveProvenance other_build = current_provenance(this_run);
  other_build.git_revision = std::string(kGitRevision) + "-other";
  const path archive = dir / "other.h5";
  write_archive_with(other_build, archive, dir / "targets");
  expect_continued(dir, archive, resume_command(dir, archive));
  const std::string warned = test::read_file(dir / "stderr.txt");
  EXPECT_NE(warned.find("warning: " + archive.string() + " was started by xparam " +
                        other_build.xparam_version + " (" + other_build.git_revision + "), this is xparam " +
                        kVersion + " (" + kGitRevision + ")"),
            std::string::npos)
      << warned;
  EXPECT_EQ(ArchiveReader(archive).provenance().git_revision, other_build.git_revision);

  const path own = dir / "own.h5";
  write_archive_with(current_provenance(this_run), own, dir / "targets");
  expect_continued(dir, own, resume_command(dir, own));
  EXPECT_EQ(test::read_file(dir / "stderr.txt").find("was started by"), std::string::npos);
}

}  // namespace
}  // namespace xparam
