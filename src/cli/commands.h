#pragma once
/// \file
/// The subcommands of `xparam`; each file src/cli/<name>_command.cpp adds one.

#include <CLI/CLI.hpp>

namespace xparam::cli {


}  // namespace xparam::cli
