#pragma once
/// \file
/// Writing a complete archive (schemas/archive.md) from a template and its targets.
///
/// The archive is written to "<path>.tmp" and renamed into place only when complete, so
/// `path` is always either absent, the previous archive, or the new one. Targets are
/// streamed one at a time (only one target's arrays are in memory) and must arrive sorted
/// by name: the datasets then do not depend on the order in which targets finished.

#include "io/archive_records.h"

#include <cstddef>
#include <filesystem>
#include <functional>
#include <vector>

namespace xparam {

/// How the archive is written.
struct ArchiveWriteSettings {
  int deflate_level = 4;     ///< zlib level (1..9) of the per-target chunked datasets
  bool xdmf_sidecar = true;  ///< also write "<stem>.xdmf" beside the archive (see io/xdmf.h)
};

/// The sizes every target's arrays must have: those of the template.
struct ArchiveShape {
  std::size_t n_vertices = 0;  ///< template vertices (#V)
  std::size_t n_faces = 0;     ///< template faces (#F)
  std::size_t n_curves = 0;    ///< template curves (#C)
  std::size_t n_anchors = 0;   ///< template anchors (#A)
  std::size_t n_measurements = 0;  ///< template measurements (#M)
};

/// The shape of `template_record`.
ArchiveShape shape_of(const TemplateRecord& template_record);

/// Gives target `i` (0-based) of the archive being written.
using TargetLoader = std::function<TargetRecord(std::size_t)>;

/// Write the archive at `path` with `count` targets, target i from `load(i)`.
/// \pre the names returned by `load` are strictly increasing (std::string order).
/// \throw ArchiveError for records whose arrays do not match the template (naming the
///        target and the array) or on any HDF5 / file-system failure; `path` is untouched then.
void write_archive(const std::filesystem::path& path, const TemplateRecord& template_record,
                   const ArchiveProvenance& provenance, std::size_t count, const TargetLoader& load,
                   const ArchiveWriteSettings& settings = {});

/// Write the archive at `path` from records in any order (sorted by name here).
void write_archive(const std::filesystem::path& path, const TemplateRecord& template_record,
                   const ArchiveProvenance& provenance, const std::vector<TargetRecord>& targets,
                   const ArchiveWriteSettings& settings = {});

/// Check the template's arrays (index ranges, matching lengths, unique anchor and curve names).
/// \throw ArchiveError naming the array.
void validate_template_record(const TemplateRecord& template_record);

/// Check one target against the template: an ok target has every array at the template's
/// size (#V, #F, #C curves); a failed target has an error text. \throw ArchiveError.
void validate_target_record(const TemplateRecord& template_record, const TargetRecord& target);

/// validate_target_record against a shape.
void validate_target_record(const ArchiveShape& shape, const TargetRecord& target);

/// Write one target alone as a "part" file (the unit of the commit protocol of
/// io/archive_commit.h): root attributes format = "xparam-archive-part", schema_version,
/// n_vertices, n_faces, n_curves, n_measurements, options_json (the options the target ran with), and a
/// /targets group with one row, laid out as in an archive. Written to "<path>.tmp", synced
/// and renamed, so `path` is complete or absent.
void write_target_part(const std::filesystem::path& path, const ArchiveShape& shape, const TargetRecord& target,
                       const std::string& options_json, const ArchiveWriteSettings& settings = {});

}  // namespace xparam
