#pragma once
/// \file
/// The scan intake's options, shared by `xparam check`, `pair` and `batch`.

#include "intake/scan_intake.h"

#include <CLI/CLI.hpp>

namespace xparam::cli {

/// Add `--intake repair|strict`, `--max-dropped-area PERCENT`, `--max-hole LENGTH` and
/// `--max-handle LENGTH` to `command`, writing into `settings`, which must outlive the parse.
void add_intake_options(CLI::App& command, IntakeSettings& settings);

}  // namespace xparam::cli
