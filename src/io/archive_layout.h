#pragma once
/// \file
/// Names and HDF5 types shared by the archive writer and reader (schemas/archive.md is the
/// prose version of this file; change both together).

#include "io/archive_hdf5.h"
#include "io/archive_records.h"

#include <cstdint>

namespace xparam::archive_layout {

inline constexpr const char* kFormat = "xparam-archive";  ///< root attribute `format`
inline constexpr const char* kPartFormat = "xparam-archive-part";  ///< `format` of a one-target part file
inline constexpr hsize_t kCurveChunkRows = 4096;          ///< rows per chunk of the flat curve-point arrays
inline constexpr hsize_t kTableChunkRows = 256;           ///< rows (targets) per chunk of the small per-target tables

/// One row of /targets/metrics in memory; the file type is the packed compound of metrics_type().
struct MetricsRow {
  double e_l2;
  double e_ang;
  double stretch_max_sv;
  std::int32_t flipped_faces;
  std::int32_t strictly_folded_faces;
  double area_ratio;
  double gt_error;
  std::int32_t swaps;
  std::int32_t merges;
  std::int32_t released_anchors;
  std::int32_t dropped_faces;
  double dropped_area;
  std::int32_t holes_filled;
  double filled_area;
  std::int32_t on_filled_vertices;
  double max_distance_to_scan;
  std::int32_t file_faces;
};

/// MetricsRow <-> TargetMetrics.
MetricsRow to_row(const TargetMetrics& metrics);
TargetMetrics from_row(const MetricsRow& row);

/// Compound type of /targets/metrics: `packed` for the file, native layout of MetricsRow for memory.
h5::Handle metrics_type(bool packed);

/// Enum type of /targets/status: failed = 0, ok = 1, suspect = 2 (8-bit).
h5::Handle status_type();

}  // namespace xparam::archive_layout
