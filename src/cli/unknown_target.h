#pragma once
/// \file
/// One refusal for `--target NAME` of a name the archive does not hold, shared by inspect,
/// export and warp.

#include "io/archive_reader.h"

#include <string>

namespace xparam::cli {

/// usage_error for `command`: "ARCHIVE: no target "NAME"; it holds A, B" (or "none"), followed by
/// "(xparam inspect lists them)" when `point_to_inspect` (every command but inspect itself).
[[noreturn]] void refuse_unknown_target(const std::string& command, const ArchiveReader& reader,
                                        const std::string& name, bool point_to_inspect);

}  // namespace xparam::cli
