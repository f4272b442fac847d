#pragma once
/// \file
/// The scan intake's options, shared by `xparam check`, `pair` and `batch`, and what it did as JSON.

#include "core/intake_record.h"
#include "intake/scan_intake.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

namespace xparam::cli {

/// Add `--intake repair|strict`, `--max-dropped-area PERCENT` and `--max-hole LENGTH` to `command`,
/// writing into `settings`, which must outlive the parse.
void add_intake_options(CLI::App& command, IntakeSettings& settings);

/// The intake's record as metrics.json and `check --json` report it (`applied` false and zeros
/// when the file was taken as it is).
nlohmann::json intake_json(const IntakeRecord& record);

}  // namespace xparam::cli
