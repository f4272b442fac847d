#pragma once
/// \file
/// Wall-clock timing of pipeline stages (reported, never compared: not deterministic).

#include <chrono>

namespace xparam {

/// Measures consecutive intervals: each lap() returns the seconds since the previous lap (or
/// since construction).
class Stopwatch {
 public:
  /// Seconds since the last lap, then starts the next interval.
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return seconds;
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

}  // namespace xparam
