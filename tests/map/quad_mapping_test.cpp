// The cross map through merged layouts (paper section 5): quad patches parameterized onto their
// eq.-2 LPBD (or a convex fallback), mapped to each other by Wachspress coordinates. The map
// stays bijective on the human pair and is still the identity for a mesh against itself.
#include "map/cross_map.h"

#include "domain/patch_extraction.h"
#include "domain/patch_merging.h"
#include "layout/layout_check.h"
#include "layout/layout_fixtures.h"
#include "param/convex_polygon.h"
#include "support/test_data.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <numeric>

namespace xparam {
namespace {

using test::data_path;
using test::handles;

TEST(PatchPolygon, UnitSquareIsItsOwnLpbd) {
  const PatchPolygon square = patch_polygon(
      {1, 1, 1, 1}, {std::numbers::pi / 2, std::numbers::pi / 2, std::numbers::pi / 2, std::numbers::pi / 2},
      {1, 1, 1, 1});
  EXPECT_FALSE(square.fallback);
  ASSERT_EQ(square.corners.size(), 4u);
  const Eigen::Vector2d expected[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int i = 0; i < 4; ++i) EXPECT_LT((square.corners[i] - expected[i]).norm(), 1e-12) << i;
}

TEST(PatchPolygon, ConcaveOrDegenerateLpbdsFallBackToConvexPolygons) {
  // Surface angles of a dart: eq. 2 keeps the reflex corner, which no mean-value map can fill.
  const std::vector<double> dart = {0.4, 0.4, 0.4, 2 * std::numbers::pi - 1.2};
  const PatchPolygon concave = patch_polygon({1, 1, 1, 1}, dart, {1, 1, 1, 1});
  ASSERT_TRUE(concave.lpbd.valid);
  EXPECT_FALSE(concave.lpbd.convex);
  EXPECT_TRUE(concave.fallback);
  EXPECT_TRUE(is_strictly_convex(concave.corners));
  // Curves that cannot close (5 > 1 + 1 + 1) but chords that can: the chords' LPBD, with the
  // chords as its sides.
  const std::vector<double> chords = {1, 1, 1, 1.5};
  const PatchPolygon open = patch_polygon(
      {1, 1, 1, 5}, {std::numbers::pi / 2, std::numbers::pi / 2, std::numbers::pi / 2, std::numbers::pi / 2},
      chords);
  EXPECT_FALSE(open.lpbd.valid);
  EXPECT_TRUE(open.fallback);
  ASSERT_TRUE(is_strictly_convex(open.corners));
  for (int i = 0; i < 4; ++i)
    EXPECT_NEAR((open.corners[(i + 1) % 4] - open.corners[i]).norm(), chords[i], 1e-9);
  // Neither closes: corners on a circle, still strictly convex.
  const PatchPolygon circle = patch_polygon({1, 1, 1, 5}, dart, {1, 1, 1, 3});
  EXPECT_TRUE(circle.fallback);
  EXPECT_TRUE(is_strictly_convex(circle.corners));
  // A degenerate triangle falls back to its chord triangle.
  const PatchPolygon flat = patch_polygon({1, 1, 2}, {0, 0, 0}, {1, 1, 1});
  EXPECT_TRUE(flat.fallback);
  EXPECT_NEAR((flat.corners[1] - flat.corners[0]).norm(), 1.0, 1e-12);
}

// Every edge whose two patches are triangles no earlier chosen edge touches (edge order): as
// many quads as the layout allows, convex LPBD or not.
std::vector<int> maximal_merge(const Layout& layout) {
  std::vector<int> owner(2 * layout.edges.size(), -1);
  for (int p = 0; p < static_cast<int>(layout.patches.size()); ++p) {
    for (int h : layout.patches[p]) owner[h] = p;
  }
  std::vector<char> taken(layout.patches.size(), 0);
  std::vector<int> edges;
  for (int e = 0; e < static_cast<int>(layout.edges.size()); ++e) {
    const int left = owner[2 * e], right = owner[2 * e + 1];
    if (taken[left] || taken[right]) continue;
    taken[left] = taken[right] = 1;
    edges.push_back(e);
  }
  return edges;
}

Layout merged_layout(const Mesh& source, const Mesh& target, const std::vector<int>& anchors) {
  Layout layout = build_consistent_layout(source, handles(anchors), target, handles(anchors)).layout;
  const std::size_t triangles = layout.patches.size();
  merge_patches(layout, maximal_merge(layout));
  LayoutCheckSettings settings;
  settings.triangles = false;
  EXPECT_TRUE(check_layout(layout, settings).consistent());
  EXPECT_LT(layout.patches.size(), triangles * 3 / 4) << "too few merges to test quads";
  return layout;
}

struct Humans {
  Mesh man = test::load(data_path("human_man.obj"));
  Mesh woman = test::load(data_path("human_woman.obj"));
  std::vector<int> anchors = test::farthest_points(man, 24, 412);
};

const Humans& humans() {
  static const Humans data;
  return data;
}

TEST(QuadMapping, MergedHumanPairMapsEveryVertexBijectively) {
  const Humans& h = humans();
  const Layout layout = merged_layout(h.man, h.woman, h.anchors);
  const CrossMap map(layout, {&h.man, &h.woman});
  EXPECT_EQ(map.inverted_triangles()[0], 0);
  EXPECT_EQ(map.inverted_triangles()[1], 0);
  double worst_clamp = 0.0;
  for (int v = 0; v < static_cast<int>(h.man.n_vertices()); ++v) {
    const MappedPoint image = map.map_vertex(v);
    ASSERT_GE(image.on_input.face, 0) << v;
    ASSERT_LT(image.on_input.face, static_cast<int>(h.woman.n_faces())) << v;
    ASSERT_TRUE(image.position.allFinite()) << v;
    EXPECT_GE(image.on_input.bary.minCoeff(), -1e-9) << v;
    worst_clamp = std::max(worst_clamp, image.clamp_distance);
  }
  EXPECT_LT(worst_clamp, 1e-6);
  // Anchors land on the target's anchors (same vertex ids on both bodies).
  for (int id : h.anchors) {
    EXPECT_LT((map.map_vertex(id).position - position(h.woman, VertexHandle(id))).norm(), 1e-9) << id;
  }
  std::printf("man->woman merged: %zu patches (%d quads), fallback polygons %d/%d\n", layout.patches.size(),
              static_cast<int>(std::count_if(layout.patches.begin(), layout.patches.end(),
                                             [](const auto& walk) { return walk.size() == 4; })),
              map.fallback_polygons()[0], map.fallback_polygons()[1]);
}

TEST(QuadMapping, MergedMeshAgainstItselfIsTheIdentity) {
  const Humans& h = humans();
  const Layout layout = merged_layout(h.man, h.man, h.anchors);
  const CrossMap map(layout, {&h.man, &h.man});
  EXPECT_EQ(map.inverted_triangles()[0], 0);
  double worst = 0.0;
  for (int v = 0; v < static_cast<int>(h.man.n_vertices()); ++v) {
    worst = std::max(worst, (map.map_vertex(v).position - position(h.man, VertexHandle(v))).norm());
  }
  EXPECT_LT(worst, 1e-9);
}

TEST(QuadMapping, UndoingEveryPatchGivesThePapersMapAndRestoreTakesItBack) {
  const Humans& h = humans();
  const Layout layout = merged_layout(h.man, h.woman, h.anchors);
  CrossMap relaxed(layout, {&h.man, &h.woman});
  CrossMapSettings paper;
  paper.relax = false;
  const CrossMap unrelaxed(layout, {&h.man, &h.woman}, paper);
  ASSERT_GE(relaxed.relaxation().patches, 1);
  std::vector<int> every_patch(layout.patches.size());
  std::iota(every_patch.begin(), every_patch.end(), 0);
  const int n_vertices = static_cast<int>(h.man.n_vertices());
  std::vector<Eigen::Vector3d> before(n_vertices);
  for (int v = 0; v < n_vertices; ++v) before[v] = relaxed.map_vertex(v).position;

  const auto saved = relaxed.save();
  // Two steps: the patch maps' relaxation and gluing, then the squeezed parameterizations'.
  relaxed.undo_relaxation(every_patch);
  relaxed.undo_relaxation(every_patch);
  double from_paper = 0.0;
  double moved = 0.0;
  for (int v = 0; v < n_vertices; ++v) {
    const Eigen::Vector3d undone = relaxed.map_vertex(v).position;
    from_paper = std::max(from_paper, (undone - unrelaxed.map_vertex(v).position).norm());
    moved = std::max(moved, (undone - before[v]).norm());
  }
  EXPECT_LT(from_paper, 1e-12);
  EXPECT_GT(moved, 1e-3);

  relaxed.restore(*saved);
  for (int v = 0; v < n_vertices; ++v) EXPECT_EQ(relaxed.map_vertex(v).position, before[v]) << v;
}

}  // namespace
}  // namespace xparam
