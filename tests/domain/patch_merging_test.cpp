// Patch merging (paper section 5): surface angles at the patch corners, hand-computed on a
// stretched octahedron and summed around every anchor of real layouts; merging keeps the
// layout consistent, makes quads a-r-b-l whose corner angles are those of the two triangles,
// and refuses what cannot be merged without touching the layout.
#include "domain/patch_merging.h"

#include "core/errors.h"
#include "layout/layout_check.h"
#include "layout/layout_fixtures.h"
#include "support/test_data.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace xparam {
namespace {

using test::data_path;
using test::handles;

constexpr int kDivisions = 4;
const Eigen::Vector3d kCorner[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
enum { kPx, kNx, kPy, kNy, kPz, kNz };
const std::vector<std::array<int, 2>> kOctahedronEdges = {{kPx, kPy}, {kPx, kNy}, {kPx, kPz}, {kPx, kNz},
                                                          {kNx, kPy}, {kNx, kNy}, {kNx, kPz}, {kNx, kNz},
                                                          {kPy, kPz}, {kPy, kNz}, {kNy, kPz}, {kNy, kNz}};

// A layout on the subdivided octahedron with anchors at the given corners (anchor k at corner
// corners[k]) and straight lattice chains along the octahedron edges `edges` (anchor ids);
// afterwards every z coordinate is multiplied by `z_scale` (the faces stay planar).
Layout octahedron_layout(const std::vector<int>& corners, const std::vector<std::array<int, 2>>& edges,
                         double z_scale) {
  Layout layout;
  layout.n_anchors = static_cast<int>(corners.size());
  for (const auto& e : edges) layout.edges.push_back({e});
  for (LayoutSide& s : layout.sides) {
    s.mesh = test::subdivided_octahedron(kDivisions);
    for (int c : corners) s.anchor_vertices.push_back(VertexHandle(c));
    for (const auto& e : edges) {
      const Eigen::Vector3d a = kCorner[corners[e[0]]], b = kCorner[corners[e[1]]];
      std::vector<VertexHandle> chain;
      for (int t = 0; t <= kDivisions; ++t) chain.push_back(test::vertex_at(s.mesh, a + (b - a) * t / kDivisions));
      s.chains.push_back(chain);
    }
    for (VertexHandle v : s.mesh.vertices()) {
      Eigen::Vector3d p = position(s.mesh, v);
      p.z() *= z_scale;
      s.mesh.set_point(v, to_point(p));
    }
  }
  std::vector<std::vector<int>> rotations;
  for (int a = 0; a < layout.n_anchors; ++a) rotations.push_back(mesh_rotation(layout, 0, a));
  layout.patches = faces_of_rotation(layout, rotations);
  assign_patches(layout);
  return layout;
}

Layout stretched_octahedron() { return octahedron_layout({0, 1, 2, 3, 4, 5}, kOctahedronEdges, 2.0); }

// Anchors of a patch's corners in walk order.
std::vector<int> corner_anchors(const Layout& layout, int p) {
  std::vector<int> anchors;
  for (int h : layout.patches[p]) anchors.push_back(layout_from(layout, h));
  return anchors;
}

// The patch whose corners are exactly `anchors` in this order from its walk's start; -1 if none.
int patch_with_corners(const Layout& layout, const std::vector<int>& anchors) {
  for (int p = 0; p < static_cast<int>(layout.patches.size()); ++p) {
    if (corner_anchors(layout, p) == anchors) return p;
  }
  return -1;
}

// The patch with the given corner anchors in any rotation.
int patch_with_anchor_set(const Layout& layout, std::set<int> anchors) {
  for (int p = 0; p < static_cast<int>(layout.patches.size()); ++p) {
    const std::vector<int> corners = corner_anchors(layout, p);
    if (std::set<int>(corners.begin(), corners.end()) == anchors && corners.size() == anchors.size()) return p;
  }
  return -1;
}

void expect_consistent_merged(const Layout& layout, const std::string& what) {
  LayoutCheckSettings settings;
  settings.triangles = false;
  const LayoutCheck check = check_layout(layout, settings);
  std::string all;
  for (const auto& line : check.violations) all += "\n  " + line;
  EXPECT_TRUE(check.consistent()) << what << ":" << all;
  const int n = layout.n_anchors;
  EXPECT_EQ(n - static_cast<int>(layout.edges.size()) + static_cast<int>(layout.patches.size()), 2) << what;
}

TEST(CornerSurfaceAngles, HandComputedOnAStretchedOctahedron) {
  const Layout layout = stretched_octahedron();
  ASSERT_EQ(layout.patches.size(), 8u);
  // Face (+x, +y, +z) with +z at height 2: at +x the sides (-1, 1, 0) and (-1, 0, 2) meet at
  // acos(1 / sqrt(10)); at +z the sides (1, 0, -2) and (0, 1, -2) at acos(4 / 5). Every octant
  // is congruent, with the z corner at +-z. Each wedge sums the angles of several lattice faces.
  const double at_equator = std::acos(1.0 / std::sqrt(10.0));
  const double at_pole = std::acos(0.8);
  for (int side = 0; side < 2; ++side) {
    for (int p = 0; p < 8; ++p) {
      const std::vector<double> angles = corner_surface_angles(layout, side, p);
      const std::vector<int> anchors = corner_anchors(layout, p);
      ASSERT_EQ(angles.size(), 3u);
      for (int i = 0; i < 3; ++i) {
        const bool pole = anchors[i] == kPz || anchors[i] == kNz;
        EXPECT_NEAR(angles[i], pole ? at_pole : at_equator, 1e-13) << "patch " << p << " corner " << i;
      }
    }
  }
}

TEST(CornerSurfaceAngles, AFoldedWedgeSumsItsFacesOnBothSidesOfTheFold) {
  // Three anchors: the octant (+x, +y, +z) and the rest of the sphere as the other patch. The
  // big patch's corner at +z spans the three other octants' corners there: 3 acos(4/5).
  const Layout layout = octahedron_layout({kPx, kPy, kPz}, {{0, 1}, {0, 2}, {1, 2}}, 2.0);
  ASSERT_EQ(layout.patches.size(), 2u);
  const double at_equator = std::acos(1.0 / std::sqrt(10.0));
  const double at_pole = std::acos(0.8);
  std::vector<int> faces(2, 0);
  for (FaceHandle f : layout.sides[1].mesh.faces()) ++faces[patch_of(layout.sides[1].mesh, f)];
  const int big = faces[0] > faces[1] ? 0 : 1;
  EXPECT_EQ(faces[1 - big], kDivisions * kDivisions);
  const std::vector<double> angles = corner_surface_angles(layout, 1, big);
  const std::vector<int> anchors = corner_anchors(layout, big);
  for (int i = 0; i < 3; ++i) {
    // At +x the rest of the sphere holds three octant corners (all at_equator).
    EXPECT_NEAR(angles[i], 3.0 * (anchors[i] == 2 ? at_pole : at_equator), 1e-12) << "corner " << i;
  }
}

TEST(MergePatches, OctahedronEdgeBecomesTheQuadARBL) {
  Layout layout = stretched_octahedron();
  // Edge 0 runs +x -> +y; the octant (+x, +y, +z) is on its left (l = +z), (+y, +x, -z) on its
  // right (r = -z).
  merge_patches(layout, {0});
  expect_consistent_merged(layout, "octahedron, edge 0 merged");
  ASSERT_EQ(layout.edges.size(), 11u);
  ASSERT_EQ(layout.patches.size(), 7u);
  for (int e = 0; e < 11; ++e) {
    EXPECT_EQ(layout.edges[e].anchors, kOctahedronEdges[e + 1]) << "edges keep their old order";
  }
  const int quad = patch_with_corners(layout, {kPx, kNz, kPy, kPz});
  ASSERT_GE(quad, 0) << "no patch walks +x, -z, +y, +z from its start";
  std::vector<int> faces(7, 0);
  for (FaceHandle f : layout.sides[1].mesh.faces()) ++faces[patch_of(layout.sides[1].mesh, f)];
  for (int p = 0; p < 7; ++p) EXPECT_EQ(faces[p], (p == quad ? 2 : 1) * kDivisions * kDivisions) << p;
  const double at_equator = std::acos(1.0 / std::sqrt(10.0));
  const double at_pole = std::acos(0.8);
  for (int side = 0; side < 2; ++side) {
    const std::vector<double> angles = corner_surface_angles(layout, side, quad);
    ASSERT_EQ(angles.size(), 4u);
    EXPECT_NEAR(angles[0], 2.0 * at_equator, 1e-13);
    EXPECT_NEAR(angles[1], at_pole, 1e-13);
    EXPECT_NEAR(angles[2], 2.0 * at_equator, 1e-13);
    EXPECT_NEAR(angles[3], at_pole, 1e-13);
  }
  // The removed chain's interior vertices are plain vertices inside the quad now.
  const Layout before = stretched_octahedron();
  for (std::size_t i = 1; i + 1 < before.sides[0].chains[0].size(); ++i) {
    for (FaceHandle f : layout.sides[0].mesh.vf_range(before.sides[0].chains[0][i])) {
      EXPECT_EQ(patch_of(layout.sides[0].mesh, f), quad);
    }
  }
}

TEST(MergePatches, RefusesWhatCannotBeMergedAndLeavesTheLayoutAlone) {
  Layout layout = stretched_octahedron();
  const auto patches = layout.patches;
  auto refused = [&](const std::vector<int>& edges, const std::string& words) {
    try {
      merge_patches(layout, edges);
      ADD_FAILURE() << "merged " << edges.size() << " edges";
    } catch (const LayoutError& error) {
      EXPECT_NE(std::string(error.what()).find(words), std::string::npos) << error.what();
    }
    EXPECT_EQ(layout.patches, patches);
    EXPECT_EQ(layout.edges.size(), 12u);
    EXPECT_EQ(layout.sides[0].chains.size(), 12u);
    test::expect_consistent(layout, "after a refused merge");
  };
  refused({12}, "layout edge 12 does not exist");
  refused({-1}, "does not exist");
  refused({0, 0}, "layout edge 0 is given twice");
  // Edges 0 (+x, +y) and 2 (+x, +z) both border the octant (+x, +y, +z).
  refused({0, 2}, "layout edge 2 borders patch");
  refused({5, 0, 2}, "layout edge 2 borders patch");

  // A quad's edges cannot be merged again: edge 8 (+y, +z) is now edge 7, between the quad and
  // the octant (-x, +y, +z).
  merge_patches(layout, {0});
  try {
    merge_patches(layout, {7});
    ADD_FAILURE() << "merged an edge of a quad";
  } catch (const LayoutError& error) {
    EXPECT_NE(std::string(error.what()).find("is not between two triangles"), std::string::npos) << error.what();
  }
  expect_consistent_merged(layout, "after refusing a quad's edge");

  // Two anchors with the same third anchor on both sides (a sphere of two triangles).
  Layout two = octahedron_layout({kPx, kPy, kPz}, {{0, 1}, {0, 2}, {1, 2}}, 1.0);
  try {
    merge_patches(two, {0});
    ADD_FAILURE() << "merged the two triangles of a three-anchor sphere";
  } catch (const LayoutError& error) {
    EXPECT_NE(std::string(error.what()).find("same third anchor 2"), std::string::npos) << error.what();
  }
}

TEST(MergedLayoutCheck, RefusesAPolygonThroughAnAnchorTwice) {
  // A spanning tree of the octahedron's corners: one face whose walk passes +x four times. It
  // has the counts of a sphere but is no polygon domain.
  const Layout tree = octahedron_layout({0, 1, 2, 3, 4, 5},
                                        {{kPx, kPy}, {kPx, kNy}, {kPx, kPz}, {kPx, kNz}, {kNx, kPy}}, 1.0);
  ASSERT_EQ(tree.patches.size(), 1u);
  LayoutCheckSettings settings;
  settings.triangles = false;
  const LayoutCheck check = check_layout(tree, settings);
  ASSERT_FALSE(check.consistent());
  EXPECT_NE(check.violations.front().find("patch 0 visits an anchor twice"), std::string::npos)
      << check.violations.front();
}

// Real layouts: the humans (different triangulations of one body) and Spot at two resolutions.
struct RealLayout {
  std::string name;
  Layout layout;
};

const std::vector<RealLayout>& real_layouts() {
  static const std::vector<RealLayout> layouts = [] {
    std::vector<RealLayout> result;
    const Mesh man = test::load(data_path("human_man.obj"));
    const Mesh woman = test::load(data_path("human_woman.obj"));
    const std::vector<int> body = test::farthest_points(man, 20, 412);
    result.push_back({"man/woman", build_consistent_layout(man, handles(body), woman, handles(body)).layout});
    const Mesh low = test::load(data_path("spot_low_resolution.obj"));
    const Mesh high = test::load(data_path("spot.ply"));
    const std::vector<int> cow = test::farthest_points(low, 16);
    result.push_back({"spot low/high",
                      build_consistent_layout(low, handles(cow), high,
                                              handles(test::nearest_vertices(low, cow, high)))
                          .layout});
    return result;
  }();
  return layouts;
}

// Every edge whose two patches are triangles no earlier chosen edge touches (edge order).
std::vector<int> maximal_merge(const Layout& layout) {
  std::vector<int> owner(2 * layout.edges.size(), -1);
  for (int p = 0; p < static_cast<int>(layout.patches.size()); ++p) {
    for (int h : layout.patches[p]) owner[h] = p;
  }
  std::vector<char> taken(layout.patches.size(), 0);
  std::vector<int> edges;
  for (int e = 0; e < static_cast<int>(layout.edges.size()); ++e) {
    const int left = owner[2 * e], right = owner[2 * e + 1];
    if (taken[left] || taken[right] || layout.patches[left].size() != 3 || layout.patches[right].size() != 3) continue;
    taken[left] = taken[right] = 1;
    edges.push_back(e);
  }
  return edges;
}

// Around every anchor the corners of all patches there fill its whole fan of mesh faces.
void expect_angles_fill_every_fan(const Layout& layout, const std::string& what) {
  for (int side = 0; side < 2; ++side) {
    const Mesh& mesh = layout.sides[side].mesh;
    std::vector<double> corners(layout.n_anchors, 0.0);
    for (int p = 0; p < static_cast<int>(layout.patches.size()); ++p) {
      const std::vector<double> angles = corner_surface_angles(layout, side, p);
      ASSERT_EQ(angles.size(), layout.patches[p].size());
      for (std::size_t i = 0; i < angles.size(); ++i) {
        EXPECT_GT(angles[i], 0.0) << what << " side " << side << " patch " << p;
        corners[layout_from(layout, layout.patches[p][i])] += angles[i];
      }
    }
    for (int a = 0; a < layout.n_anchors; ++a) {
      double fan = 0.0;
      for (HalfedgeHandle h : mesh.voh_range(layout.sides[side].anchor_vertices[a])) {
        const Eigen::Vector3d apex = position(mesh, mesh.from_vertex_handle(h));
        const Eigen::Vector3d u = position(mesh, mesh.to_vertex_handle(h)) - apex;
        const Eigen::Vector3d w = position(mesh, mesh.to_vertex_handle(mesh.next_halfedge_handle(h))) - apex;
        fan += std::acos(std::clamp(u.normalized().dot(w.normalized()), -1.0, 1.0));
      }
      EXPECT_NEAR(corners[a], fan, 1e-9) << what << " side " << side << " anchor " << a;
    }
  }
}

TEST(CornerSurfaceAngles, CornersAroundEveryAnchorFillItsFanOnRealLayouts) {
  for (const RealLayout& real : real_layouts()) {
    expect_angles_fill_every_fan(real.layout, real.name);
    Layout merged = real.layout;
    merge_patches(merged, maximal_merge(merged));
    expect_angles_fill_every_fan(merged, real.name + " merged");
  }
}

TEST(MergePatches, RealLayoutsStayConsistentAndQuadsKeepTheirTrianglesAngles) {
  for (const RealLayout& real : real_layouts()) {
    const Layout& before = real.layout;
    const std::vector<int> edges = maximal_merge(before);
    ASSERT_GE(edges.size(), before.patches.size() / 4) << real.name;
    // Expected quad corners a, r, b, l and their angles from the two triangles, per side.
    struct Expected {
      std::vector<int> corners;
      std::array<std::vector<double>, 2> angles;
    };
    std::vector<Expected> expected;
    for (int e : edges) {
      int left = -1, right = -1;
      for (int p = 0; p < static_cast<int>(before.patches.size()); ++p) {
        for (int h : before.patches[p]) {
          if (h == 2 * e) left = p;
          if (h == 2 * e + 1) right = p;
        }
      }
      const int a = before.edges[e].anchors[0], b = before.edges[e].anchors[1];
      Expected quad;
      std::map<int, std::array<double, 2>> angle_at;  // anchor -> angle per side
      for (int side = 0; side < 2; ++side) {
        for (int p : {left, right}) {
          const std::vector<double> angles = corner_surface_angles(before, side, p);
          const std::vector<int> anchors = corner_anchors(before, p);
          for (int i = 0; i < 3; ++i) angle_at[anchors[i]][side] += angles[i];
        }
      }
      int l = -1, r = -1;
      for (int x : corner_anchors(before, left)) l = (x != a && x != b) ? x : l;
      for (int x : corner_anchors(before, right)) r = (x != a && x != b) ? x : r;
      quad.corners = {a, r, b, l};
      for (int side = 0; side < 2; ++side) {
        for (int x : quad.corners) quad.angles[side].push_back(angle_at[x][side]);
      }
      expected.push_back(quad);
    }

    Layout merged = before;
    merge_patches(merged, edges);
    const std::string what = real.name + ", " + std::to_string(edges.size()) + " merges";
    expect_consistent_merged(merged, what);
    EXPECT_EQ(merged.edges.size(), before.edges.size() - edges.size()) << what;
    EXPECT_EQ(merged.patches.size(), before.patches.size() - edges.size()) << what;
    for (int side = 0; side < 2; ++side) EXPECT_EQ(merged.sides[side].mesh.n_vertices(), before.sides[side].mesh.n_vertices());
    int quads = 0;
    for (const auto& walk : merged.patches) quads += walk.size() == 4;
    EXPECT_EQ(quads, static_cast<int>(edges.size())) << what;
    for (const Expected& quad : expected) {
      const int p = patch_with_corners(merged, quad.corners);
      ASSERT_GE(p, 0) << what << ": no quad walks " << quad.corners[0] << " " << quad.corners[1] << " "
                      << quad.corners[2] << " " << quad.corners[3];
      for (int side = 0; side < 2; ++side) {
        const std::vector<double> angles = corner_surface_angles(merged, side, p);
        for (int i = 0; i < 4; ++i) EXPECT_NEAR(angles[i], quad.angles[side][i], 1e-12) << what << " corner " << i;
      }
    }
    // Surviving triangles keep their corners (renumbered halfedges, same anchors).
    for (int p = 0; p < static_cast<int>(before.patches.size()); ++p) {
      const std::vector<int> anchors = corner_anchors(before, p);
      bool merged_away = false;
      for (int e : edges) {
        for (int h : before.patches[p]) merged_away = merged_away || h / 2 == e;
      }
      if (!merged_away) {
        EXPECT_GE(patch_with_anchor_set(merged, {anchors.begin(), anchors.end()}), 0) << what << " patch " << p;
      }
    }
  }
}

}  // namespace
}  // namespace xparam
