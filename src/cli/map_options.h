#pragma once
/// \file
/// The options of the map itself, shared by `xparam pair` and `xparam batch`: the base-domain
/// optimization and the remesh untangling.

#include "map/pair_mapping.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

namespace xparam::cli {

/// Add `--optimize METRIC` (none, ad, l2, area, dad, dl2, sdl, gar, balanced; default balanced),
/// `--merge/--no-merge` (default merge), `--no-stretch` and `--keep-corners` to `command`, writing into
/// `settings`, which must outlive the parse (`xparam layout` takes just these).
void add_optimization_options(CLI::App& command, DomainOptimizationSettings& settings);

/// The optimization options, `--relax/--no-relax`, `--second-layout/--no-second-layout` and
/// `--untangle/--no-untangle` (all default on), writing into `settings`, which must outlive the
/// parse.
void add_map_options(CLI::App& command, PairSettings& settings);

/// What the base-domain optimization did, as metrics.json and layout.json report it.
nlohmann::json optimization_json(const DomainOptimizationResult& optimization);

}  // namespace xparam::cli
