#pragma once
/// \file
/// Merging shard archives (one template, disjoint subsets of the targets, e.g. one per
/// machine) into one archive whose datasets are identical to a single run over all targets:
/// rows are copied and re-sorted by name, so the merged file is written exactly as the
/// single run's assembly would write it.

#include "io/archive_writer.h"

#include <filesystem>
#include <vector>

namespace xparam {

/// Merge `shards` into `out` (written through "<out>.tmp", with its XDMF sidecar).
/// \throw ArchiveError when there are no shards, a shard is unreadable, the templates or
///        provenance (xparam version, git revision, options) differ, or a target name
///        appears in two shards (naming both files).
void merge_archives(const std::vector<std::filesystem::path>& shards, const std::filesystem::path& out,
                    const ArchiveWriteSettings& settings = {});

}  // namespace xparam
