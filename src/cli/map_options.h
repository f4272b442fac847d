#pragma once
/// \file
/// The options of the map itself, shared by `xparam pair` and `xparam batch`: the base-domain
/// optimization and the remesh untangling.

#include "map/pair_mapping.h"

#include <CLI/CLI.hpp>

namespace xparam::cli {

/// Add `--optimize METRIC` (none, ad, l2, area, dad, dl2, sdl, gar, balanced; default balanced),
/// `--merge/--no-merge` (default merge), `--no-stretch` and `--untangle/--no-untangle` (default
/// untangle) to `command`, writing into `settings`, which must outlive the parse.
void add_map_options(CLI::App& command, PairSettings& settings);

}  // namespace xparam::cli
