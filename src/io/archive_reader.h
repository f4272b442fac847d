#pragma once
/// \file
/// Reading an archive written by io/archive_writer.h (layout: schemas/archive.md).
///
/// The reader keeps the file open, so reading many targets (merge, export) opens it once.
/// The small per-target columns (names, status, metrics, files) are read at open; the large
/// arrays of a target only when asked for.

#include "io/archive_hdf5.h"
#include "io/archive_records.h"

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace xparam {

/// The small columns of one target: everything but its arrays.
struct ArchiveTargetSummary {
  std::string name;            ///< target name
  bool ok = false;             ///< status: ok or suspect (the pipeline finished)
  bool suspect = false;        ///< status suspect: ok, but a quality limit failed
  std::string error;           ///< error text, empty when ok
  std::string diagnosis;       ///< the diagnosis JSON, empty when failed
  std::string mesh_file;       ///< input mesh file
  std::string anchors_file;    ///< input anchor file
  std::string mesh_sha256;     ///< SHA-256 of the mesh file
  std::string anchors_sha256;  ///< SHA-256 of the anchor file
  /// The options the target ran with: the archive's options_json, or a part file's own (empty
  /// for a part written before parts recorded them).
  std::string options_json;
  TargetMetrics metrics;       ///< the metrics table row
  /// #M the target's measurements (/targets/measurements; NaN for a failed target), in the
  /// order of the template's measurement_names
  std::vector<double> measurements;
  StageSeconds seconds{};      ///< the timings row
};

/// An open archive.
class ArchiveReader {
 public:
  /// Open `path` (an archive, or a one-target part file of io/archive_commit.h) read-only and
  /// read its small columns.
  /// \throw ArchiveError when it is missing, not HDF5, not an xparam archive, or of a schema version
  /// outside kOldestReadableArchiveSchemaVersion .. kArchiveSchemaVersion.
  explicit ArchiveReader(const std::filesystem::path& path);

  /// The archive's file name.
  const std::filesystem::path& path() const { return path_; }
  /// Root attributes: who wrote it, with which options (a part file: its options_json only).
  const ArchiveProvenance& provenance() const { return provenance_; }
  /// Root attribute schema_version.
  int schema_version() const { return schema_version_; }
  /// Whether /targets/distance_to_scan is stored (schema 5 on); read_target explains what an older
  /// archive gives instead.
  bool records_distance_to_scan() const { return schema_version_ >= 5; }
  /// Template vertex count (#V of every remesh).
  std::size_t n_vertices() const { return n_vertices_; }
  /// Template face count (#F of every remesh).
  std::size_t n_faces() const { return n_faces_; }
  /// Template measurement count (#M columns of /targets/measurements).
  std::size_t n_measurements() const { return n_measurements_; }
  /// The template's measurement names (#M; empty for a part file, which has no template).
  const std::vector<std::string>& measurement_names() const { return measurement_names_; }
  /// The unit of each measurement (#M; empty for a part file).
  const std::vector<std::string>& measurement_units() const { return measurement_units_; }
  /// Targets in archive (name) order.
  const std::vector<ArchiveTargetSummary>& targets() const { return targets_; }
  /// Row of the target called `name`, if present.
  std::optional<std::size_t> find(const std::string& name) const;

  /// Whether this is a one-target part file (no template, no provenance).
  bool is_part() const { return is_part_; }
  /// The template with its anchors and curves. \throw ArchiveError for a part file.
  TemplateRecord read_template() const;
  /// Everything about the target in row `row` (arrays empty for a failed target). An archive that
  /// does not record distance_to_scan gives 0 for images off filled-in surface and NaN on it.
  /// \throw ArchiveError when row is out of range.
  TargetRecord read_target(std::size_t row) const;

 private:
  std::filesystem::path path_;
  h5::Handle file_;
  ArchiveProvenance provenance_;
  bool is_part_ = false;
  int schema_version_ = 0;
  std::size_t n_vertices_ = 0;
  std::size_t n_faces_ = 0;
  std::size_t n_curves_ = 0;
  std::size_t n_anchors_ = 0;
  std::size_t n_measurements_ = 0;
  std::vector<std::string> measurement_names_, measurement_units_;
  std::vector<ArchiveTargetSummary> targets_;
};

/// A whole archive in memory (tests and small archives).
struct ArchiveContents {
  ArchiveProvenance provenance;        ///< root attributes
  TemplateRecord template_record;      ///< /template
  std::vector<TargetRecord> targets;   ///< /targets rows in order
};

/// Read every dataset of the archive at `path`.
ArchiveContents read_archive(const std::filesystem::path& path);

}  // namespace xparam
