#include "domain/base_domain_optimization.h"

#include "core/errors.h"
#include "core/stopwatch.h"
#include "domain/boundary_swap.h"
#include "domain/dense_swap_metrics.h"
#include "domain/layout_measures.h"
#include "domain/patch_merging.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <queue>
#include <set>
#include <string>
#include <utility>

namespace xparam {
namespace {

// The layout's combinatorics as a value: the anchor pair of every edge, sorted. Swaps keep
// edge and patch indices, so this identifies a configuration whatever order swaps came in.
using Configuration = std::vector<std::array<int, 2>>;

std::array<int, 2> anchor_pair(int x, int y) { return {std::min(x, y), std::max(x, y)}; }

// Algorithm 1 (and the balanced algorithm of section 4.3) on one layout. Keys live in a
// max-heap with lazy deletion: each entry carries the version its edge had when it was
// evaluated; re-evaluating or swapping an edge bumps the version, so older entries are
// skipped when popped.
class BoundarySwapper {
 public:
  BoundarySwapper(Layout& layout, const DomainOptimizationSettings& settings, DomainOptimizationResult& result)
      : layout_(layout), settings_(settings), result_(result) {
    for (int side = 0; side < 2; ++side) {
      lengths_[side] = curve_lengths(layout_, side);
      areas_[side] = patch_areas(layout_, side);
    }
    const int n_edges = static_cast<int>(layout_.edges.size());
    version_.assign(n_edges, 0);
    patch_maps_.resize(layout_.patches.size());
    measured_.assign(layout_.patches.size(), false);
    if (is_dense_metric(settings_.metric)) input_areas_ = input_face_areas(layout_.sides[0].mesh);
    for (const LayoutEdge& edge : layout_.edges) current_.push_back(anchor_pair(edge.anchors[0], edge.anchors[1]));
    seen_.insert(sorted(current_));
  }

  void run() {
    const int n_edges = static_cast<int>(layout_.edges.size());
    result_.dl2_before = dl2_sum();
    if (settings_.metric == SwapMetric::balanced) set_balanced_threshold();
    std::vector<int> all(n_edges);
    for (int e = 0; e < n_edges; ++e) all[e] = e;
    evaluate_and_push(all);
    while (!heap_.empty()) {
      const Entry top = heap_.top();
      heap_.pop();
      if (top.version != version_[top.edge]) continue;
      swap(top);
    }
    result_.dl2_after = dl2_sum();
  }

 private:
  struct Entry {
    SwapKey key;
    int edge = -1;
    int version = 0;
    // Heap order: the greater key first, on equal keys the smaller edge index.
    friend bool operator<(const Entry& lhs, const Entry& rhs) {
      if (lhs.key < rhs.key) return true;
      if (rhs.key < lhs.key) return false;
      return lhs.edge > rhs.edge;
    }
  };

  // What evaluating one edge found (computed in parallel, consumed in edge order).
  struct Evaluation {
    std::optional<SwapKey> key;
    bool refused = false;       // try_swap refused the swap
    bool unmeasurable = false;  // ad, l2: the map after the swap could not be measured
  };

  // ad, l2: the map of one patch of the current layout; nullopt when it cannot be measured.
  using PatchMap = std::optional<PatchMapDistortion>;

  PatchMap try_measure(const Layout& layout, const std::vector<int>& patches) const {
    try {
      return measure_patch_map(layout, patches, input_areas_);
    } catch (const ParamError&) {
      return std::nullopt;
    }
  }

  static Configuration sorted(Configuration configuration) {
    std::sort(configuration.begin(), configuration.end());
    return configuration;
  }

  // The quad of e with its sides and before-swap measures; nullopt when a patch of e is not a
  // triangle.
  struct QuadMeasures {
    SwapQuad quad;
    std::array<int, 4> sides{};
    SwapMeasures measures;
  };
  std::optional<QuadMeasures> quad_measures(int e) const {
    const std::optional<SwapQuad> quad = swap_quad(layout_, e);
    if (!quad) return std::nullopt;
    QuadMeasures q{*quad, quad_side_edges(layout_, *quad), {}};
    for (int side = 0; side < 2; ++side) q.measures[side] = swap_side_measures(q.quad, q.sides, lengths_[side], areas_[side]);
    return q;
  }

  // Sum of E_DL2 (eq. 11) over every edge whose patches are triangles.
  double dl2_sum() const {
    double sum = 0.0;
    for (int e = 0; e < static_cast<int>(layout_.edges.size()); ++e) {
      if (const auto q = quad_measures(e)) sum += dl2_energy_before(q->measures);
    }
    return sum;
  }

  // Section 4.3 steps 1-2: the threshold over the curves whose LPBDs are valid. Degenerate
  // curves are candidates anyway (step 3), and their huge E_DL2 (an LPBD area of 1e-8) would
  // otherwise push the threshold above every real curve.
  void set_balanced_threshold() {
    std::vector<double> energies;
    std::vector<double> all;
    for (int e = 0; e < static_cast<int>(layout_.edges.size()); ++e) {
      const auto q = quad_measures(e);
      if (!q) continue;
      all.push_back(dl2_energy_before(q->measures));
      if (lpbds_valid_before(q->measures)) energies.push_back(all.back());
    }
    threshold_ = balanced_threshold(energies);
    result_.balanced_threshold = threshold_;
    result_.active_curves = static_cast<int>(std::count_if(all.begin(), all.end(), [&](double energy) { return energy > threshold_; }));
  }

  // Whether curve e winds on both sides (winds()).
  bool winding(int e, const QuadMeasures& q) const {
    std::array<double, 2> chords{};
    for (int side = 0; side < 2; ++side) {
      const LayoutSide& embedding = layout_.sides[side];
      const auto at = [&](int k) {
        return position(embedding.mesh, embedding.anchor_vertices[layout_.edges[e].anchors[k]]);
      };
      chords[side] = (at(0) - at(1)).norm();
    }
    return winds({q.measures[0].ab, q.measures[1].ab}, chords);
  }

  Evaluation evaluate(int e) const {
    Evaluation evaluation;
    const std::optional<QuadMeasures> q = quad_measures(e);
    if (!q) return evaluation;
    // Balanced step 3: only the active curves (by the threshold of step 2, on their current
    // E_DL2) and the degenerate ones; and the winding ones, when asked.
    if (settings_.metric == SwapMetric::balanced && lpbds_valid_before(q->measures) &&
        !(dl2_energy_before(q->measures) > threshold_) &&
        !(settings_.swap_winding_curves && winding(e, *q))) {
      return evaluation;
    }
    const SwapTrial trial = try_swap(layout_, e, settings_.stretching);
    if (!trial.possible) {
      evaluation.refused = true;
      return evaluation;
    }
    const SwapMeasures measures = with_trial(q->measures, trial);
    if (!is_dense_metric(settings_.metric)) {
      evaluation.key = swap_key(settings_.metric, measures);
      return evaluation;
    }
    // A degenerate LPBD after the swap is refused by swap_key whatever the map does; do not
    // pay for measuring it.
    if (!lpbds_valid_after(measures)) return evaluation;
    const PatchMap after = try_measure(trial.after, {trial.after_patches[0], trial.after_patches[1]});
    evaluation.unmeasurable = !after || std::isinf(after->e_l2()) || std::isinf(after->e_ang());
    evaluation.key = swap_key(settings_.metric, measures, dense_measures(q->quad, after));
    return evaluation;
  }

  // Eq. 3 and 6 of the quad's patches before (from the per-patch cache, left then right) and
  // after the swap; an unmeasurable map counts as +infinity (swap_key's rule).
  DenseSwapMeasures dense_measures(const SwapQuad& quad, const PatchMap& after) const {
    constexpr double kInfinity = std::numeric_limits<double>::infinity();
    const PatchMap& left = patch_maps_[quad.left_patch];
    const PatchMap& right = patch_maps_[quad.right_patch];
    DenseSwapMeasures dense;
    if (left && right) {
      PatchMapDistortion before = *left;
      before += *right;
      dense.e_ang_before = before.e_ang();
      dense.e_l2_before = before.e_l2();
    } else {
      dense.e_ang_before = dense.e_l2_before = kInfinity;
    }
    dense.e_ang_after = after ? after->e_ang() : kInfinity;
    dense.e_l2_after = after ? after->e_l2() : kInfinity;
    return dense;
  }

  // ad, l2: measure (in parallel, into per-patch slots) the current map of every patch of
  // `edges`' quads that is not cached yet.
  void measure_patches(const std::vector<int>& edges) {
    if (!is_dense_metric(settings_.metric)) return;
    std::vector<int> missing;
    for (int e : edges) {
      const std::optional<SwapQuad> quad = swap_quad(layout_, e);
      if (!quad) continue;
      for (int p : {quad->left_patch, quad->right_patch}) {
        if (!measured_[p]) missing.push_back(p);
      }
    }
    std::sort(missing.begin(), missing.end());
    missing.erase(std::unique(missing.begin(), missing.end()), missing.end());
    tbb::parallel_for(std::size_t{0}, missing.size(),
                      [&](std::size_t i) { patch_maps_[missing[i]] = try_measure(layout_, {missing[i]}); });
    for (int p : missing) measured_[p] = true;
  }

  // Evaluate `edges` (independent, so in parallel into per-index slots) and push the
  // candidates in the order given, bumping every edge's version.
  void evaluate_and_push(const std::vector<int>& edges) {
    measure_patches(edges);
    std::vector<Evaluation> evaluations(edges.size());
    tbb::parallel_for(std::size_t{0}, edges.size(), [&](std::size_t i) { evaluations[i] = evaluate(edges[i]); });
    for (std::size_t i = 0; i < edges.size(); ++i) {
      const int e = edges[i];
      ++version_[e];
      if (evaluations[i].refused) ++result_.refused_swaps;
      if (evaluations[i].unmeasurable) ++result_.unmeasurable_swaps;
      if (evaluations[i].key) heap_.push({*evaluations[i].key, e, version_[e]});
    }
  }

  void swap(const Entry& entry) {
    const int e = entry.edge;
    const std::optional<SwapQuad> quad = swap_quad(layout_, e);
    XP_ASSERT_MSG(quad, "edge " << e << " lost its quad without being re-evaluated");
    // Never return to a configuration seen before: a later swap may undo an earlier one, and
    // greedy keys measured on stretched curves need not be antisymmetric.
    Configuration next = current_;
    next[e] = anchor_pair(quad->l, quad->r);
    Configuration next_sorted = sorted(next);
    if (seen_.count(next_sorted) != 0) {
      ++result_.repeated_configurations;
      ++version_[e];
      return;
    }
    const std::array<int, 4> sides = quad_side_edges(layout_, *quad);
    try {
      apply_swap(layout_, e, settings_.stretching);
    } catch (const LayoutError&) {
      // Another swap since the evaluation made this one impossible (l-r joined elsewhere, an
      // anchor down to three edges); apply_swap left the layout unchanged.
      ++result_.refused_swaps;
      ++version_[e];
      return;
    }
    ++result_.swaps;
    if (entry.key.repairs) ++result_.repair_swaps;
    current_ = std::move(next);
    seen_.insert(std::move(next_sorted));
    // The quad's two patch indices now hold the new patches; every other patch kept its faces.
    measured_[quad->left_patch] = measured_[quad->right_patch] = false;
    ++version_[e];
    for (int side = 0; side < 2; ++side) {
      lengths_[side][e] = curve_length(layout_, side, e);
      for (int s : sides) lengths_[side][s] = curve_length(layout_, side, s);
      remeasure_patch_areas(layout_, side, e, {quad->left_patch, quad->right_patch}, areas_[side]);
    }
    // Only the quads of the four sides changed (Algorithm 1); e itself would swap back.
    evaluate_and_push({sides.begin(), sides.end()});
  }

  Layout& layout_;
  const DomainOptimizationSettings& settings_;
  DomainOptimizationResult& result_;
  std::array<std::vector<double>, 2> lengths_;  // per side, per edge
  std::array<std::vector<double>, 2> areas_;    // per side, per patch
  std::vector<int> version_;                    // per edge
  std::priority_queue<Entry> heap_;
  Configuration current_;  // per edge, by edge index
  std::set<Configuration> seen_;
  double threshold_ = 0.0;  // balanced only
  std::vector<double> input_areas_;   // ad, l2: input_face_areas of the template side
  std::vector<PatchMap> patch_maps_;  // ad, l2: per patch, the current map's measure
  std::vector<bool> measured_;        // ad, l2: per patch, patch_maps_ is up to date
};

// Algorithm 2: every edge between two triangles gets eq. 15 (in parallel, the patches do not
// change while evaluating); then greedily by value, an edge whose patch already went into a
// quad is skipped (that is exactly "a merged patch makes its four neighbour edges
// ineligible"), and all chosen edges are merged at once.
void merge_greedily(Layout& layout, DomainOptimizationResult& result) {
  const int n_edges = static_cast<int>(layout.edges.size());
  const std::array<std::vector<double>, 2> lengths = {curve_lengths(layout, 0), curve_lengths(layout, 1)};
  std::vector<std::optional<double>> values(n_edges);
  tbb::parallel_for(0, n_edges, [&](int e) {
    const std::optional<SwapQuad> quad = swap_quad(layout, e);
    if (!quad) return;
    const std::array<int, 4> sides = quad_side_edges(layout, *quad);
    const MergeMeasures measures = {merge_side_measures(layout, 0, *quad, sides, lengths[0]),
                                    merge_side_measures(layout, 1, *quad, sides, lengths[1])};
    values[e] = merge_metric(measures, false);
  });
  std::vector<std::pair<double, int>> candidates;
  for (int e = 0; e < n_edges; ++e) {
    if (values[e] && *values[e] > 0.0) candidates.emplace_back(*values[e], e);
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const auto& x, const auto& y) { return x.first != y.first ? x.first > y.first : x.second < y.second; });
  std::vector<bool> merged_patch(layout.patches.size(), false);
  std::vector<int> chosen;
  for (const auto& [value, e] : candidates) {
    const SwapQuad quad = *swap_quad(layout, e);
    if (merged_patch[quad.left_patch] || merged_patch[quad.right_patch]) continue;
    merged_patch[quad.left_patch] = merged_patch[quad.right_patch] = true;
    chosen.push_back(e);
  }
  std::sort(chosen.begin(), chosen.end());
  if (!chosen.empty()) merge_patches(layout, chosen);
  result.merges = static_cast<int>(chosen.size());
  result.merged_edges = std::move(chosen);
}

void check_preconditions(const Layout& layout) {
  for (std::size_t p = 0; p < layout.patches.size(); ++p) {
    if (layout.patches[p].size() != 3) {
      throw LayoutError("optimize_base_domain: patch " + std::to_string(p) + " has " +
                        std::to_string(layout.patches[p].size()) + " sides; the optimization starts from triangles");
    }
  }
  for (int side = 0; side < 2; ++side) {
    if (!has_patch_property(layout.sides[side].mesh)) {
      throw LayoutError("optimize_base_domain: side " + std::to_string(side) + " has no patch ids");
    }
  }
}

}  // namespace

DomainOptimizationResult optimize_base_domain(Layout& layout, const DomainOptimizationSettings& settings) {
  check_preconditions(layout);
  DomainOptimizationResult result;
  result.settings = settings;
  const std::array<std::size_t, 2> vertices_before = {layout.sides[0].mesh.n_vertices(),
                                                      layout.sides[1].mesh.n_vertices()};
  Stopwatch watch;
  if (settings.stretch) {
    result.unstretched_curves = static_cast<int>(stretch_layout(layout, settings.stretching).unstretched.size());
  }
  result.seconds_stretch = watch.lap();
  if (settings.metric != SwapMetric::none) BoundarySwapper(layout, settings, result).run();
  result.seconds_swap = watch.lap();
  if (settings.merge) merge_greedily(layout, result);
  result.seconds_merge = watch.lap();
  for (int side = 0; side < 2; ++side) {
    result.vertices_added[side] = static_cast<int>(layout.sides[side].mesh.n_vertices() - vertices_before[side]);
  }
  return result;
}

}  // namespace xparam
