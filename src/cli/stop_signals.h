#pragma once
/// \file
/// Ctrl-C (SIGINT) and SIGTERM during a batch run: the first asks the run to stop (no further
/// target starts, the targets in flight finish and are committed, the archive is assembled,
/// exit 130); a second one ends the process at once, exit 130 (what was committed stays:
/// `--resume` continues from it).

#include <atomic>

namespace xparam::cli {

/// Catches SIGINT and SIGTERM for its lifetime (the previous handlers come back after it).
class StopSignals {
 public:
  /// Install the handlers.
  StopSignals();
  /// Restore the previous handlers.
  ~StopSignals();
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

  /// Raised by the first signal; BatchSettings::stop watches it.
  const std::atomic<bool>& requested() const;
};

}  // namespace xparam::cli
