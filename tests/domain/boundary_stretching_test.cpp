// Boundary stretching on consistent layouts of the bundled meshes: the stretched layout passes
// the checker, every curve is locally shortest in its two-patch region except exactly where it
// was kept off another curve, no curve gets longer, refinement stays bounded, and the result
// is deterministic. Keeping corners leaves no corner collapsed that was open before.
#include "domain/boundary_stretching.h"

#include "core/errors.h"
#include "domain/patch_merging.h"
#include "geodesic/locally_shortest.h"
#include "layout/chain_edit.h"
#include "layout/consistent_layout.h"
#include "layout/layout_fixtures.h"
#include "support/test_data.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <set>

namespace xparam {
namespace {

using test::human_layout;

// Built once per test program (the construction dominates the run time).
const Layout& spot_layout() {
  static const Layout layout = [] {
    const Mesh low = test::load(test::data_path("spot_low_resolution.obj"));
    const Mesh high = test::load(test::data_path("spot.ply"));
    const std::vector<int> ids = test::farthest_points(low, 14);
    return build_consistent_layout(low, test::handles(ids), high,
                                   test::handles(test::nearest_vertices(low, ids, high)))
        .layout;
  }();
  return layout;
}

// The documented bound of the funnel with snapping (geodesic/straighten_path.h).
constexpr double kTolerance = 2.5 * StraightenSettings{}.snap_tolerance;

// Faces of edge e's two patches; without the faces at `avoided` when given.
std::vector<bool> region_of(const Layout& layout, int side, int e,
                            const std::vector<VertexHandle>& avoided = {}) {
  const Mesh& mesh = layout.sides[side].mesh;
  std::vector<bool> mask = patch_mask(mesh, patches_of_edge(layout, e), layout.sides[side].chains[e]);
  for (const VertexHandle w : avoided) {
    for (const FaceHandle f : mesh.vf_range(w)) mask[f.idx()] = false;
  }
  return mask;
}

// The interior chain vertices of edge e that miss pi on a side lying in its full region.
std::set<int> exceptions(const Layout& layout, int side, int e) {
  const Mesh& mesh = layout.sides[side].mesh;
  const std::vector<bool> region = region_of(layout, side, e);
  const std::vector<VertexHandle>& chain = layout.sides[side].chains[e];
  std::set<int> result;
  for (std::size_t k = 1; k + 1 < chain.size(); ++k) {
    if (!is_locally_shortest(mesh, region, {chain[k - 1], chain[k], chain[k + 1]}, kTolerance))
      result.insert(chain[k].idx());
  }
  return result;
}

std::set<int> ids_of(const std::vector<VertexHandle>& vertices) {
  std::set<int> ids;
  for (const VertexHandle v : vertices) ids.insert(v.idx());
  return ids;
}

// Stretch every edge of a copy of `original` one by one, checking each curve right after it
// was stretched and the whole layout at the end.
void stretch_and_check(const Layout& original, const std::string& what) {
  Layout layout = original;
  std::array<int, 2> chain_vertices{};
  for (int side = 0; side < 2; ++side) {
    for (const auto& chain : layout.sides[side].chains)
      chain_vertices[side] += static_cast<int>(chain.size());
  }
  std::array<int, 2> added{}, avoided{}, passed_clearance{};
  std::vector<CurveStretch> curves;
  for (int e = 0; e < static_cast<int>(layout.edges.size()); ++e) {
    SCOPED_TRACE(what + ", edge " + std::to_string(e));
    std::array<int, 2> before{};
    for (int side = 0; side < 2; ++side)
      before[side] = static_cast<int>(layout.sides[side].mesh.n_vertices());
    const CurveStretch curve = stretch_edge(layout, e, {});
    curves.push_back(curve);
    for (int side = 0; side < 2; ++side) {
      const Mesh& mesh = layout.sides[side].mesh;
      const std::vector<VertexHandle>& chain = layout.sides[side].chains[e];
      EXPECT_EQ(curve.vertices_added[side], static_cast<int>(mesh.n_vertices()) - before[side]);
      EXPECT_TRUE(curve.converged[side]);
      EXPECT_LE(curve.length[side], curve.input_length[side] * (1.0 + 1e-9));
      EXPECT_NEAR(curve.length[side], chain_length(mesh, chain), 1e-12 * curve.length[side]);
      EXPECT_EQ(curve.contacts_avoided[side], static_cast<int>(curve.avoided[side].size()));
      // Locally shortest in the region the funnel had: the two patches minus the faces at
      // the vertices the curve was kept off.
      std::string why;
      EXPECT_TRUE(
          is_locally_shortest(mesh, region_of(layout, side, e, curve.avoided[side]), chain, kTolerance, &why))
          << "side " << side << ": " << why;
      // In the full region the only exceptions are clearance vertices, each one next to a
      // vertex the curve was kept off.
      const std::set<int> clearance = ids_of(curve.clearance_vertices[side]);
      const std::set<int> kept_off = ids_of(curve.avoided[side]);
      for (const int v : exceptions(layout, side, e)) {
        EXPECT_TRUE(clearance.count(v))
            << "side " << side << ": chain vertex " << v << " bends but was not kept off anything";
        bool next_to_avoided = false;
        for (const VertexHandle w : mesh.vv_range(VertexHandle(v)))
          next_to_avoided = next_to_avoided || kept_off.count(w.idx());
        EXPECT_TRUE(next_to_avoided) << "side " << side << ": clearance vertex " << v;
        ++passed_clearance[side];
      }
      added[side] += curve.vertices_added[side];
      avoided[side] += curve.contacts_avoided[side];
    }
  }
  test::expect_consistent(layout, what + " after stretching");
  // Later curves never bend earlier ones: the exceptions are still clearance vertices only.
  for (int e = 0; e < static_cast<int>(layout.edges.size()); ++e) {
    for (int side = 0; side < 2; ++side) {
      const std::set<int> clearance = ids_of(curves[e].clearance_vertices[side]);
      for (const int v : exceptions(layout, side, e)) {
        EXPECT_TRUE(clearance.count(v))
            << what << ", edge " << e << ", side " << side << ": chain vertex " << v;
      }
    }
  }
  for (int side = 0; side < 2; ++side) {
    EXPECT_LT(added[side], 3 * chain_vertices[side]) << what << ", side " << side;
    std::cout << what << ", side " << side << ": " << layout.edges.size() << " curves, "
              << chain_vertices[side] << " chain vertices before, " << added[side] << " vertices added ("
              << static_cast<double>(added[side]) / static_cast<double>(layout.edges.size())
              << " per curve), contacts avoided " << avoided[side] << ", chain vertices at clearance "
              << passed_clearance[side] << "\n";
  }
}

TEST(BoundaryStretching, HumanPairStretchedCurvesAreLocallyShortest) {
  stretch_and_check(human_layout(), "human pair");
}

TEST(BoundaryStretching, SpotPairStretchedCurvesAreLocallyShortest) {
  stretch_and_check(spot_layout(), "spot pair");
}

TEST(BoundaryStretching, StretchLayoutIsDeterministicAndSumsItsCurves) {
  Layout first = spot_layout();
  Layout second = spot_layout();
  const StretchResult a = stretch_layout(first);
  const StretchResult b = stretch_layout(second);
  ASSERT_EQ(a.curves.size(), first.edges.size());
  for (int side = 0; side < 2; ++side) {
    const Mesh& m1 = first.sides[side].mesh;
    const Mesh& m2 = second.sides[side].mesh;
    ASSERT_EQ(m1.n_vertices(), m2.n_vertices());
    ASSERT_EQ(m1.n_faces(), m2.n_faces());
    EXPECT_EQ(first.sides[side].chains, second.sides[side].chains);
    for (const VertexHandle v : m1.vertices()) ASSERT_EQ(position(m1, v), position(m2, v));
    for (const FaceHandle f : m1.faces()) ASSERT_EQ(patch_of(m1, f), patch_of(m2, f));
    int sum = 0;
    for (std::size_t e = 0; e < a.curves.size(); ++e) {
      EXPECT_EQ(a.curves[e].edge, static_cast<int>(e));
      EXPECT_EQ(a.curves[e].length[side], b.curves[e].length[side]);
      sum += a.curves[e].vertices_added[side];
    }
    EXPECT_EQ(a.vertices_added[side], sum);
    EXPECT_EQ(static_cast<int>(m1.n_vertices()),
              static_cast<int>(spot_layout().sides[side].mesh.n_vertices()) + sum);
  }
  test::expect_consistent(first, "spot stretched");
}

// A second pass finds the curves that were kept off nothing already straight: they get shorter
// by no more than the snapping allows.
TEST(BoundaryStretching, StretchingTwiceChangesAlmostNothing) {
  Layout layout = spot_layout();
  const StretchResult first = stretch_layout(layout);
  const StretchResult again = stretch_layout(layout);
  for (const CurveStretch& curve : again.curves) {
    for (int side = 0; side < 2; ++side) {
      if (first.curves[curve.edge].contacts_avoided[side] > 0) continue;
      EXPECT_NEAR(curve.length[side], curve.input_length[side], 1e-6 * curve.input_length[side])
          << "edge " << curve.edge << ", side " << side;
    }
  }
  test::expect_consistent(layout, "spot stretched twice");
}

// Corners (patch, corner index) whose surface angle is collapsed on one side (StretchSettings:
// below collapsed_angle and below collapsed_ratio times the other side's) in `after` but not in
// `before` (the same layout before stretching).
std::vector<std::pair<int, int>> newly_collapsed(const Layout& before, const Layout& after,
                                                 const StretchSettings& settings) {
  const auto collapsed = [&](const Layout& layout, int p, int i) {
    const double a = corner_surface_angles(layout, 0, p)[i];
    const double b = corner_surface_angles(layout, 1, p)[i];
    return std::min(a, b) < settings.collapsed_angle &&
           std::min(a, b) < settings.collapsed_ratio * std::max(a, b);
  };
  std::vector<std::pair<int, int>> corners;
  for (int p = 0; p < static_cast<int>(after.patches.size()); ++p) {
    for (int i = 0; i < static_cast<int>(after.patches[p].size()); ++i) {
      if (collapsed(after, p, i) && !collapsed(before, p, i)) corners.emplace_back(p, i);
    }
  }
  return corners;
}

// Plain stretching collapses corners of the bundled layouts under settings wider than the
// defaults (a corner below 0.5 rad and half the other side's; the defaults are for fingertips
// on real scans, tests/map/real_pairs_test.cpp); keeping corners leaves none collapsed that was
// open, leaves out exactly the curves it reports (their chains are the traced ones) and stays
// consistent and deterministic; keeping them at one anchor leaves out only curves of that anchor.
void expect_corners_kept(const Layout& traced, const std::string& what) {
  StretchSettings settings;
  settings.collapsed_angle = 0.5;
  settings.collapsed_ratio = 0.5;
  settings.max_keep_passes = 8;
  Layout plain = traced;
  stretch_layout(plain, settings);
  EXPECT_GE(newly_collapsed(traced, plain, settings).size(), 1u)
      << what << ": nothing for keep_corners to do";

  settings.keep_corners = true;
  Layout kept = traced;
  const StretchResult result = stretch_layout(kept, settings);
  ASSERT_LT(result.passes, settings.max_keep_passes) << what;
  EXPECT_TRUE(newly_collapsed(traced, kept, settings).empty()) << what;
  EXPECT_GE(result.unstretched.size(), 1u) << what;
  EXPECT_EQ(result.curves.size() + result.unstretched.size(), traced.edges.size()) << what;
  for (int e : result.unstretched) {
    for (int side = 0; side < 2; ++side)
      EXPECT_EQ(kept.sides[side].chains[e], traced.sides[side].chains[e]) << what;
  }
  test::expect_consistent(kept, what + " stretched keeping corners");

  // Only at one anchor: the corner plain stretching collapsed there stays open, and every curve
  // left out ends at that anchor.
  const auto [patch, corner] = newly_collapsed(traced, plain, settings).front();
  const int anchor = layout_from(traced, traced.patches[patch][corner]);
  StretchSettings at_one = settings;
  at_one.keep_corners_at = {anchor};
  Layout kept_at_one = traced;
  const StretchResult local = stretch_layout(kept_at_one, at_one);
  EXPECT_GE(local.unstretched.size(), 1u) << what;
  for (int e : local.unstretched) {
    const std::array<int, 2>& ends = traced.edges[e].anchors;
    EXPECT_TRUE(ends[0] == anchor || ends[1] == anchor) << what << ": edge " << e;
  }
  for (const auto& [p, i] : newly_collapsed(traced, kept_at_one, settings))
    EXPECT_NE(layout_from(traced, traced.patches[p][i]), anchor) << what;
  test::expect_consistent(kept_at_one, what + " stretched keeping one anchor's corners");

  Layout again = traced;
  EXPECT_EQ(stretch_layout(again, settings).unstretched, result.unstretched) << what;
  EXPECT_EQ(again.sides[1].chains, kept.sides[1].chains) << what;
}

TEST(BoundaryStretching, KeepingCornersLeavesNoCornerCollapsed) {
  expect_corners_kept(human_layout(), "human pair");
  expect_corners_kept(spot_layout(), "spot pair");
}

TEST(BoundaryStretching, RejectsBadSettingsAndEdges) {
  Layout layout = spot_layout();
  StretchSettings settings;
  settings.contact_clearance = 0.0;
  EXPECT_THROW(stretch_edge(layout, 0, settings), InputError);
  settings.contact_clearance = 0.5;
  EXPECT_THROW(stretch_edge(layout, 0, settings), InputError);
  EXPECT_THROW(stretch_edge(layout, -1), LayoutError);
  EXPECT_THROW(stretch_edge(layout, static_cast<int>(layout.edges.size())), LayoutError);
  StretchSettings no_pass;
  no_pass.keep_corners = true;
  no_pass.max_keep_passes = 0;
  EXPECT_THROW(stretch_layout(layout, no_pass), InputError);
  EXPECT_EQ(layout.sides[0].mesh.n_vertices(), spot_layout().sides[0].mesh.n_vertices());
}

}  // namespace
}  // namespace xparam
