#pragma once
/// \file
/// The verdict on one mapped target and the diagnosis behind it.
///
/// A target whose pipeline finished has a bijective map, but a map can still be useless: folded
/// remesh faces, a stretch in the thousands, an arm's area lost, a landmark the map had to let
/// go of. The quality limits below (batch options, stated defaults) turn those figures into
/// `ok` or `suspect`; a target whose pipeline failed is `failed`. The diagnosis is what
/// `xparam pair` prints about a map, as JSON, stored per target in the archive
/// (/targets/diagnosis) and shown by `xparam inspect --target NAME`: the reasons for the
/// verdict, folds by nearest anchor, anchors whose layout corners disagree, landmarks that look
/// swapped (layout/anchor_swaps.h), released and helper anchors, and the placement warnings.

#include "layout/anchor_swaps.h"
#include "map/pair_mapping.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace xparam {

/// Limits past which a bijective map is `suspect` (README, "Quality verdict").
struct QualityLimits {
  /// Remesh faces folded by the strict count (RemeshQualityResult::strictly_folded_faces) a map
  /// may have. Default 0: a fold by that count is one the map optimization could not remove.
  int max_folds = 0;
  /// Largest global L2 stretch E_L2 (paper eq. 6; 1 for an isometry up to scale). Default 10:
  /// most maps of docs/evaluation.md are 1–7; a landmark set that disagrees with the
  /// surface gives tens to thousands.
  double max_e_l2 = 10.0;
  /// Largest |area ratio − 1| (remesh area / target area). Default 0.05: a lost finger or
  /// ear is 1–3%, a limb 5% or more.
  double max_area_deviation = 0.05;
  /// Largest distance from the map to a landmark it does not pass through (a released anchor,
  /// or one moved by --anchor-slack), as a fraction of the square root of the target's area.
  /// Default 0.02 (2.7 cm on an adult body of 1.8 m²).
  double max_anchor_miss = 0.02;
};

/// ok / suspect for a finished map, failed for a target whose pipeline failed.
enum class Verdict { Ok, Suspect, Failed };

/// "ok", "suspect", "failed".
const char* to_string(Verdict verdict);

/// The verdict on one finished map and its diagnosis.
struct TargetJudgement {
  Verdict verdict = Verdict::Ok;     ///< Ok or Suspect
  std::vector<std::string> reasons;  ///< one per limit the map passes, naming figure and limit; empty when ok
  /// {"reasons", "folds_by_anchor", "disagreeing_corners", "swapped_anchors", "released_anchors",
  /// "helper_anchors", "warnings"}: schemas/target.schema.json, $defs/diagnosis.
  nlohmann::ordered_json diagnosis;
};

/// Judge `mapping` against `limits` and gather its diagnosis. `swapped` are the landmark pairs
/// that look traded (find_swapped_anchors); any such pair makes the map suspect, since the map
/// then passes through landmarks the user did not mean.
TargetJudgement judge_mapping(const PairMapping& mapping, const std::vector<SwappedAnchors>& swapped,
                              const QualityLimits& limits);

/// The limits as a JSON object (recorded with the batch's options: a resumed run with other
/// limits reruns its targets, so one archive never mixes verdicts of two sets of limits).
nlohmann::ordered_json limits_json(const QualityLimits& limits);

}  // namespace xparam
