#pragma once
/// \file
/// How every xparam command talks to a person about its command line: help with defaults in
/// plain words, number checks whose message says the bound (CLI11's own print the range up to
/// DBL_MAX, 300 digits), and "did you mean" for a misspelt long option.

#include <CLI/CLI.hpp>

#include <memory>
#include <string>

namespace xparam::cli {

/// A help formatter that writes `--merge, --no-merge` rather than `--merge,--no-merge{false}`
/// and puts an option's default after its description as "(default: X)".
std::shared_ptr<CLI::Formatter> plain_formatter();

/// A number check: the value is at least `low` (`inclusive`) or above it. Its message names the
/// bound and the value, e.g. "must be at least 1, got 0".
CLI::Validator at_least(double low, bool inclusive = true);

/// "--optimize" for "--optimise": the long option of the command `argv` selected (or of `app`)
/// nearest to an unknown `--word` of argv by edit distance, when near enough to be a typo.
/// Empty when no argument is unknown or none is near.
std::string did_you_mean(const CLI::App& app, int argc, const char* const* argv);

}  // namespace xparam::cli
