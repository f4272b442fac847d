#pragma once
/// \file
/// The whole maps map_pair is made of (map/pair_mapping.h), for its translation units only
/// (map/pair_mapping.cpp, map/tip_rounds.cpp): one map of the pair through given anchors (layout,
/// base domain, patch maps, composition, optimization on the target, with its later layouts), what
/// the pair's maps share, and the tests a map on other anchors must pass to replace another.

#include "core/anchor_placement.h"
#include "core/anchors.h"
#include "core/closest_point.h"
#include "core/errors.h"
#include "core/feature_curves.h"
#include "core/mesh.h"
#include "map/map_optimization.h"
#include "map/pair_mapping.h"
#include "param/relaxation_memo.h"

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace xparam::pair_maps {

// What the maps of one pair share. The whole maps (a layout built, optimized, parameterized,
// composed and optimized on the target) it may still make (PairSettings::max_maps): the first map
// is always made, a retry only while some are left; counted in maps, not seconds, so the results
// stay deterministic. And the patch relaxations made so far, which later maps reuse where a patch
// and its start are the same (param/relaxation_memo.h).
struct PairWork {
  int maps_left = 0;
  bool reached = false;  // a retry was not made for want of maps
  RelaxationMemo relaxations;
  // Nearest-point indexes over the two input meshes ([0] template, [1] target), each built the
  // first time it is needed: every map places its anchors given by position again, and every
  // round of tips with rows fits the toes onto the target.
  std::array<std::optional<ClosestPointIndex>, 2> input_surfaces;
  std::array<const Mesh*, 2> surface_meshes{};  // the meshes they were built over

  // The index over `input`, the pair's template (side 0) or target (side 1).
  const ClosestPointIndex& input_surface(int side, const Mesh& input) {
    if (!input_surfaces[side]) {
      input_surfaces[side].emplace(input);
      surface_meshes[side] = &input;
    }
    XP_ASSERT_MSG(surface_meshes[side] == &input, "one pair's maps on two different meshes");
    return *input_surfaces[side];
  }
  // The same when placing `anchors` needs it, else null.
  const ClosestPointIndex* input_surface(int side, const Mesh& input, const AnchorSet& anchors) {
    return has_position_anchor(anchors) ? &input_surface(side, input) : nullptr;
  }

  bool allows_another_map() {
    if (maps_left <= 0) reached = true;
    return maps_left > 0;
  }
};

// What every further try of map_pair maps again from.
struct PairInputs {
  const Mesh& source;
  const Mesh& target;
  const std::vector<FeatureCurve>& curves;
  const PairSettings& settings;
  const StageCallback& on_stage;
  PairWork& work;
};

// A map and the anchor sets it was made through.
struct AnchoredMap {
  PairMapping map;
  AnchorSet source_anchors;
  AnchorSet target_anchors;
};

// The anchors' names, in their order.
std::vector<std::string> anchor_names(const PlacedAnchors& placed);

// The template vertices an anchor holds, within its slack of the target's landmark: a vertex
// anchor's vertex, or every corner of the face (or edge) an anchor inside it lies in, which move
// only together (map/map_optimization.h).
std::vector<PinnedVertex> pinned_vertices(const std::array<PlacedAnchors, 2>& anchors, const Mesh& source,
                                          const Mesh& target, const PairSettings& settings);

// A map of the pair through anchors as given (no anchor released): its first layout's map, made
// when constructed, and the later layouts that may mend that map's folds (corners kept open,
// PairSettings::retry_keeping_corners), made only when asked. It keeps what they need (the meshes
// with the anchors placed) so that map_pair can first try maps through tips found on the first
// map, and make the later layouts only when none of those wins: on the realistic set (session 49)
// a tip map won on 40 of 44 pairs, and none of them changed when the later layouts of the map it
// replaced were left out (SHREC'19 17 [73 CAESAR]: E_L2 1.1011 -> 1.1018), which had cost up to
// 5.6 s a pair (FAUST 000/080 [72 scan]: 9.2 -> 3.6 s).
class AnchoredLayouts {
 public:
  // Places the anchors and makes the first layout's map into `map`.
  AnchoredLayouts(const Mesh& source, const AnchorSet& source_anchors, const Mesh& target,
                  const AnchorSet& target_anchors, const std::vector<FeatureCurve>& curves,
                  const PairSettings& settings, PairWork& work, const StageCallback& on_stage,
                  PairMapping& map);
  AnchoredLayouts(const AnchoredLayouts&) = delete;
  AnchoredLayouts& operator=(const AnchoredLayouts&) = delete;

  // Whether later layouts are still to be made: the map folds, the settings ask for them, and
  // they were not made yet.
  bool may_retry() const;
  // Make them (as many as PairWork allows); `map`, the map the constructor made, is replaced by
  // the one with the fewest folds, the earliest on a tie. \pre may_retry()
  void retry(PairMapping& map);

 private:
  const Mesh& source_;
  const Mesh& target_;
  const std::vector<FeatureCurve>& curves_;
  const PairSettings settings_;
  PairWork& work_;
  const StageCallback on_stage_;
  Mesh source_refined_, target_refined_;  // the inputs with the anchors placed
  std::vector<std::array<int, 3>> faces_;
  std::vector<std::string> names_;
  // The best map's remesh folds before its optimization on the target, and after (the remesh's
  // own count).
  int composed_folds_ = 0;
  int folds_ = 0;
  bool retried_ = false;
};

// map_pair on the anchors as given (no anchor released). When the first layout's map folds, later
// layouts are tried only if `worth_retrying` (when given) accepts that map.
PairMapping map_through_anchors(const Mesh& source, const AnchorSet& source_anchors, const Mesh& target,
                                const AnchorSet& target_anchors, const std::vector<FeatureCurve>& curves,
                                const PairSettings& settings, PairWork& work, const StageCallback& on_stage,
                                const std::function<bool(const PairMapping&)>& worth_retrying = {});

// map_through_anchors, or nothing when those anchors cannot be laid out or parameterized.
std::optional<PairMapping> map_if_possible(
    const Mesh& source, const AnchorSet& source_anchors, const Mesh& target, const AnchorSet& target_anchors,
    const std::vector<FeatureCurve>& curves, const PairSettings& settings, PairWork& work,
    const StageCallback& on_stage, const std::function<bool(const PairMapping&)>& worth_retrying = {});

// Whether `other` collapses no more template faces than `current` and covers the target's area
// to 2%, or no worse than `current` beyond noise: what a map made on other anchors must keep to
// replace the current one.
bool keeps_faces_and_area(const PairMapping& other, const PairMapping& current);

// Whether a map on other anchors (helpers added, or one more released) replaces the current
// one: it folds less, collapses no more template faces, and covers the target's area to 2% or
// no worse than the current map (a map that folds less by collapsing faces or by leaving part
// of the target uncovered is not better).
bool folds_less(const PairMapping& other, const PairMapping& current);

// A map through `current`'s anchors plus helper anchors behind its tips, when `current` folds and
// its corners disagree (PairSettings::tip_anchors): each of tip_anchor_reaches in turn until a
// map has no fold, a map replacing the best so far when it folds less. Nothing when no try
// folds less than `current`.
std::optional<AnchoredMap> with_helpers_behind_tips(const PairInputs& in, const AnchoredMap& current,
                                                    PairSeconds& seconds);

// Template faces a map stretches past use: L2 stretch (eq. 5) over 10 times the map's own scale,
// sqrt(image area / template area). A map that squeezes an unanchored protrusion into its root
// leaves the target's protrusion covered by a few such faces (SHREC'19 18 [29 anthropometric]: the
// template's forearm spread over the target's hand, E_L2 8600), as lost to the user as folded ones.
int grossly_stretched_faces(const PairMapping& map);

// Whether a map through helper anchors replaces `current`, which squeezes part of the template to
// nothing (grossly_stretched_faces): it folds no more by both counts, squeezes fewer faces so, is
// less stretched (E_L2), collapses no more faces and covers the target's area as well.
bool squeezes_less(const PairMapping& other, const PairMapping& current);

// A map through `current`'s anchors plus helper anchors behind its disagreeing corners, when
// `current` squeezes faces to nothing without folding (a map the retries for folds never see):
// each of tip_anchor_reaches in turn while the best so far squeezes any, kept by squeezes_less.
// No helper holds a template vertex an anchor holds (SHREC'19 22 [73 CAESAR]: behind Rt. Tragion,
// in a face at the Tragion's vertex, it made the map miss that landmark by 3.5 mm). Nothing when
// no try replaces `current`.
std::optional<AnchoredMap> with_helpers_behind_squeezed_tips(const PairInputs& in, const AnchoredMap& current,
                                                             PairSeconds& seconds);

}  // namespace xparam::pair_maps
