#include "io/archive_layout.h"

#include <cstddef>

namespace xparam::archive_layout {

MetricsRow to_row(const TargetMetrics& m) {
  return {m.e_l2,          m.e_ang,        m.stretch_max_sv,       m.flipped_faces, m.strictly_folded_faces,
          m.area_ratio,    m.gt_error,     m.swaps,                m.merges,        m.released_anchors,
          m.dropped_faces, m.dropped_area, m.holes_filled,         m.filled_area,   m.on_filled_vertices,
          m.max_distance_to_scan, m.file_faces};
}

TargetMetrics from_row(const MetricsRow& r) {
  TargetMetrics m;
  m.e_l2 = r.e_l2;
  m.e_ang = r.e_ang;
  m.stretch_max_sv = r.stretch_max_sv;
  m.flipped_faces = r.flipped_faces;
  m.strictly_folded_faces = r.strictly_folded_faces;
  m.area_ratio = r.area_ratio;
  m.gt_error = r.gt_error;
  m.swaps = r.swaps;
  m.merges = r.merges;
  m.released_anchors = r.released_anchors;
  m.dropped_faces = r.dropped_faces;
  m.dropped_area = r.dropped_area;
  m.holes_filled = r.holes_filled;
  m.filled_area = r.filled_area;
  m.on_filled_vertices = r.on_filled_vertices;
  m.max_distance_to_scan = r.max_distance_to_scan;
  m.file_faces = r.file_faces;
  return m;
}

h5::Handle metrics_type(bool packed) {
  h5::Handle type(H5Tcreate(H5T_COMPOUND, sizeof(MetricsRow)), H5Tclose, "metrics type");
  const hid_t f64 = packed ? H5T_IEEE_F64LE : H5T_NATIVE_DOUBLE;
  const hid_t i32 = packed ? H5T_STD_I32LE : H5T_NATIVE_INT32;
  const auto insert = [&](const char* name, std::size_t offset, hid_t member) {
    h5::check(H5Tinsert(type.get(), name, offset, member), "metrics type", name);
  };
  // Column names are those of the paper and of schemas/archive.md.
  insert("E_L2", offsetof(MetricsRow, e_l2), f64);
  insert("E_ang", offsetof(MetricsRow, e_ang), f64);
  insert("stretch_max_sv", offsetof(MetricsRow, stretch_max_sv), f64);
  insert("flipped_faces", offsetof(MetricsRow, flipped_faces), i32);
  insert("strictly_folded_faces", offsetof(MetricsRow, strictly_folded_faces), i32);
  insert("area_ratio", offsetof(MetricsRow, area_ratio), f64);
  insert("gt_error", offsetof(MetricsRow, gt_error), f64);
  insert("swaps", offsetof(MetricsRow, swaps), i32);
  insert("merges", offsetof(MetricsRow, merges), i32);
  insert("released_anchors", offsetof(MetricsRow, released_anchors), i32);
  insert("dropped_faces", offsetof(MetricsRow, dropped_faces), i32);
  insert("dropped_area", offsetof(MetricsRow, dropped_area), f64);
  insert("holes_filled", offsetof(MetricsRow, holes_filled), i32);
  insert("filled_area", offsetof(MetricsRow, filled_area), f64);
  insert("on_filled_vertices", offsetof(MetricsRow, on_filled_vertices), i32);
  insert("max_distance_to_scan", offsetof(MetricsRow, max_distance_to_scan), f64);
  insert("file_faces", offsetof(MetricsRow, file_faces), i32);
  if (packed) h5::check(H5Tpack(type.get()), "metrics type", "cannot pack");
  return type;
}

h5::Handle status_type() {
  h5::Handle type(H5Tenum_create(H5T_STD_I8LE), H5Tclose, "status type");
  const std::int8_t failed = 0;
  const std::int8_t ok = 1;
  h5::check(H5Tenum_insert(type.get(), "failed", &failed), "status type", "failed");
  h5::check(H5Tenum_insert(type.get(), "ok", &ok), "status type", "ok");
  const std::int8_t suspect = 2;
  h5::check(H5Tenum_insert(type.get(), "suspect", &suspect), "status type", "suspect");
  return type;
}

}  // namespace xparam::archive_layout
