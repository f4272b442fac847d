// What `xparam batch` shows while it runs: plain lines without control characters when stderr
// is a pipe, a live block with each running target's stage on a terminal (a pseudo-terminal made
// by script(1)), nothing with --quiet.
#include "batch_test_support.h"

#include <gtest/gtest.h>

#include <signal.h>

#include <chrono>
#include <regex>
#include <thread>

namespace xparam {
namespace {

using test::fs::path;
using test::quoted;

std::string quick_run(const path& dir) {
  test::copy_sample_targets(dir / "targets", {"woman"});
  return test::template_options() + test::kQuick + " --max-maps 1 --targets " + quoted(dir / "targets") +
         " --out " + quoted(dir / "out.h5");
}

bool has_control_characters(const std::string& text) {
  for (unsigned char c : text)
    if ((c < 0x20 && c != '\n') || c == 0x7f) return true;
  return false;
}

TEST(BatchProgress, PipedRunPrintsPlainLinesAndQuietNothing) {
  const path dir = test::fresh_temp_dir("progress_piped");
  const std::string run = quick_run(dir);
  ASSERT_EQ(test::batch(dir, run), 0) << test::read_file(dir / "stderr.txt");
  const std::string log = test::read_file(dir / "stderr.txt");
  EXPECT_FALSE(has_control_characters(log)) << log;
  // The finished target's line stays with its figures.
  EXPECT_TRUE(std::regex_search(log, std::regex(R"(\[1/1\] ok woman  E_L2 [0-9.]+  folds 0 \(strict 0\)  area 0\.9)")))
      << log;
  EXPECT_NE(log.find("1 target: 1 ok, 0 suspect, 0 failed"), std::string::npos) << log;

  ASSERT_EQ(test::batch(dir, run + " --force --quiet"), 0);
  EXPECT_EQ(test::read_file(dir / "stderr.txt"), "");
}

TEST(BatchProgress, TerminalShowsARunningTargetsStageSoonAfterTheStart) {
  if (test::run_status("command -v script > /dev/null") != 0) GTEST_SKIP() << "script(1) (bsdutils) is missing";
  const path dir = test::fresh_temp_dir("progress_terminal");
  const std::string command = quoted(test::xparam_binary()) + " batch" + quick_run(dir);
  // script -q: no banner; -f: flush every write; -e: its exit status is the command's.
  // The command's own words are single-quoted, so the whole is double-quoted.
  std::string shell = "script -qfec \"";
  shell += command + "\" /dev/null > " + quoted(dir / "terminal.txt");
  const auto start = std::chrono::steady_clock::now();
  std::thread runner([&] { EXPECT_EQ(test::run_status(shell), 0); });
  // A live line "  woman  STAGE  ELAPSED" while the target runs (after a line break, or after the
  // erase-below code that starts each redraw).
  const std::regex stage_line(R"((\n|\[J)  woman  [a-z][a-z ]*  [0-9.]+ s)");
  double seen_after = -1.0;
  while (std::chrono::steady_clock::now() - start < std::chrono::seconds(60)) {
    if (std::regex_search(test::read_file(dir / "terminal.txt"), stage_line)) {
      seen_after = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  runner.join();
  const std::string screen = test::read_file(dir / "terminal.txt");
  ASSERT_GE(seen_after, 0.0) << screen;
  // Before the target finished, not only in the closing lines; redrawn in place (cursor up).
  EXPECT_LT(screen.find("  woman  "), screen.find("[1/1] ok woman")) << screen;
  EXPECT_NE(screen.find("\033["), std::string::npos) << screen;
#if defined(NDEBUG) && !defined(__SANITIZE_ADDRESS__)
  // The template is read in well under a second: the first stage shows within 2 s (Release).
  EXPECT_LT(seen_after, 2.0) << screen;
#endif
}

}  // namespace
}  // namespace xparam
