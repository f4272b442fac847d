#pragma once
/// \file
/// Bitwise comparison of archive records (tests of the archive and of batch determinism).

#include "io/archive_records.h"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>

namespace xparam::test {

/// Bitwise equality, so NaN == NaN and -0.0 != 0.0.
inline bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

/// Same shape and every entry bitwise equal (entries compared as doubles).
template <typename A, typename B>
bool same_bits(const A& a, const B& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) return false;
  for (Eigen::Index i = 0; i < a.size(); ++i) {
    if (!same_bits(static_cast<double>(a.data()[i]), static_cast<double>(b.data()[i]))) return false;
  }
  return true;
}

/// Expects two records of the same target to agree bit for bit in everything the pipeline
/// computes deterministically: identity, status, input digests, every array and every metric
/// (all but the seconds, which are timings).
inline void expect_same_results(const TargetRecord& a, const TargetRecord& b) {
  SCOPED_TRACE(a.name);
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.ok, b.ok);
  EXPECT_EQ(a.suspect, b.suspect);
  EXPECT_EQ(a.error, b.error);
  EXPECT_EQ(a.diagnosis, b.diagnosis);
  EXPECT_EQ(a.mesh_file, b.mesh_file);
  EXPECT_EQ(a.anchors_file, b.anchors_file);
  EXPECT_EQ(a.mesh_sha256, b.mesh_sha256);
  EXPECT_EQ(a.anchors_sha256, b.anchors_sha256);
  EXPECT_TRUE(same_bits(a.remesh_vertices, b.remesh_vertices));
  EXPECT_TRUE(same_bits(a.corr_face, b.corr_face));
  EXPECT_TRUE(same_bits(a.corr_bary, b.corr_bary));
  EXPECT_TRUE(same_bits(a.distance_to_scan, b.distance_to_scan));
  EXPECT_TRUE(same_bits(a.face_patch, b.face_patch));
  EXPECT_TRUE(same_bits(a.face_l2_stretch, b.face_l2_stretch));
  EXPECT_TRUE(same_bits(a.face_angle_distortion, b.face_angle_distortion));
  EXPECT_TRUE(same_bits(a.anchor_miss, b.anchor_miss));
  EXPECT_TRUE(same_bits(a.measurements, b.measurements));
  ASSERT_EQ(a.curves.size(), b.curves.size());
  for (std::size_t c = 0; c < a.curves.size(); ++c) {
    EXPECT_EQ(a.curves[c].face, b.curves[c].face);
    EXPECT_TRUE(same_bits(a.curves[c].bary, b.curves[c].bary));
    EXPECT_TRUE(same_bits(a.curves[c].xyz, b.curves[c].xyz));
  }
  EXPECT_TRUE(same_bits(a.metrics.e_l2, b.metrics.e_l2));
  EXPECT_TRUE(same_bits(a.metrics.e_ang, b.metrics.e_ang));
  EXPECT_TRUE(same_bits(a.metrics.stretch_max_sv, b.metrics.stretch_max_sv));
  EXPECT_EQ(a.metrics.flipped_faces, b.metrics.flipped_faces);
  EXPECT_EQ(a.metrics.strictly_folded_faces, b.metrics.strictly_folded_faces);
  EXPECT_TRUE(same_bits(a.metrics.area_ratio, b.metrics.area_ratio));
  EXPECT_TRUE(same_bits(a.metrics.gt_error, b.metrics.gt_error));
  EXPECT_EQ(a.metrics.swaps, b.metrics.swaps);
  EXPECT_EQ(a.metrics.merges, b.metrics.merges);
  EXPECT_EQ(a.metrics.released_anchors, b.metrics.released_anchors);
  EXPECT_EQ(a.metrics.dropped_faces, b.metrics.dropped_faces);
  EXPECT_TRUE(same_bits(a.metrics.dropped_area, b.metrics.dropped_area));
  EXPECT_EQ(a.metrics.holes_filled, b.metrics.holes_filled);
  EXPECT_TRUE(same_bits(a.metrics.filled_area, b.metrics.filled_area));
  EXPECT_EQ(a.metrics.on_filled_vertices, b.metrics.on_filled_vertices);
  EXPECT_TRUE(same_bits(a.metrics.max_distance_to_scan, b.metrics.max_distance_to_scan));
  EXPECT_EQ(a.metrics.file_faces, b.metrics.file_faces);
}

}  // namespace xparam::test
