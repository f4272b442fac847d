#pragma once
/// \file
/// How the CLI writes numbers and counts for a person: three significant digits, seconds as a
/// person reads them, "1 target" but "2 targets", and one way to refuse a wrong command line.

#include <cstddef>
#include <string>

namespace xparam::cli {

/// Three significant digits ("1.53", "2.24e+03", "0.000220"); "-" for NaN (no value).
std::string figure(double value);

/// Seconds as a person reads them: "0.22 s", "12.4 s", "3:05" (m:ss), "1:02:03" (h:mm:ss);
/// "-" for NaN.
std::string seconds_text(double seconds);

/// "1 target", "2 targets", "0 targets" (`noun` takes an "s" for the plural).
std::string plural(std::size_t count, const std::string& noun);

/// Print "xparam COMMAND: MESSAGE" on stderr and end the command with exit status 1 (a usage
/// error: README, "Exit codes"), whatever layer found the problem.
[[noreturn]] void usage_error(const std::string& command, const std::string& message);

}  // namespace xparam::cli
