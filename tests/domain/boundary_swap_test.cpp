// The boundary swapping operator on stretched layouts of the bundled meshes: random swap
// sequences keep the layout consistent, try_swap (on the quad's workspace) measures what
// apply_swap (on the full layout) makes, swapping twice restores the edge, refusals leave the
// layout unchanged.
#include "domain/boundary_swap.h"

#include "core/errors.h"
#include "domain/layout_measures.h"
#include "domain/stretched_layouts.h"
#include "geodesic/locally_shortest.h"
#include "layout/chain_edit.h"
#include "layout/consistent_layout.h"
#include "support/test_data.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <chrono>
#include <iostream>
#include <random>

namespace xparam {
namespace {

// Everything a swap may change, to prove a refused swap changed nothing.
void expect_same(const Layout& a, const Layout& b) {
  ASSERT_EQ(a.edges.size(), b.edges.size());
  for (std::size_t e = 0; e < a.edges.size(); ++e) EXPECT_EQ(a.edges[e].anchors, b.edges[e].anchors);
  EXPECT_EQ(a.patches, b.patches);
  for (int side = 0; side < 2; ++side) {
    EXPECT_EQ(a.sides[side].mesh.n_vertices(), b.sides[side].mesh.n_vertices());
    EXPECT_EQ(a.sides[side].chains, b.sides[side].chains);
  }
}

// What apply_swap produced for the trial's quad: the new chain's length and the two patches'
// areas, per side, within test::kTrialTolerance of the trial's.
void expect_trial_matches(const Layout& layout, const SwapTrial& trial) {
  const int e = trial.quad.edge;
  for (int side = 0; side < 2; ++side) {
    const Mesh& mesh = layout.sides[side].mesh;
    EXPECT_NEAR(trial.length[side], chain_length(mesh, layout.sides[side].chains[e]),
                test::kTrialTolerance * trial.length[side]);
    std::array<double, 2> area{};
    for (const FaceHandle f : mesh.faces()) {
      const int p = patch_of(mesh, f);
      if (p != trial.quad.left_patch && p != trial.quad.right_patch) continue;
      auto corner = mesh.cfv_begin(f);
      const Eigen::Vector3d x = position(mesh, *corner++);
      const Eigen::Vector3d y = position(mesh, *corner++);
      const Eigen::Vector3d z = position(mesh, *corner);
      area[p == trial.quad.left_patch ? 0 : 1] += 0.5 * (y - x).cross(z - x).norm();
    }
    for (int k = 0; k < 2; ++k) EXPECT_NEAR(trial.area[side][k], area[k], test::kTrialTolerance * area[k]);
  }
}

// `count` swaps of random edges (fixed seed); refused ones are checked to change nothing. After
// each swap, the patch areas measured again for the quad's patches alone (as the base-domain
// optimization keeps them) equal those of the whole side to the bit.
void random_swaps(const Layout& original, unsigned seed, int count, const std::string& what) {
  Layout layout = original;
  std::array<std::vector<double>, 2> areas = {patch_areas(layout, 0), patch_areas(layout, 1)};
  std::mt19937 random(seed);
  int applied = 0, refused = 0;
  double seconds = 0.0;
  int tried = 0;
  for (int step = 0; step < count; ++step) {
    const int e = static_cast<int>(random() % layout.edges.size());
    SCOPED_TRACE(what + ", step " + std::to_string(step) + ", edge " + std::to_string(e));
    const auto start = std::chrono::steady_clock::now();
    const SwapTrial trial = try_swap(layout, e);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ++tried;
    if (!trial.possible) {
      EXPECT_FALSE(trial.refusal.empty());
      const Layout before = layout;
      EXPECT_THROW(apply_swap(layout, e), LayoutError);
      expect_same(layout, before);
      ++refused;
      continue;
    }
    const SwapQuad quad = trial.quad;
    apply_swap(layout, e);
    ++applied;
    EXPECT_EQ(layout.edges[e].anchors, (std::array<int, 2>{quad.l, quad.r}));
    EXPECT_EQ(layout.sides[0].chains[e].front(), layout.sides[0].anchor_vertices[quad.l]);
    EXPECT_EQ(layout.sides[1].chains[e].back(), layout.sides[1].anchor_vertices[quad.r]);
    expect_trial_matches(layout, trial);
    for (int side = 0; side < 2; ++side) {
      remeasure_patch_areas(layout, side, e, {quad.left_patch, quad.right_patch}, areas[side]);
      EXPECT_EQ(areas[side], patch_areas(layout, side));
    }
    const LayoutCheck check = check_layout(layout);
    ASSERT_TRUE(check.consistent()) << check.violations.front();
  }
  EXPECT_GT(applied, count / 3) << what;
  std::cout << what << ": " << applied << " swaps applied, " << refused << " refused; one try_swap "
            << 1e3 * seconds / tried << " ms on average (" << original.sides[0].mesh.n_vertices() << " + "
            << original.sides[1].mesh.n_vertices() << " vertices)\n";
}

TEST(BoundarySwap, RandomSwapsOnTheHumanPairKeepTheLayoutConsistent) {
  random_swaps(test::stretched_human_layout(), 5, 24, "human pair");
}

TEST(BoundarySwap, RandomSwapsOnSpotKeepTheLayoutConsistent) {
  random_swaps(test::stretched_spot_layout(), 11, 30, "spot pair");
}

TEST(BoundarySwap, SwappingAnEdgeTwiceGivesBackItsAnchors) {
  const Layout& original = test::stretched_human_layout();
  int checked = 0;
  for (int e = 0; e < static_cast<int>(original.edges.size()) && checked < 3; ++e) {
    if (!try_swap(original, e).possible) continue;
    Layout layout = original;
    apply_swap(layout, e);
    const SwapTrial back = try_swap(layout, e);
    ASSERT_TRUE(back.possible) << back.refusal;
    apply_swap(layout, e);
    // The edge runs b -> a now (its new l is the old b), in the same two patches.
    const auto& ends = original.edges[e].anchors;
    EXPECT_EQ(layout.edges[e].anchors, (std::array<int, 2>{ends[1], ends[0]}));
    test::expect_consistent(layout, "edge " + std::to_string(e) + " swapped twice");
    const SwapQuad quad = swap_quad(original, e).value();
    for (int p = 0; p < static_cast<int>(original.patches.size()); ++p) {
      // The same patches with e reversed: (b, a, r) is now on the left of e, in left_patch.
      const int was = p == quad.left_patch ? quad.right_patch : p == quad.right_patch ? quad.left_patch : p;
      std::vector<int> restored = layout.patches[p], expected = original.patches[was];
      for (int& h : expected) {
        if (layout_edge_of(h) == e) h = layout_opposite(h);
      }
      std::sort(restored.begin(), restored.end());
      std::sort(expected.begin(), expected.end());
      EXPECT_EQ(restored, expected) << "patch " << p;
    }
    ++checked;
  }
  EXPECT_EQ(checked, 3);
}

int degree(const Layout& layout, int anchor) {
  int count = 0;
  for (const LayoutEdge& edge : layout.edges)
    count += (edge.anchors[0] == anchor) + (edge.anchors[1] == anchor);
  return count;
}

bool joined(const Layout& layout, int x, int y) {
  for (const LayoutEdge& edge : layout.edges) {
    if ((edge.anchors[0] == x && edge.anchors[1] == y) || (edge.anchors[0] == y && edge.anchors[1] == x))
      return true;
  }
  return false;
}

// Every edge whose quad the combinatorics forbid is refused with its reason, and apply_swap
// throws and leaves the layout as it was; both kinds occur on these layouts.
void check_refusals(const Layout& original, const std::string& what) {
  int already_joined = 0, low_degree = 0;
  for (int e = 0; e < static_cast<int>(original.edges.size()); ++e) {
    const std::optional<SwapQuad> quad = swap_quad(original, e);
    ASSERT_TRUE(quad.has_value());
    const bool is_joined = joined(original, quad->l, quad->r);
    const bool is_low = degree(original, quad->a) <= 3 || degree(original, quad->b) <= 3;
    if (!is_joined && !is_low) continue;
    const SwapTrial trial = try_swap(original, e);
    EXPECT_FALSE(trial.possible) << what << ", edge " << e;
    if (is_low) {
      EXPECT_NE(trial.refusal.find("would be left with"), std::string::npos) << trial.refusal;
      ++low_degree;
    } else {
      EXPECT_NE(trial.refusal.find("already joined"), std::string::npos) << trial.refusal;
      ++already_joined;
    }
    Layout layout = original;
    EXPECT_THROW(apply_swap(layout, e), LayoutError);
    expect_same(layout, original);
  }
  EXPECT_GT(already_joined, 0) << what;
  EXPECT_GT(low_degree, 0) << what;
}

TEST(BoundarySwap, RefusesJoinedCornersAndLowDegreeAnchors) {
  check_refusals(test::stretched_human_layout(), "human pair");
  check_refusals(test::stretched_spot_layout(), "spot pair");
}

TEST(BoundarySwap, QuadNamesTheFourCornersCounterClockwise) {
  const Layout& layout = test::stretched_spot_layout();
  for (int e = 0; e < static_cast<int>(layout.edges.size()); ++e) {
    const SwapQuad quad = swap_quad(layout, e).value();
    EXPECT_EQ(quad.a, layout.edges[e].anchors[0]);
    EXPECT_EQ(quad.b, layout.edges[e].anchors[1]);
    // The left patch is (a, b, l): its walk holds a -> b and ends at l after b.
    const auto& left = layout.patches[quad.left_patch];
    const auto& right = layout.patches[quad.right_patch];
    EXPECT_NE(std::find(left.begin(), left.end(), 2 * e), left.end());
    EXPECT_NE(std::find(right.begin(), right.end(), 2 * e + 1), right.end());
    for (const int h : left)
      EXPECT_TRUE(layout_from(layout, h) == quad.a || layout_from(layout, h) == quad.b ||
                  layout_from(layout, h) == quad.l);
    for (const int h : right)
      EXPECT_TRUE(layout_from(layout, h) == quad.a || layout_from(layout, h) == quad.b ||
                  layout_from(layout, h) == quad.r);
  }
  EXPECT_THROW(try_swap(layout, -1), LayoutError);
}

}  // namespace
}  // namespace xparam
