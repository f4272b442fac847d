// The verdict's reason for strict folds: the figure, the limit, the landmark most of them are
// nearest, and, for a map that held its landmarks exactly, the option for hand-placed landmarks.
#include "batch/target_verdict.h"

#include <gtest/gtest.h>

#include <string>

namespace xparam {
namespace {

// A finished map with `folds` strictly folded faces, all nearest landmark "elbow", and nothing
// else over the default limits.
PairMapping folded_map(int folds, double anchor_slack) {
  PairMapping mapping;
  mapping.quality.strictly_folded_faces = folds;
  mapping.quality.area_ratio = 1.0;
  mapping.quality.target_area = 1.0;
  mapping.distortion.all.e_l2 = 1.05;
  mapping.folds_by_anchor.push_back({0, "elbow", folds});
  mapping.settings.anchor_slack = anchor_slack;
  return mapping;
}

TEST(TargetVerdict, FoldsAtExactLandmarksPointToTheSlack) {
  const TargetJudgement judged = judge_mapping(folded_map(3, 0.0), {}, QualityLimits{});
  EXPECT_EQ(judged.verdict, Verdict::Suspect);
  ASSERT_EQ(judged.reasons.size(), 1u);
  EXPECT_EQ(judged.reasons[0],
            "3 folded faces by the strict count (limit 0), most nearest \"elbow\" (3); landmarks placed by "
            "hand may need --anchor-slack R (their placement error)");
}

TEST(TargetVerdict, FoldsWithSlackAlreadyGivenNameOnlyTheLandmark) {
  const TargetJudgement judged = judge_mapping(folded_map(1, 0.01), {}, QualityLimits{});
  EXPECT_EQ(judged.verdict, Verdict::Suspect);
  ASSERT_EQ(judged.reasons.size(), 1u);
  EXPECT_EQ(judged.reasons[0], "1 folded face by the strict count (limit 0), most nearest \"elbow\" (1)");
}

TEST(TargetVerdict, NoFoldNoReason) {
  const TargetJudgement judged = judge_mapping(folded_map(0, 0.0), {}, QualityLimits{});
  EXPECT_EQ(judged.verdict, Verdict::Ok);
  EXPECT_TRUE(judged.reasons.empty());
}

}  // namespace
}  // namespace xparam
