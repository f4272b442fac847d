#include "cli/stop_signals.h"

#include "cli/commands.h"

#include <signal.h>
#include <unistd.h>

#include <cstring>

namespace xparam::cli {
namespace {

std::atomic<bool> stop_requested{false};
struct sigaction previous_interrupt = {};
struct sigaction previous_terminate = {};

// Async-signal-safe: an atomic store, write(2) and _exit only.
void on_signal(int) {
  if (stop_requested.exchange(true)) {
    constexpr char kNow[] = "\nxparam batch: stopped at once; the committed targets stay: run again with --resume\n";
    [[maybe_unused]] const ssize_t written = ::write(STDERR_FILENO, kNow, sizeof(kNow) - 1);
    ::_exit(kExitInterrupted);
  }
  constexpr char kStopping[] =
      "\nxparam batch: stopping: no further target starts; the targets in flight finish and are committed "
      "(interrupt again to stop at once)\n";
  [[maybe_unused]] const ssize_t written = ::write(STDERR_FILENO, kStopping, sizeof(kStopping) - 1);
}

}  // namespace

StopSignals::StopSignals() {
  stop_requested = false;
  struct sigaction action = {};
  action.sa_handler = on_signal;
  action.sa_flags = SA_RESTART;  // a target's file reads must not fail with EINTR
  sigemptyset(&action.sa_mask);
  ::sigaction(SIGINT, &action, &previous_interrupt);
  ::sigaction(SIGTERM, &action, &previous_terminate);
}

StopSignals::~StopSignals() {
  ::sigaction(SIGINT, &previous_interrupt, nullptr);
  ::sigaction(SIGTERM, &previous_terminate, nullptr);
}

const std::atomic<bool>& StopSignals::requested() const { return stop_requested; }

}  // namespace xparam::cli
