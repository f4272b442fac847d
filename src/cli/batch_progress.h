#pragma once
/// \file
/// What `xparam batch` shows while it runs, on stderr.
///
/// On a terminal: a live block, redrawn at least twice a second, with one line per running
/// target (name, stage, elapsed time) and an overall line (a bar, done of total, ok / suspect /
/// failed counts, the rate and an ETA from the first finished target on); every finished target
/// leaves one permanent line above the block with its figures. Piped (stderr not a terminal):
/// only the permanent lines, without control characters. Quiet: nothing. A hand-written
/// renderer of a few ANSI codes (cursor up, erase below): Debian packages no C++ progress
/// library (indicators and the like are not in the archive), and fmt's colours would not draw
/// the block.

#include "batch/batch_driver.h"

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <map>
#include <mutex>
#include <string>
#include <thread>

namespace xparam::cli {

/// How the progress is shown.
enum class ProgressMode {
  Live,   ///< a terminal: live block plus permanent lines
  Plain,  ///< a pipe or file: permanent lines only
  Quiet,  ///< nothing
};

/// Live when stderr is a terminal, Plain otherwise; Quiet when `quiet`.
ProgressMode progress_mode_for_stderr(bool quiet);

/// The progress display of one batch run. Thread-safe: stages come from the worker threads.
class BatchProgressView {
 public:
  /// `total`: the targets this run executes.
  BatchProgressView(ProgressMode mode, std::size_t total);
  /// Stops the redrawing; on a terminal the running lines are erased and the overall line stays.
  ~BatchProgressView();
  BatchProgressView(const BatchProgressView&) = delete;
  BatchProgressView& operator=(const BatchProgressView&) = delete;

  /// A line of what happens before the targets start (the template being read), shown live.
  void preparing(const std::string& what);
  /// A target's stage started (TargetStageCallback).
  void stage(const std::string& target, const std::string& stage);
  /// A target finished (BatchProgressCallback).
  void finished(const BatchProgress& progress);

 private:
  using Clock = std::chrono::steady_clock;
  struct Running {
    std::string stage;
    Clock::time_point started;
  };

  void redraw_locked();
  void erase_block_locked();
  std::string overall_line_locked() const;
  void ticker();

  ProgressMode mode_;
  std::size_t total_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;
  std::string preparing_;
  std::map<std::string, Running> running_;  // by name: the block lists them in name order
  BatchProgress last_;
  Clock::time_point start_ = Clock::now();
  std::size_t block_lines_ = 0;  // lines of the live block now on screen
  std::thread ticker_;
};

/// One finished target's permanent line: "[3/7] ok woman  E_L2 1.53  folds 0  area 0.991  12.4 s",
/// with the reasons after a suspect one and the error after a failed one.
std::string finished_line(const BatchProgress& progress);

}  // namespace xparam::cli
