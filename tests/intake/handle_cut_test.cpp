// The intake's handle cut (step 4) on Spot with a thin tube added over its flank (known truth in
// tests/intake/intake_damage.h): genus 1 becomes genus 0 by one cut along a loop as long as the
// tube's girth, both sides capped, the caps numbered and flagged as filled-in surface; a handle
// whose loop is over --max-handle is refused.
#include "intake/scan_intake.h"
#include "intake/scan_loader.h"

#include "core/validation.h"
#include "intake/intake_damage.h"
#include "support/expect_error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>

namespace xparam {
namespace {

using test::spot_with_handle;

TEST(HandleCut, ThinTubeIsCutAlongItsGirthAndCappedAsFilledSurface) {
  const test::HandleDamage damage = spot_with_handle();
  const TriangleSoup& damaged = damage.soup;
  const MeshReport before = validate_soup(damaged);
  ASSERT_TRUE(before.usable) << (before.errors().empty() ? "" : before.errors()[0]->message);
  ASSERT_EQ(before.genus, 1);

  const Eigen::Vector3d on_tube = damage.ring_centres[damage.ring_centres.size() / 2];
  const PreparedScan prepared = prepare_scan(damaged, {{"Tube", on_tube}, {"Far", Eigen::Vector3d(0, 0, -5)}});
  const IntakeRecord& record = prepared.record;
  ASSERT_EQ(record.handles.size(), 1u);
  const CutHandle& handle = record.handles[0];
  // The loop found around the handle is one of the tube's inner rings, the shortest (a loop over
  // the body and back through the tube is about ten times longer).
  EXPECT_NEAR(handle.length, damage.ring_perimeter, 1e-9 * damage.ring_perimeter);
  EXPECT_EQ(handle.nearest_anchor, "Tube");
  EXPECT_TRUE(record.holes.empty());
  EXPECT_EQ(record.unused_vertices, 0);
  EXPECT_EQ(record.filled_faces, handle.faces);
  EXPECT_EQ(record.filled_vertices, handle.vertices);
  EXPECT_GT(handle.area, 0.0);
  EXPECT_NE(record.describe().back().find("handle cut along a loop of length"), std::string::npos);

  // Closed, one part, genus 0.
  const MeshReport after = validate_soup(prepared.soup);
  EXPECT_TRUE(after.usable) << (after.errors().empty() ? "" : after.errors()[0]->message);
  EXPECT_EQ(after.genus, 0);
  EXPECT_EQ(after.boundary_loops, 0);
  EXPECT_EQ(after.components, 1);

  // The cut copied the vertices of one inner ring: each tube vertex of that ring is the source
  // of two prepared vertices at its position; no other file vertex is.
  std::map<int, int> copies;
  const auto file_vertices = static_cast<int>(damaged.vertices.size());
  for (std::size_t v = 0; v < prepared.vertex_source.size(); ++v) {
    const int source = prepared.vertex_source[v];
    if (source >= file_vertices) continue;
    ++copies[source];
    EXPECT_EQ(prepared.soup.vertices[v], damaged.vertices[source]);
  }
  std::vector<int> cut;
  for (const auto& [source, count] : copies)
    if (count == 2) cut.push_back(source);
  const bool cut_a_ring = std::any_of(damage.rings.begin(), damage.rings.end(), [&](std::vector<int> ring) {
    std::sort(ring.begin(), ring.end());
    return ring == cut;
  });
  EXPECT_TRUE(cut_a_ring) << cut.size() << " vertices copied";
  EXPECT_EQ(prepared.soup.vertices.size(),
            damaged.vertices.size() + cut.size() + static_cast<std::size_t>(handle.vertices));

  // The caps are the fill faces, numbered after the file's, and lie across the tube: within two
  // tube radii of the cut ring's centre.
  const auto file_faces = static_cast<int>(damaged.triangles.size());
  ASSERT_EQ(prepared.soup.triangles.size(), damaged.triangles.size() + static_cast<std::size_t>(handle.faces));
  Eigen::Vector3d cut_centre = Eigen::Vector3d::Zero();
  for (int v : cut) cut_centre += damaged.vertices[v] / static_cast<double>(cut.size());
  for (std::size_t f = 0; f < prepared.soup.triangles.size(); ++f) {
    const bool filled = prepared.face_source[f] >= file_faces;
    EXPECT_EQ(filled, f >= damaged.triangles.size()) << "face " << f;
    if (!filled) continue;
    const auto& t = prepared.soup.triangles[f];
    const Eigen::Vector3d centroid =
        (prepared.soup.vertices[t[0]] + prepared.soup.vertices[t[1]] + prepared.soup.vertices[t[2]]) / 3.0;
    EXPECT_LT((centroid - cut_centre).norm(), 2.0 * damage.tube_radius) << "cap face " << f;
  }
}

TEST(HandleCut, TheLoaderCutsAUsableGenusOneFileAndFlagsTheCapsStrictKeepsIt) {
  const test::HandleDamage damage = spot_with_handle();
  const LoadedMesh cut = load_scan_soup("spot_with_handle.obj", damage.soup, {}, {});
  ASSERT_EQ(cut.intake.handles.size(), 1u);
  EXPECT_EQ(cut.report.genus, 0);
  int flagged = 0;
  for (FaceHandle f : cut.mesh.faces()) flagged += cut.file_order.is_filled(f.idx());
  EXPECT_EQ(flagged, cut.intake.handles[0].faces);

  IntakeSettings strict;
  strict.mode = IntakeMode::Strict;
  const LoadedMesh kept = load_scan_soup("spot_with_handle.obj", damage.soup, {}, strict);
  EXPECT_FALSE(kept.intake.applied);
  EXPECT_EQ(kept.report.genus, 1);
}

TEST(HandleCut, HandleOverTheLimitIsRefusedNamingItsLengthTheAnchorAndTheFix) {
  const test::HandleDamage damage = spot_with_handle();
  IntakeSettings settings;
  settings.max_handle = 0.5 * damage.ring_perimeter;
  const Eigen::Vector3d on_tube = damage.ring_centres.front();
  const std::string message =
      test::error_message_of([&] { prepare_scan(damage.soup, {{"Tube", on_tube}}, settings); });
  EXPECT_MESSAGE_HAS(message, "spot_low_resolution.obj: handle (genus 1) with a loop of ");
  EXPECT_MESSAGE_HAS(message, "at \"Tube\" is over --max-handle ");
  EXPECT_MESSAGE_HAS(message, "close the handle");
  EXPECT_MESSAGE_HAS(message, "raise --max-handle");
  // The default limit (5% of Spot's 2.7 diagonal) takes this tube.
  EXPECT_NO_THROW(prepare_scan(damage.soup, {}));
  // --max-handle 0 (what an archive from before handle cutting ran with) cuts none.
  IntakeSettings none;
  none.max_handle = 0.0;
  none.max_handle_relative = 0.0;
  EXPECT_MESSAGE_HAS(test::error_message_of([&] { prepare_scan(damage.soup, {}, none); }),
                     "is over --max-handle 0 (no handle is cut)");
}

}  // namespace
}  // namespace xparam
