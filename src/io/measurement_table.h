#pragma once
/// \file
/// The measurements of an archive as a CSV table (`xparam export --measurements`): one row for
/// the template, then one per target in archive order; one column per measurement.

#include <filesystem>
#include <string>

namespace xparam {

class ArchiveReader;

/// The table as CSV text: header `name,status,NAME (UNIT),...`; the template's row has status
/// `template`; a value not available (a failed target, a plane that missed) is an empty cell.
/// Values are written with 17 significant digits, so they read back exactly.
/// \throw ArchiveError when the archive has no measurements (naming it and the option that adds them)
std::string measurement_csv(const ArchiveReader& reader);

/// Write measurement_csv of `archive` to `out` (atomically: complete or absent).
void export_measurements(const std::filesystem::path& archive, const std::filesystem::path& out);

}  // namespace xparam
