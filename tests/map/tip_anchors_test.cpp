// Helper anchors behind tips: on a mesh laid out against itself each anchor's helper is the same
// point on both sides, a vertex of the anchor's widest corner within reach of the anchor; names
// stay apart from the anchors'; bad arguments are refused. Cat/horse, where the helpers unfold
// the map, is in real_pairs_test.cpp.
#include "map/tip_anchors.h"

#include "core/errors.h"
#include "domain/patch_extraction.h"
#include "domain/patch_merging.h"
#include "layout/layout_fixtures.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

namespace xparam {
namespace {

// Every anchor as a tip (the corner shares do not matter to tip_anchors).
std::vector<CornerMismatch> every_anchor(const test::SelfLayout& self) {
  std::vector<CornerMismatch> tips;
  for (int k = 0; k < self.built.layout.n_anchors; ++k) tips.push_back({k, self.names[k], {}, {}});
  return tips;
}

// The patch of anchor k's widest corner on side 0.
int widest_patch(const Layout& layout, int k) {
  const CornerAngles angles = corner_angles(layout);
  int widest = -1;
  double widest_angle = -1.0;
  for (std::size_t p = 0; p < layout.patches.size(); ++p) {
    for (std::size_t i = 0; i < layout.patches[p].size(); ++i) {
      if (layout_from(layout, layout.patches[p][i]) == k && angles[0][p][i] > widest_angle) {
        widest_angle = angles[0][p][i];
        widest = static_cast<int>(p);
      }
    }
  }
  return widest;
}

// Vertices of patch p's faces on side 0 within `reach` (3-D) of anchor k that lie on none of
// the patch's curves. Edge paths are no shorter, so a corner without such vertices has no room
// for a helper.
int vertices_off_the_curves(const Layout& layout, int p, int k, double reach) {
  const Mesh& mesh = layout.sides[0].mesh;
  const Eigen::Vector3d tip = position(mesh, layout.sides[0].anchor_vertices[k]);
  std::vector<bool> on_curve(mesh.n_vertices(), false);
  for (const int h : layout.patches[p]) {
    for (const VertexHandle v : layout.sides[0].chains[layout_edge_of(h)]) on_curve[v.idx()] = true;
  }
  std::vector<bool> counted(mesh.n_vertices(), false);
  int off = 0;
  for (const FaceHandle f : mesh.faces()) {
    if (patch_of(mesh, f) != p) continue;
    for (const VertexHandle v : mesh.fv_range(f)) {
      if (!on_curve[v.idx()] && !counted[v.idx()] && (position(mesh, v) - tip).norm() <= reach) {
        counted[v.idx()] = true;
        ++off;
      }
    }
  }
  return off;
}

// The patches of the faces around the refined vertex at `point` (none when no vertex is there).
std::vector<int> patches_at(const Mesh& refined, const Eigen::Vector3d& point) {
  std::vector<int> patches;
  for (const VertexHandle v : refined.vertices()) {
    if ((position(refined, v) - point).norm() > 1e-12) continue;
    for (const FaceHandle f : refined.vf_range(v)) patches.push_back(patch_of(refined, f));
  }
  return patches;
}

TEST(TipAnchors, AMeshAgainstItselfGetsOneHelperPerTipWithRoomInItsWidestCorner) {
  const test::SelfLayout self;
  const Layout& layout = self.built.layout;
  constexpr double kReach = 1.0;
  const std::vector<TipAnchor> helpers =
      tip_anchors(layout, {&self.mesh, &self.mesh}, self.names, every_anchor(self), kReach);
  std::size_t next = 0;
  for (int k = 0; k < layout.n_anchors; ++k) {
    SCOPED_TRACE(self.names[k]);
    // Within reach: no farther in 3-D than the reach along the shortest curve leaving the tip.
    double shortest = std::numeric_limits<double>::infinity();
    for (std::size_t e = 0; e < layout.edges.size(); ++e) {
      if (layout.edges[e].anchors[0] == k || layout.edges[e].anchors[1] == k)
        shortest = std::min(shortest, chain_length(layout, 0, static_cast<int>(e)));
    }
    if (next == helpers.size() || helpers[next].tip != self.names[k]) {
      EXPECT_EQ(vertices_off_the_curves(layout, widest_patch(layout, k), k, kReach * shortest), 0);
      continue;
    }
    const TipAnchor& helper = helpers[next++];
    EXPECT_EQ(helper.specs[0].name, self.names[k] + " (behind)");
    EXPECT_EQ(helper.specs[1].name, helper.specs[0].name);
    const SurfacePoint& on_template = std::get<SurfacePoint>(helper.specs[0].location);
    const SurfacePoint& on_target = std::get<SurfacePoint>(helper.specs[1].location);
    EXPECT_EQ(on_template.face, on_target.face);
    EXPECT_LT((on_template.bary - on_target.bary).norm(), 1e-12);

    const Eigen::Vector3d point = position(self.mesh, on_template);
    const double distance = (point - position(self.mesh, self.anchors[k])).norm();
    EXPECT_GT(distance, 0.0);
    EXPECT_LE(distance, kReach * shortest + 1e-12);

    // A vertex of the refined mesh with a face in the widest corner's patch.
    const std::vector<int> around = patches_at(layout.sides[0].mesh, point);
    ASSERT_FALSE(around.empty());
    EXPECT_NE(std::find(around.begin(), around.end(), widest_patch(layout, k)), around.end());
  }
  EXPECT_EQ(next, helpers.size());
  EXPECT_GE(helpers.size(), self.names.size() * 3 / 4);  // measured 27 of 29
}

TEST(TipAnchors, HelperNamesStayApartFromTheAnchors) {
  test::SelfLayout self;
  self.names[1] = self.names[0] + " (behind)";
  const std::vector<TipAnchor> helpers =
      tip_anchors(self.built.layout, {&self.mesh, &self.mesh}, self.names, {{0, self.names[0], {}, {}}}, 0.3);
  ASSERT_EQ(helpers.size(), 1u);
  EXPECT_EQ(helpers[0].specs[0].name, self.names[0] + " (behind)'");
}

TEST(TipAnchors, RefusesNamesThatDoNotMatchTheAnchors) {
  const test::SelfLayout self;
  std::vector<std::string> fewer = self.names;
  fewer.pop_back();
  EXPECT_THROW(tip_anchors(self.built.layout, {&self.mesh, &self.mesh}, fewer, every_anchor(self), 0.3),
               ParamError);
}

}  // namespace
}  // namespace xparam
