#pragma once
/// \file
/// The subcommands of `xparam`; each file src/cli/<name>_command.cpp adds one.

#include <CLI/CLI.hpp>

namespace xparam::cli {

/// Exit codes shared by every subcommand (README, "Exit codes"). A command that ends with a
/// code other than 0 throws CLI::RuntimeError(code) after printing why; main returns the code.
inline constexpr int kExitUsage = 1;        ///< the command line is wrong (unknown option, missing file, bad value)
inline constexpr int kExitSomeFailed = 2;   ///< the job ran, but some inputs failed (batch targets, check meshes)
inline constexpr int kExitFatal = 3;        ///< the job could not run or a stage failed (bad template, unwritable output)
inline constexpr int kExitInterrupted = 130;  ///< batch stopped by SIGINT/SIGTERM; what finished is committed (--resume)

void add_check_command(CLI::App& app);  ///< `xparam check MESH...` (check_command.cpp)
void add_pair_command(CLI::App& app);   ///< `xparam pair --source S ... --out DIR` (pair_command.cpp)
void add_batch_command(CLI::App& app);  ///< `xparam batch --template T --targets DIR --out A.h5` (batch_command.cpp)
void add_inspect_command(CLI::App& app);  ///< `xparam inspect ARCHIVE [--json]` (inspect_command.cpp)
void add_export_command(CLI::App& app);   ///< `xparam export ARCHIVE --target NAME --out FILE` (export_command.cpp)
void add_merge_command(CLI::App& app);    ///< `xparam merge SHARD.h5... --out ARCHIVE.h5` (merge_command.cpp)
void add_warp_command(CLI::App& app);    ///< `xparam warp --archive A.h5 --garment G.obj --out DIR|OUT.h5` (warp_command.cpp)
void add_layout_command(CLI::App& app);  ///< `xparam layout --source S ... --out DIR [--check]` (layout_command.cpp)

}  // namespace xparam::cli
