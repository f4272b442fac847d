#include "batch/target_verdict.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace xparam {
namespace {

// Three significant digits: what a person compares against a limit.
std::string figure(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3g", value);
  return text;
}

// Degrees to a tenth: the corner shares are read, not recomputed.
nlohmann::ordered_json tenths(const std::vector<double>& degrees) {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (double d : degrees) list.push_back(std::round(d * 10.0) / 10.0);
  return list;
}

// Whether `name` is one of the helper anchors the map added (their images may move by design).
bool is_helper(const PairMapping& mapping, const std::string& name) {
  for (const TipAnchor& helper : mapping.tip_anchors)
    if (helper.specs[0].name == name) return true;
  for (const ExtremityAnchor& helper : mapping.extremity_anchors)
    if (helper.specs[0].name == name) return true;
  return false;
}

// The largest distance from the map to a user's landmark it does not pass through exactly, and
// its name.
std::pair<double, std::string> largest_miss(const PairMapping& mapping) {
  std::pair<double, std::string> largest{0.0, ""};
  const std::vector<PlacedAnchor>& placed = mapping.anchors[0].anchors;
  for (std::size_t k = 0; k < mapping.anchor_miss.size() && k < placed.size(); ++k)
    if (mapping.anchor_miss[k] > largest.first && !is_helper(mapping, placed[k].name))
      largest = {mapping.anchor_miss[k], placed[k].name};
  for (const ReleasedAnchor& released : mapping.released_anchors)
    if (released.miss_distance > largest.first) largest = {released.miss_distance, released.name};
  return largest;
}

// "7 folded faces by the strict count (limit 0), most nearest \"LEFT_WRIST\" (5)", and, when the
// map held its landmarks exactly, the option for landmarks placed by hand: folds gathered between two
// close landmarks placed a little differently on the target (FAUST 000/080's scan landmarks at the
// elbow: 3 strict folds) go with 1 cm of slack (docs/evaluation.md).
std::string folds_reason(const PairMapping& mapping, int folds, int limit) {
  std::string reason = std::to_string(folds) + (folds == 1 ? " folded face" : " folded faces") +
                       " by the strict count (limit " + std::to_string(limit) + ")";
  if (mapping.folds_by_anchor.empty()) return reason;
  reason += ", most nearest \"" + mapping.folds_by_anchor.front().name + "\" (" +
            std::to_string(mapping.folds_by_anchor.front().folded_faces) + ")";
  if (mapping.settings.anchor_slack == 0.0)
    reason += "; landmarks placed by hand may need --anchor-slack R (their placement error)";
  return reason;
}

std::vector<std::string> reasons_for(const PairMapping& mapping, const std::vector<SwappedAnchors>& swapped,
                                     const QualityLimits& limits) {
  std::vector<std::string> reasons;
  const int folds = mapping.quality.strictly_folded_faces;
  if (folds > limits.max_folds) reasons.push_back(folds_reason(mapping, folds, limits.max_folds));
  const double e_l2 = mapping.distortion.all.e_l2;
  if (!(e_l2 <= limits.max_e_l2))
    reasons.push_back("E_L2 " + figure(e_l2) + " (limit " + figure(limits.max_e_l2) + ")");
  const double area_ratio = mapping.quality.area_ratio;
  if (!(std::abs(area_ratio - 1.0) <= limits.max_area_deviation))
    reasons.push_back("area ratio " + figure(area_ratio) + " (limit 1 ± " + figure(limits.max_area_deviation) + ")");
  const auto [miss, missed] = largest_miss(mapping);
  const double size = std::sqrt(mapping.quality.target_area);
  if (miss > limits.max_anchor_miss * size)
    reasons.push_back("the map misses landmark \"" + missed + "\" by " + figure(miss) + " (" +
                      figure(miss / size) + " of the target's size, limit " + figure(limits.max_anchor_miss) + ")");
  for (const SwappedAnchors& pair : swapped)
    reasons.push_back("landmarks \"" + pair.first_name + "\" and \"" + pair.second_name +
                      "\" look swapped on the target (their distances to the other landmarks fit each other's)");
  return reasons;
}

nlohmann::ordered_json diagnosis_json(const PairMapping& mapping, const std::vector<SwappedAnchors>& swapped,
                                      const std::vector<std::string>& reasons) {
  nlohmann::ordered_json out;
  out["reasons"] = reasons;
  out["folds_by_anchor"] = nlohmann::ordered_json::array();
  for (const AnchorFolds& folds : mapping.folds_by_anchor)
    out["folds_by_anchor"].push_back({{"anchor", folds.name}, {"folded_faces", folds.folded_faces}});
  out["disagreeing_corners"] = nlohmann::ordered_json::array();
  for (const CornerMismatch& corners : mapping.mismatched_corners)
    out["disagreeing_corners"].push_back({{"anchor", corners.name},
                                          {"template_degrees", tenths(corners.template_degrees)},
                                          {"target_degrees", tenths(corners.target_degrees)}});
  out["swapped_anchors"] = nlohmann::ordered_json::array();
  for (const SwappedAnchors& pair : swapped)
    out["swapped_anchors"].push_back({pair.first_name, pair.second_name});
  out["released_anchors"] = nlohmann::ordered_json::array();
  for (const ReleasedAnchor& released : mapping.released_anchors)
    out["released_anchors"].push_back(
        {{"anchor", released.name}, {"folded_faces", released.folded_faces}, {"miss", released.miss_distance}});
  out["helper_anchors"] = nlohmann::ordered_json::array();
  for (const TipAnchor& helper : mapping.tip_anchors) out["helper_anchors"].push_back(helper.specs[0].name);
  for (const ExtremityAnchor& helper : mapping.extremity_anchors)
    out["helper_anchors"].push_back(helper.specs[0].name);
  out["warnings"] = nlohmann::ordered_json::array();
  for (const PlacedAnchors& side : mapping.anchors)
    for (const std::string& warning : side.warnings) out["warnings"].push_back(warning);
  // Only for a target mapped through a working copy, so the others' diagnosis is as it was.
  if (const WorkingCopyRecord& copy = mapping.working_copy; copy.used())
    out["working_copy"] = {{"target_vertices", copy.target_vertices},
                           {"vertices", copy.vertices},
                           {"faces", copy.faces},
                           {"max_carry_distance", copy.max_carry_distance},
                           {"mean_carry_distance", copy.mean_carry_distance}};
  return out;
}

}  // namespace

const char* to_string(Verdict verdict) {
  switch (verdict) {
    case Verdict::Ok: return "ok";
    case Verdict::Suspect: return "suspect";
    case Verdict::Failed: return "failed";
  }
  return "failed";
}

TargetJudgement judge_mapping(const PairMapping& mapping, const std::vector<SwappedAnchors>& swapped,
                              const QualityLimits& limits) {
  TargetJudgement judgement;
  judgement.reasons = reasons_for(mapping, swapped, limits);
  judgement.verdict = judgement.reasons.empty() ? Verdict::Ok : Verdict::Suspect;
  judgement.diagnosis = diagnosis_json(mapping, swapped, judgement.reasons);
  return judgement;
}

nlohmann::ordered_json limits_json(const QualityLimits& limits) {
  nlohmann::ordered_json json;
  json["max_folds"] = limits.max_folds;
  json["max_e_l2"] = limits.max_e_l2;
  json["max_area_deviation"] = limits.max_area_deviation;
  json["max_anchor_miss"] = limits.max_anchor_miss;
  return json;
}

}  // namespace xparam
