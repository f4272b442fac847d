#pragma once
/// \file
/// The base-domain optimization options shared by `xparam pair` and `xparam batch`.

#include "domain/base_domain_optimization.h"

#include <CLI/CLI.hpp>

namespace xparam::cli {

/// Add `--optimize METRIC` (none, area, dad, dl2, sdl, gar, balanced; default balanced),
/// `--merge/--no-merge` (default merge) and `--no-stretch` to `command`, writing into `settings`,
/// which must outlive the parse.
void add_optimization_options(CLI::App& command, DomainOptimizationSettings& settings);

}  // namespace xparam::cli
