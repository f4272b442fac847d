// Landmarks that look traded between two meshes (layout/anchor_swaps.h): the SMPL man against the
// bent man and the woman (other pose, other body, same landmark vertices).
#include "layout/anchor_swaps.h"

#include "core/errors.h"
#include "layout_fixtures.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace xparam {
namespace {

struct Landmarks {
  std::vector<int> ids;
  std::vector<std::string> names;
};

// tests/data/human.anchors.json: 41 SMPL landmarks, valid on every SMPL-ordered mesh.
Landmarks human_landmarks() {
  std::ifstream in(test::data_path("human.anchors.json"));
  const nlohmann::json json = nlohmann::json::parse(in);
  Landmarks landmarks;
  for (const auto& anchor : json.at("anchors")) {
    landmarks.ids.push_back(anchor.at("vertex").get<int>());
    landmarks.names.push_back(anchor.at("name").get<std::string>());
  }
  return landmarks;
}

std::size_t index_of(const Landmarks& landmarks, const std::string& name) {
  return static_cast<std::size_t>(std::find(landmarks.names.begin(), landmarks.names.end(), name) -
                                  landmarks.names.begin());
}

TEST(AnchorSwaps, RightLandmarksOnAnotherPoseAndBodyAreNotSwapped) {
  const Mesh man = test::load(test::data_path("human_man.obj"));
  const Landmarks landmarks = human_landmarks();
  for (const char* target : {"sample_targets/man_bent.obj", "sample_targets/woman.obj"}) {
    SCOPED_TRACE(target);
    const Mesh other = test::load(test::data_path(target));
    EXPECT_TRUE(find_swapped_anchors(man, test::handles(landmarks.ids), other, test::handles(landmarks.ids),
                                     landmarks.names)
                    .empty());
  }
}

TEST(AnchorSwaps, EveryLeftRightPairTradedOnTheTargetIsNamed) {
  const Mesh man = test::load(test::data_path("human_man.obj"));
  const Mesh bent = test::load(test::data_path("sample_targets/man_bent.obj"));
  const Landmarks landmarks = human_landmarks();
  for (const auto& [left, right] : {std::pair{"LEFT_NIPPLE", "RIGHT_NIPPLE"}, std::pair{"LEFT_WRIST", "RIGHT_WRIST"},
                                    std::pair{"LEFT_HEEL", "RIGHT_HEEL"}}) {
    SCOPED_TRACE(left);
    std::vector<int> traded = landmarks.ids;
    std::swap(traded[index_of(landmarks, left)], traded[index_of(landmarks, right)]);
    const std::vector<SwappedAnchors> swapped =
        find_swapped_anchors(man, test::handles(landmarks.ids), bent, test::handles(traded), landmarks.names);
    ASSERT_EQ(swapped.size(), 1u);
    const std::vector<std::string> named = {swapped[0].first_name, swapped[0].second_name};
    EXPECT_NE(std::find(named.begin(), named.end(), left), named.end());
    EXPECT_NE(std::find(named.begin(), named.end(), right), named.end());
    EXPECT_LT(swapped[0].swapped, 0.5 * swapped[0].disagreement);
  }
}

TEST(AnchorSwaps, ListsOfDifferentLengthsAreRefused) {
  const Mesh man = test::load(test::data_path("human_man.obj"));
  const Landmarks landmarks = human_landmarks();
  std::vector<int> fewer = landmarks.ids;
  fewer.pop_back();
  EXPECT_THROW(find_swapped_anchors(man, test::handles(landmarks.ids), man, test::handles(fewer), landmarks.names),
               LayoutError);
}

}  // namespace
}  // namespace xparam
