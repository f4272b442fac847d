#include "cli/text_format.h"

#include "cli/commands.h"

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>

namespace xparam::cli {

std::string figure(double value) {
  if (std::isnan(value)) return "-";
  char text[32];
  std::snprintf(text, sizeof(text), "%.3g", value);
  return text;
}

std::string seconds_text(double seconds) {
  if (std::isnan(seconds)) return "-";
  char text[48];
  if (seconds < 60.0) {
    std::snprintf(text, sizeof(text), seconds < 10.0 ? "%.2f s" : "%.1f s", seconds);
    return text;
  }
  const long total = std::lround(seconds);
  if (total < 3600)
    std::snprintf(text, sizeof(text), "%ld:%02ld", total / 60, total % 60);
  else
    std::snprintf(text, sizeof(text), "%ld:%02ld:%02ld", total / 3600, total / 60 % 60, total % 60);
  return text;
}

std::string plural(std::size_t count, const std::string& noun) {
  return std::to_string(count) + " " + noun + (count == 1 ? "" : "s");
}

void usage_error(const std::string& command, const std::string& message) {
  std::cerr << "xparam " << command << ": " << message << "\n";
  throw CLI::RuntimeError(kExitUsage);
}

}  // namespace xparam::cli
