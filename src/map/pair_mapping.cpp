#include "map/pair_mapping.h"

#include "core/stopwatch.h"
#include "map/pair_finish.h"
#include "map/tip_rounds.h"
#include "map/whole_maps.h"
#include "map/working_copy.h"

#include <algorithm>
#include <optional>

namespace xparam {

using pair_maps::AnchoredLayouts;
using pair_maps::AnchoredMap;
using pair_maps::folds_less;
using pair_maps::map_if_possible;
using pair_maps::PairInputs;
using pair_maps::PairWork;
using pair_maps::with_extremity_anchors;
using pair_maps::with_helpers_behind_tips;

namespace {

// `set` without the anchor named `name`.
AnchorSet without_anchor(const AnchorSet& set, const std::string& name) {
  AnchorSet kept = set;
  std::erase_if(kept.anchors, [&](const AnchorSpec& anchor) { return anchor.name == name; });
  return kept;
}

// A map through `start`'s anchors less some released one at a time, when `start` folds
// (PairSettings::max_released_anchors; see map_pair), their miss distances not yet measured.
// Nothing when no release folds less.
std::optional<AnchoredMap> release_anchors(const PairInputs& in, const AnchoredMap& start,
                                           PairSeconds& seconds) {
  std::optional<AnchoredMap> best;
  std::vector<ReleasedAnchor> released;
  for (;;) {
    const AnchoredMap& current = best ? *best : start;
    if (current.map.quality.flipped_faces.empty() ||
        static_cast<int>(released.size()) >= in.settings.max_released_anchors ||
        static_cast<int>(current.source_anchors.anchors.size()) <= kMinAnchors)
      break;
    bool helped = false;
    const std::vector<AnchorFolds> candidates = current.map.folds_by_anchor;
    for (const AnchorFolds& candidate : candidates) {
      if (!in.work.allows_another_map()) break;
      AnchoredMap fewer{{},
                        without_anchor(current.source_anchors, candidate.name),
                        without_anchor(current.target_anchors, candidate.name)};
      if (in.on_stage) in.on_stage("mapping again without anchor \"" + candidate.name + "\"");
      std::optional<PairMapping> trial =
          map_if_possible(in.source, fewer.source_anchors, in.target, fewer.target_anchors, in.curves,
                          in.settings, in.work, in.on_stage);
      if (!trial) continue;  // the anchors left cannot be laid out or parameterized: this anchor stays
      seconds.add_stages(trial->seconds);
      if (!folds_less(*trial, current.map)) continue;
      released.push_back({candidate.name, candidate.folded_faces, 0.0});
      fewer.map = std::move(*trial);
      best = std::move(fewer);  // `current` may refer to *best: nothing of it is read after this
      helped = true;
      break;
    }
    if (!helped) break;
  }
  if (best) best->map.released_anchors = std::move(released);
  return best;
}

// Rounds of tips from `start` (PairSettings::tip_rounds), each matching tips through the map the
// round before left: the last round's map that won, or nothing when the first round's did not.
std::optional<AnchoredMap> tip_rounds(const PairInputs& in, const AnchoredMap& start, PairSeconds& seconds) {
  std::optional<AnchoredMap> tipped;
  for (int round = 0; round < in.settings.tip_rounds; ++round) {
    std::optional<AnchoredMap> next = with_extremity_anchors(in, tipped ? *tipped : start, seconds);
    if (!next) break;
    tipped = std::move(next);
  }
  return tipped;
}

}  // namespace

void PairSeconds::add_stages(const PairSeconds& other) {
  anchors += other.anchors;
  layout += other.layout;
  optimize += other.optimize;
  parameterize += other.parameterize;
  relax += other.relax;
  compose += other.compose;
  untangle += other.untangle;
  optimize_map += other.optimize_map;
  metrics += other.metrics;
}

PairMapping map_pair(const Mesh& source, const AnchorSet& source_anchors, const Mesh& target,
                     const AnchorSet& target_anchors, const std::vector<FeatureCurve>& curves,
                     const PairSettings& settings, const StageCallback& on_stage) {
  Stopwatch total;
  // A large target is mapped through its working copy, and the map carried back onto it.
  if (on_stage && settings.work_vertices > 0 && static_cast<int>(target.n_vertices()) > settings.work_vertices)
    on_stage("working copy");
  Stopwatch copy_watch;
  std::string refusal;
  const std::optional<WorkingCopy> copy =
      WorkingCopy::make(target, target_anchors, settings.work_vertices, settings.placement, &refusal);
  const double copy_seconds = copy_watch.lap();
  const Mesh& mapped = copy ? copy->mesh() : target;
  const AnchorSet& mapped_anchors = copy ? copy->anchors() : target_anchors;
  PairWork work;
  work.maps_left = settings.max_maps;
  const PairInputs in{source, mapped, curves, settings, on_stage, work};
  // The map through the landmarks. The later layouts that may mend its folds wait for the rounds
  // of tips, whose maps replace it on most pairs (AnchoredLayouts).
  AnchoredMap plain{{}, source_anchors, mapped_anchors};
  AnchoredLayouts landmark_layouts(source, source_anchors, mapped, mapped_anchors, curves, settings, work,
                                   on_stage, plain.map);
  PairSeconds seconds;              // of every map but `plain`'s, which are added last
  std::optional<AnchoredMap> best;  // a map better than `plain`, when one was found
  if (settings.extremity_anchors) best = tip_rounds(in, plain, seconds);
  // No map through tips won: the later layouts of the map through the landmarks.
  if (!best && landmark_layouts.may_retry()) landmark_layouts.retry(plain.map);
  if (settings.tip_anchors) {
    const AnchoredMap& so_far = best ? *best : plain;
    if (!so_far.map.quality.flipped_faces.empty()) {
      if (std::optional<AnchoredMap> helped = with_helpers_behind_tips(in, so_far, seconds))
        best = std::move(helped);
    }
  }
  if (settings.max_released_anchors > 0 && !(best ? *best : plain).map.quality.flipped_faces.empty()) {
    // Releasing starts from the map through the landmarks alone (a helper or a tip is no
    // landmark), its later layouts made, then helpers and tips are tried on what it leaves; the
    // better of the two ways is kept (SHREC'19 17: helpers leave 1 fold, releasing the misplaced
    // knuckle none).
    if (landmark_layouts.may_retry()) landmark_layouts.retry(plain.map);
    std::optional<AnchoredMap> released = release_anchors(in, plain, seconds);
    if (released && settings.tip_anchors && !released->map.quality.flipped_faces.empty()) {
      if (std::optional<AnchoredMap> helped = with_helpers_behind_tips(in, *released, seconds))
        released = std::move(helped);
    }
    if (released && settings.extremity_anchors) {
      if (std::optional<AnchoredMap> tipped = tip_rounds(in, *released, seconds))
        released = std::move(tipped);
    }
    if (released && folds_less(released->map, (best ? *best : plain).map)) best = std::move(released);
  }
  // A map that squeezes part of the template to nothing without folding is one no retry above
  // sees: SHREC'19 22 [73 CAESAR], a mitten, where the middle fingertip's corners disagree and the
  // template's ring and little fingers shrink to a point at the knuckle (E_L2 2.64, no fold; 1.10
  // through helpers behind the fingertip). Tried last, on a map no round of tips replaced (tips
  // carry their own slack, which a map through helpers behind them would drop).
  if (settings.tip_anchors) {
    const AnchoredMap& last = best ? *best : plain;
    if (last.map.extremity_anchors.empty() && pair_maps::grossly_stretched_faces(last.map) > 0) {
      if (std::optional<AnchoredMap> helped = pair_maps::with_helpers_behind_squeezed_tips(in, last, seconds))
        best = std::move(helped);
    }
  }
  seconds.add_stages(plain.map.seconds);
  PairMapping result = best ? std::move(best->map) : std::move(plain.map);
  if (copy) {
    if (on_stage) on_stage("carry back");
    copy->carry_back(result, source, curves);
    result.working_copy.seconds += copy_seconds;
    // A released anchor's landmark is among the first map's (the released map no longer has it).
    if (!result.released_anchors.empty())
      for (PlacedAnchor& anchor : plain.map.anchors[1].anchors)
        anchor.input_point = copy->on_target(anchor.input_point).location;
  } else if (!refusal.empty()) {
    result.anchors[1].warnings.push_back("target: " + refusal);
  }
  if (!result.released_anchors.empty()) {
    std::vector<std::string> names;
    for (const ReleasedAnchor& anchor : result.released_anchors) names.push_back(anchor.name);
    const std::vector<double> misses =
        miss_distances(names, plain.map.anchors, source, target, result.remesh_vertices);
    for (std::size_t k = 0; k < names.size(); ++k) result.released_anchors[k].miss_distance = misses[k];
  }
  result.seconds = seconds;
  result.seconds.total = total.lap();
  result.maps_made = settings.max_maps - work.maps_left;
  result.map_limit_reached = work.reached;
  return result;
}

}  // namespace xparam
