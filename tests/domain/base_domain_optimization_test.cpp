#include "domain/base_domain_optimization.h"

#include "core/anchor_placement.h"
#include "core/errors.h"
#include "domain/boundary_swap.h"
#include "domain/dense_swap_metrics.h"
#include "domain/layout_measures.h"
#include "io/anchor_reader.h"
#include "io/mesh_loader.h"
#include "layout/consistent_layout.h"
#include "layout/layout_check.h"
#include "support/test_data.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <map>
#include <set>
#include <string>

namespace xparam {
namespace {

// The consistent layout of a bundled pair through the pipeline's own steps (load, place the
// anchors by name, build the layout).
Layout build_layout(const std::string& source_file, const std::string& source_anchors,
                    const std::string& target_file, const std::string& target_anchors) {
  const LoadedMesh source = load_mesh(test::data_path(source_file));
  const LoadedMesh target = load_mesh(test::data_path(target_file));
  const AnchorSet source_set = read_anchors(test::data_path(source_anchors));
  const AnchorSet target_set = match_anchors(source_set, read_anchors(test::data_path(target_anchors)));
  Mesh source_refined = source.mesh;
  Mesh target_refined = target.mesh;
  const auto vertices = [](const PlacedAnchors& placed) {
    std::vector<VertexHandle> result;
    for (const PlacedAnchor& anchor : placed.anchors) result.push_back(anchor.vertex);
    return result;
  };
  const PlacedAnchors s = place_anchors(source_refined, source.mesh, source_set);
  const PlacedAnchors t = place_anchors(target_refined, target.mesh, target_set);
  return build_consistent_layout(source_refined, vertices(s), target_refined, vertices(t)).layout;
}

// The two bundled pairs, stretched once (the swap and merge tests start from there).
// Swapping by `metric` alone: no stretching before, no merging after.
DomainOptimizationSettings swaps_only(SwapMetric metric) {
  DomainOptimizationSettings settings;
  settings.stretch = false;
  settings.metric = metric;
  settings.merge = false;
  return settings;
}

struct Pair {
  std::string name;
  Layout initial;
  Layout stretched;
};

Pair make_pair(const std::string& name, Layout layout) {
  Pair pair{name, layout, std::move(layout)};
  DomainOptimizationSettings stretch_only;
  stretch_only.metric = SwapMetric::none;
  stretch_only.merge = false;
  optimize_base_domain(pair.stretched, stretch_only);
  return pair;
}

const std::vector<Pair>& pairs() {
  static const std::vector<Pair> all = [] {
    std::vector<Pair> result;
    result.push_back(make_pair("man/woman", build_layout("human_man.obj", "human_man.anchors.json",
                                                         "human_woman.obj", "human_woman.anchors.json")));
    result.push_back(
        make_pair("spot/spot low", build_layout("spot.ply", "spot.anchors.json", "spot_low_resolution.obj",
                                                "spot_low_resolution.anchors.json")));
    return result;
  }();
  return all;
}

void expect_consistent(const Layout& layout, bool triangles, const std::string& what) {
  LayoutCheckSettings settings;
  settings.triangles = triangles;
  const LayoutCheck check = check_layout(layout, settings);
  std::string all;
  for (const auto& line : check.violations) all += "\n  " + line;
  EXPECT_TRUE(check.consistent()) << what << ":" << all;
}

// Everything a layout measures, per edge: E_DL2 (eq. 11) and whether its LPBDs are valid.
struct Dl2Survey {
  double sum = 0.0;
  int invalid_triangles = 0;  // triangle LPBDs (per side) that are degenerate
};

Dl2Survey survey(const Layout& layout) {
  const std::array<std::vector<double>, 2> lengths = {curve_lengths(layout, 0), curve_lengths(layout, 1)};
  const std::array<std::vector<double>, 2> areas = {patch_areas(layout, 0), patch_areas(layout, 1)};
  Dl2Survey result;
  for (int e = 0; e < static_cast<int>(layout.edges.size()); ++e) {
    const SwapQuad quad = *swap_quad(layout, e);
    const std::array<int, 4> sides = quad_side_edges(layout, quad);
    const SwapMeasures m = {swap_side_measures(quad, sides, lengths[0], areas[0]),
                            swap_side_measures(quad, sides, lengths[1], areas[1])};
    result.sum += dl2_energy_before(m);
  }
  for (int side = 0; side < 2; ++side) {
    for (const std::vector<int>& patch : layout.patches) {
      std::array<double, 3> l{};
      for (int k = 0; k < 3; ++k) l[k] = lengths[side][layout_edge_of(patch[k])];
      if (!triangle_lpbd(l[0], l[1], l[2]).valid) ++result.invalid_triangles;
    }
  }
  return result;
}

TEST(BaseDomainOptimization, MetricNamesAreTheOptionNames) {
  EXPECT_EQ(parse_swap_metric(to_string(SwapMetric::balanced)), SwapMetric::balanced);
  EXPECT_EQ(to_string(DomainOptimizationSettings{}.metric), "balanced");
}

TEST(BaseDomainOptimization, EveryMetricKeepsTheLayoutConsistent) {
  for (const Pair& pair : pairs()) {
    const Dl2Survey start = survey(pair.stretched);
    for (SwapMetric metric : {SwapMetric::area, SwapMetric::dad, SwapMetric::dl2, SwapMetric::sdl,
                              SwapMetric::gar, SwapMetric::balanced}) {
      const std::string what = pair.name + " " + std::string(to_string(metric));
      Layout layout = pair.stretched;
      const DomainOptimizationResult result = optimize_base_domain(layout, swaps_only(metric));
      expect_consistent(layout, true, what);
      EXPECT_EQ(result.merges, 0) << what;
      EXPECT_LE(result.repair_swaps, result.swaps) << what;
      // Swaps never leave a degenerate LPBD, so the count of degenerate triangles cannot grow.
      const Dl2Survey end = survey(layout);
      EXPECT_LE(end.invalid_triangles, start.invalid_triangles) << what;
      // The result's E_DL2 sums are those of the layouts.
      EXPECT_NEAR(result.dl2_before, start.sum, 1e-9 * start.sum) << what;
      EXPECT_NEAR(result.dl2_after, end.sum, 1e-9 * end.sum) << what;
      // Every pair of anchors joined at most once (a swap to an existing edge is refused).
      std::set<std::pair<int, int>> joined;
      for (const LayoutEdge& edge : layout.edges) {
        EXPECT_TRUE(joined
                        .emplace(std::min(edge.anchors[0], edge.anchors[1]),
                                 std::max(edge.anchors[0], edge.anchors[1]))
                        .second)
            << what;
      }
    }
  }
}

TEST(BaseDomainOptimization, BalancedDoesNotRaiseTheDomainStretch) {
  for (const Pair& pair : pairs()) {
    Layout layout = pair.stretched;
    DomainOptimizationSettings settings;
    settings.stretch = false;
    settings.merge = false;
    const DomainOptimizationResult result = optimize_base_domain(layout, settings);
    EXPECT_LE(result.dl2_after, result.dl2_before) << pair.name;
    EXPECT_GT(result.balanced_threshold, 2.0) << pair.name;  // two different bodies: some stretch
    EXPECT_GT(result.active_curves, 0) << pair.name;
    EXPECT_LT(result.active_curves, static_cast<int>(layout.edges.size())) << pair.name;
    expect_consistent(layout, true, pair.name + " balanced");
  }
}

// Everything an optimized layout is made of, to compare two runs bit for bit.
void expect_identical(const Layout& x, const Layout& y, const std::string& what) {
  ASSERT_EQ(x.edges.size(), y.edges.size()) << what;
  for (std::size_t e = 0; e < x.edges.size(); ++e) EXPECT_EQ(x.edges[e].anchors, y.edges[e].anchors) << what;
  EXPECT_EQ(x.patches, y.patches) << what;
  for (int side = 0; side < 2; ++side) {
    const Mesh& a = x.sides[side].mesh;
    const Mesh& b = y.sides[side].mesh;
    ASSERT_EQ(a.n_vertices(), b.n_vertices()) << what;
    ASSERT_EQ(a.n_faces(), b.n_faces()) << what;
    for (VertexHandle v : a.vertices()) ASSERT_EQ(a.point(v), b.point(v)) << what;
    EXPECT_EQ(x.sides[side].chains, y.sides[side].chains) << what;
  }
}

TEST(BaseDomainOptimization, IdenticalWithOneAndTwoThreads) {
  // The humans: the whole pipeline (stretch, DL2 swapping, which swaps most there, merge) twice.
  const Pair& pair = pairs()[0];
  const auto run = [&](int threads) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    Layout layout = pair.initial;
    DomainOptimizationSettings settings;
    settings.metric = SwapMetric::dl2;
    const DomainOptimizationResult result = optimize_base_domain(layout, settings);
    return std::make_pair(std::move(layout), result);
  };
  const auto [one, one_result] = run(1);
  const auto [two, two_result] = run(2);
  expect_identical(one, two, pair.name);
  EXPECT_GT(one_result.swaps, 0);  // else the test would compare two copies of the input
  EXPECT_GT(one_result.merges, 0);
  EXPECT_EQ(one_result.swaps, two_result.swaps);
  EXPECT_EQ(one_result.refused_swaps, two_result.refused_swaps);
  EXPECT_EQ(one_result.merged_edges, two_result.merged_edges);
  EXPECT_EQ(one_result.dl2_after, two_result.dl2_after);
  EXPECT_EQ(one_result.vertices_added, two_result.vertices_added);
}

std::vector<int> every_patch(const Layout& layout) {
  std::vector<int> patches(layout.patches.size());
  for (std::size_t p = 0; p < patches.size(); ++p) patches[p] = static_cast<int>(p);
  return patches;
}

TEST(BaseDomainOptimization, DenseAngleDistortionCountsEveryInputFaceOnce) {
  // The stretched curves cut many template faces into pieces; eq. 3 over all patches still
  // counts each input face once in all (its pieces' area shares add up to one).
  const Pair& pair = pairs()[1];
  const std::vector<int> all_patches = every_patch(pair.stretched);
  const std::vector<double> input_areas = input_face_areas(pair.stretched.sides[0].mesh);
  const PatchMapDistortion map = measure_patch_map(pair.stretched, all_patches, input_areas);
  const double input_faces = static_cast<double>(input_areas.size());
  EXPECT_GT(map.sums.faces, input_faces + 100) << pair.name;  // the curves did cut faces
  EXPECT_NEAR(map.angle_weight, input_faces, 1e-9 * input_faces) << pair.name;
}

TEST(BaseDomainOptimization, DenseMetricsLowerTheirEnergyConsistentlyAtAnyThreadCount) {
  // AD and L2 (paper section 4.1) on the smaller pair, at one and two threads. Every applied
  // swap lowered the dense energy of its own quad; that the whole map's energy goes down too
  // is not a theorem (eq. 6 is not a sum over patches, and a swap re-cuts the faces along its
  // curves), but it holds on this pair, and a key of the wrong sign would raise it.
  const Pair& pair = pairs()[1];
  const std::vector<int> all_patches = every_patch(pair.stretched);
  const std::vector<double> input_areas = input_face_areas(pair.stretched.sides[0].mesh);
  const PatchMapDistortion start = measure_patch_map(pair.stretched, all_patches, input_areas);
  for (SwapMetric metric : {SwapMetric::ad, SwapMetric::l2}) {
    const std::string what = pair.name + " " + std::string(to_string(metric));
    const auto run = [&](int threads) {
      const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
      Layout layout = pair.stretched;
      const DomainOptimizationResult result = optimize_base_domain(layout, swaps_only(metric));
      return std::make_pair(std::move(layout), result);
    };
    const auto [one, one_result] = run(1);
    const auto [two, two_result] = run(2);
    expect_consistent(one, true, what);
    expect_identical(one, two, what);
    EXPECT_GT(one_result.swaps, 0) << what;  // else the comparison would be of two copies of the input
    EXPECT_EQ(one_result.swaps, two_result.swaps) << what;
    EXPECT_EQ(one_result.refused_swaps, two_result.refused_swaps) << what;
    EXPECT_EQ(one_result.unmeasurable_swaps, two_result.unmeasurable_swaps) << what;
    const PatchMapDistortion end = measure_patch_map(one, all_patches, input_areas);
    if (metric == SwapMetric::ad) {
      EXPECT_LT(end.e_ang(), start.e_ang()) << what;
    } else {
      EXPECT_LT(end.e_l2(), start.e_l2()) << what;
    }
  }
}

TEST(BaseDomainOptimization, MergingMakesQuadsOnlyWhereEquationFifteenIsPositive) {
  int total_merges = 0;
  for (const Pair& pair : pairs()) {
    // Swap first (balanced), then merge on its own so the merge values can be read before.
    Layout layout = pair.stretched;
    DomainOptimizationSettings swap_only;
    swap_only.stretch = false;
    swap_only.merge = false;
    optimize_base_domain(layout, swap_only);
    const std::array<std::vector<double>, 2> lengths = {curve_lengths(layout, 0), curve_lengths(layout, 1)};
    std::map<int, double> value;  // edges with a value (not refused)
    for (int e = 0; e < static_cast<int>(layout.edges.size()); ++e) {
      const SwapQuad quad = *swap_quad(layout, e);
      const std::array<int, 4> sides = quad_side_edges(layout, quad);
      const auto v = merge_metric({merge_side_measures(layout, 0, quad, sides, lengths[0]),
                                   merge_side_measures(layout, 1, quad, sides, lengths[1])},
                                  false);
      if (v) value[e] = *v;
    }
    const Layout before = layout;
    DomainOptimizationSettings merge_only;
    merge_only.stretch = false;
    merge_only.metric = SwapMetric::none;
    const DomainOptimizationResult result = optimize_base_domain(layout, merge_only);
    expect_consistent(layout, false, pair.name + " merged");
    EXPECT_EQ(result.merges, static_cast<int>(result.merged_edges.size()));
    EXPECT_EQ(layout.edges.size(), before.edges.size() - result.merged_edges.size());
    int quads = 0;
    for (const auto& patch : layout.patches) quads += patch.size() == 4 ? 1 : 0;
    EXPECT_EQ(quads, result.merges) << pair.name;
    total_merges += result.merges;
    // Each merged edge had eq. 15 > 0; no two share a patch; and greedy leaves no positive
    // edge whose two patches are both still triangles.
    std::set<int> merged_patches;
    for (int e : result.merged_edges) {
      ASSERT_TRUE(value.count(e)) << pair.name << " edge " << e << " was refused";
      EXPECT_GT(value[e], 0.0) << pair.name << " edge " << e;
      const SwapQuad quad = *swap_quad(before, e);
      EXPECT_TRUE(merged_patches.insert(quad.left_patch).second) << pair.name;
      EXPECT_TRUE(merged_patches.insert(quad.right_patch).second) << pair.name;
    }
    for (const auto& [e, v] : value) {
      if (v <= 0.0) continue;
      const SwapQuad quad = *swap_quad(before, e);
      EXPECT_TRUE(merged_patches.count(quad.left_patch) || merged_patches.count(quad.right_patch))
          << pair.name << ": edge " << e << " has eq. 15 = " << v << " and free triangles";
    }
    // A merged layout is no start for another optimization.
    EXPECT_EQ(result.merges > 0, [&] {
      try {
        Layout again = layout;
        optimize_base_domain(again, merge_only);
      } catch (const LayoutError&) {
        return true;
      }
      return false;
    }()) << pair.name;
  }
  EXPECT_GT(total_merges, 0);  // the bundled pairs do merge (the humans about ten patch pairs)
}

}  // namespace
}  // namespace xparam
