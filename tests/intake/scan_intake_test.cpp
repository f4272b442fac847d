// The intake on synthetic damage with known truth (tests/intake/intake_damage.h): what it
// repairs, drops and fills, how every prepared element maps back to the file, and what it refuses.
#include "intake/scan_intake.h"

#include "core/validation.h"
#include "intake/intake_damage.h"
#include "support/expect_error.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

namespace xparam {
namespace {

// The vertex of `soup` nearest to `p`.
int nearest_vertex(const TriangleSoup& soup, const Eigen::Vector3d& p) {
  int best = 0;
  for (std::size_t i = 1; i < soup.vertices.size(); ++i)
    if ((soup.vertices[i] - p).norm() < (soup.vertices[best] - p).norm()) best = static_cast<int>(i);
  return best;
}

// Spot's right flank, away from every anchor.
constexpr double kFlank[3] = {0.35, -0.1, 0.4};

// Every prepared face that came from the file has the file face's corners (same positions),
// from the same first corner, in the order `reversed` says; fill faces are numbered after the file's.
void expect_traced_to_file(const TriangleSoup& file, const PreparedScan& prepared) {
  const auto file_faces = static_cast<int>(file.triangles.size());
  for (std::size_t f = 0; f < prepared.soup.triangles.size(); ++f) {
    const int source = prepared.face_source[f];
    if (source >= file_faces) continue;
    std::array<int, 3> corners = file.triangles[source];
    if (prepared.reversed[f]) std::swap(corners[1], corners[2]);
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(prepared.soup.vertices[prepared.soup.triangles[f][k]], file.vertices[corners[k]]) << "face " << f;
    EXPECT_EQ(prepared.prepared_face_of_file[source], static_cast<int>(f));
  }
  for (std::size_t v = 0; v < prepared.soup.vertices.size(); ++v) {
    const int source = prepared.vertex_source[v];
    if (source < static_cast<int>(file.vertices.size())) {
      EXPECT_EQ(prepared.soup.vertices[v], file.vertices[source]);
    }
  }
}

TEST(ScanIntake, DuplicatedFaceIsRemovedAndTheRestKeepsTheFileNumbering) {
  const TriangleSoup clean = test::clean_spot();
  for (bool reversed : {false, true}) {
    const TriangleSoup damaged = test::duplicate_face(clean, 100, reversed);
    ASSERT_FALSE(validate_soup(damaged).usable);
    const PreparedScan prepared = prepare_scan(damaged, {});
    EXPECT_EQ(prepared.record.duplicate_faces, 1);
    EXPECT_TRUE(prepared.record.dropped_parts.empty());
    EXPECT_TRUE(prepared.record.holes.empty());
    ASSERT_EQ(prepared.soup.triangles.size(), clean.triangles.size());
    for (std::size_t f = 0; f < clean.triangles.size(); ++f) EXPECT_EQ(prepared.face_source[f], static_cast<int>(f));
    EXPECT_EQ(prepared.prepared_face_of_file.back(), -1);  // the duplicate
    expect_traced_to_file(damaged, prepared);
    const MeshReport report = validate_soup(prepared.soup);
    EXPECT_TRUE(report.usable);
    EXPECT_EQ(report.genus, 0);
  }
}

TEST(ScanIntake, FloaterIsDroppedWithItsFacesAndArea) {
  const TriangleSoup clean = test::clean_spot();
  const double edge = 0.02;
  const TriangleSoup damaged = test::add_floater(clean, Eigen::Vector3d(2.0, 0.0, 0.0), edge);
  const PreparedScan prepared = prepare_scan(damaged, {});
  EXPECT_EQ(prepared.record.parts, 2);
  ASSERT_EQ(prepared.record.dropped_parts.size(), 1u);
  EXPECT_EQ(prepared.record.dropped_parts[0].faces, 4);
  // Three right triangles of legs `edge` and one equilateral of side edge * sqrt(2).
  const double area = 1.5 * edge * edge + std::sqrt(3.0) / 4.0 * 2.0 * edge * edge;
  EXPECT_NEAR(prepared.record.dropped_parts[0].area, area, 1e-12);
  EXPECT_EQ(prepared.soup.triangles.size(), clean.triangles.size());
  for (int v = 0; v < 4; ++v) EXPECT_EQ(prepared.prepared_vertex_of_file[clean.vertices.size() + v], -1);
  expect_traced_to_file(damaged, prepared);
  EXPECT_TRUE(validate_soup(prepared.soup).usable);
}

TEST(ScanIntake, HoleIsFilledWithNewFacesNumberedAfterTheFile) {
  const TriangleSoup clean = test::clean_spot();
  std::vector<int> removed;
  const int center = nearest_vertex(clean, Eigen::Vector3d(kFlank[0], kFlank[1], kFlank[2]));
  const TriangleSoup damaged = test::punch_hole(clean, center, 0.08, removed);
  ASSERT_GE(removed.size(), 6u);
  const PreparedScan prepared = prepare_scan(damaged, {});
  ASSERT_EQ(prepared.record.holes.size(), 1u);
  const FilledHole& hole = prepared.record.holes[0];
  EXPECT_EQ(prepared.record.filled_faces, hole.faces);
  EXPECT_EQ(prepared.soup.triangles.size(), damaged.triangles.size() + static_cast<std::size_t>(hole.faces));
  EXPECT_TRUE(hole.faired);
  // The patch covers about the area punched out (a faired patch bulges a little, never by half).
  double punched = 0.0;
  for (int f : removed) {
    const auto& t = clean.triangles[f];
    punched += 0.5 * (clean.vertices[t[1]] - clean.vertices[t[0]]).cross(clean.vertices[t[2]] - clean.vertices[t[0]]).norm();
  }
  EXPECT_NEAR(hole.area, punched, 0.5 * punched);
  // The vertices inside the hole are unused in the damaged file.
  std::set<int> used;
  for (const auto& t : damaged.triangles) used.insert(t.begin(), t.end());
  EXPECT_EQ(prepared.record.unused_vertices, static_cast<int>(clean.vertices.size() - used.size()));
  for (std::size_t f = 0; f < prepared.face_source.size(); ++f)
    EXPECT_EQ(prepared.face_source[f] >= static_cast<int>(damaged.triangles.size()), f >= damaged.triangles.size());
  expect_traced_to_file(damaged, prepared);
  const MeshReport report = validate_soup(prepared.soup);
  EXPECT_TRUE(report.usable) << (report.errors().empty() ? "" : report.errors()[0]->message);
  EXPECT_EQ(report.genus, 0);
}

TEST(ScanIntake, HoleOverTheLimitIsRefusedNamingItsSizeTheNearestAnchorAndTheFix) {
  const TriangleSoup clean = test::clean_spot();
  std::vector<int> removed;
  const Eigen::Vector3d flank(kFlank[0], kFlank[1], kFlank[2]);
  const TriangleSoup damaged = test::punch_hole(clean, nearest_vertex(clean, flank), 0.08, removed);
  IntakeSettings settings;
  settings.max_hole = 0.05;
  const std::string message = test::error_message_of([&] { prepare_scan(damaged, {{"Flank", flank}}, settings); });
  EXPECT_MESSAGE_HAS(message, "spot_low_resolution.obj: hole of ");
  EXPECT_MESSAGE_HAS(message, "at \"Flank\" is over --max-hole 0.05");
  EXPECT_MESSAGE_HAS(message, "raise --max-hole");
}

TEST(ScanIntake, LargeLoosePartIsRefusedAndSoIsAnAnchorOnADroppedPart) {
  const TriangleSoup clean = test::clean_spot();
  // A box of edge 1 next to Spot: about a quarter of the area.
  const TriangleSoup damaged = test::add_floater(clean, Eigen::Vector3d(3.0, 0.0, 0.0), 1.0);
  std::string message = test::error_message_of([&] { prepare_scan(damaged, {}); });
  EXPECT_MESSAGE_HAS(message, "spot_low_resolution.obj: 2 parts; the one kept holds");
  EXPECT_MESSAGE_HAS(message, "is over --max-dropped-area 10%");
  IntakeSettings generous;
  generous.max_dropped_area = 0.5;
  EXPECT_NO_THROW(prepare_scan(damaged, {}, generous));

  const TriangleSoup small = test::add_floater(clean, Eigen::Vector3d(3.0, 0.0, 0.0), 0.02);
  message = test::error_message_of(
      [&] { prepare_scan(small, {{"Nose tip", Eigen::Vector3d(0.0, 0.4, -0.7)}, {"Lost", Eigen::Vector3d(3.0, 0.0, 0.0)}}); });
  EXPECT_MESSAGE_HAS(message, "anchor \"Lost\" lies on a part");
  EXPECT_MESSAGE_HAS(message, "move the anchor");
}

TEST(ScanIntake, AnchorsChooseThePartKept) {
  const TriangleSoup clean = test::clean_spot();
  // Two parts of the same mesh side by side: the anchors decide.
  TriangleSoup twice = clean;
  const int n = static_cast<int>(clean.vertices.size());
  for (const Eigen::Vector3d& p : clean.vertices) twice.vertices.push_back(p + Eigen::Vector3d(5.0, 0.0, 0.0));
  for (const auto& t : clean.triangles) twice.triangles.push_back({t[0] + n, t[1] + n, t[2] + n});
  IntakeSettings settings;
  settings.max_dropped_area = 0.6;
  const PreparedScan prepared = prepare_scan(twice, {{"Nose tip", Eigen::Vector3d(5.0, 0.4, -0.7)}}, settings);
  ASSERT_EQ(prepared.record.dropped_parts.size(), 1u);
  EXPECT_EQ(prepared.face_source.front(), static_cast<int>(clean.triangles.size()));
  EXPECT_EQ(prepared.prepared_vertex_of_file[0], -1);
}

}  // namespace
}  // namespace xparam
