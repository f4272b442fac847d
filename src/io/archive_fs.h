#pragma once
/// \file
/// Durable file replacement for the archive's commit protocol: a file is written under a
/// temporary name, flushed to disk, then renamed over its final name, so a reader (or a
/// process killed at any instant) sees either the old complete file or the new one.

#include <filesystem>

namespace xparam {

/// The temporary name `path` is written under before it is put in place: "<path>.tmp".
std::filesystem::path temporary_path(const std::filesystem::path& path);

/// fsync `temporary`, rename it over `destination`, fsync the directory so the rename
/// itself survives a power cut. \throw ArchiveError naming the file on any failure.
void commit_file(const std::filesystem::path& temporary, const std::filesystem::path& destination);

}  // namespace xparam
