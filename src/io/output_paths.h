#pragma once
/// \file
/// Checks, before any work, that the files a run will write can be written, so a bad path is
/// found in a second rather than after hours of targets (an unwritable --summary used to be
/// found only after every target ran).

#include <filesystem>
#include <string>

namespace xparam {

/// Check that `file` can be written: it is not a directory, its folder exists and a file can be
/// created in it (tried with a probe file, removed at once, so read-only mounts and permissions
/// are seen alike), and when it exists it can be opened for writing (it is not changed).
/// `role` names it in the message ("--summary", "the archive's XDMF sidecar").
/// \throw InputError "FILE (role): why; what to do"
void check_writable_file(const std::filesystem::path& file, const std::string& role);

/// Check that `directory` can be created and written: when it exists it must be a writable
/// directory, otherwise check_writable_file rules apply to the name. \throw InputError
void check_writable_directory(const std::filesystem::path& directory, const std::string& role);

/// Every output of a batch run into `archive`: the archive, its parts directory, its lock
/// file's folder and its XDMF sidecar (io/xdmf.h). \throw InputError naming the first problem
void check_archive_outputs(const std::filesystem::path& archive);

}  // namespace xparam
