// Corners that disagree between the two meshes: a mesh laid out against itself agrees at every
// anchor (each anchor's corners sum to a full turn, the same on both sides), and bad arguments
// are refused. Cat/horse, where they do disagree, is in real_pairs_test.cpp.
#include "map/corner_report.h"

#include "core/errors.h"
#include "layout/consistent_layout.h"
#include "layout/layout_fixtures.h"
#include "support/test_data.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace xparam {
namespace {

TEST(MismatchedCorners, AMeshAgainstItselfAgreesAtEveryAnchor) {
  const test::SelfLayout self;
  const Layout& layout = self.built.layout;
  EXPECT_TRUE(mismatched_corners(layout, self.names).empty());
  // With no threshold every anchor is listed, with one corner per curve leaving it.
  const std::vector<CornerMismatch> all = mismatched_corners(layout, self.names, 0.0);
  ASSERT_EQ(static_cast<int>(all.size()), layout.n_anchors);
  std::vector<int> degree(layout.n_anchors, 0);
  for (const LayoutEdge& edge : layout.edges) {
    ++degree[edge.anchors[0]];
    ++degree[edge.anchors[1]];
  }
  for (const CornerMismatch& anchor : all) {
    EXPECT_EQ(anchor.name, self.names[anchor.anchor]);
    ASSERT_EQ(static_cast<int>(anchor.template_degrees.size()), degree[anchor.anchor]);
    ASSERT_EQ(anchor.target_degrees.size(), anchor.template_degrees.size());
    double sum = 0.0;
    for (std::size_t i = 0; i < anchor.template_degrees.size(); ++i) {
      EXPECT_GT(anchor.template_degrees[i], 0.0);
      EXPECT_NEAR(anchor.template_degrees[i], anchor.target_degrees[i], 1e-9);
      sum += anchor.template_degrees[i];
    }
    EXPECT_NEAR(sum, 360.0, 1e-9);
  }
}

TEST(MismatchedCorners, RefusesNamesThatDoNotMatchTheAnchors) {
  const test::SelfLayout self;
  std::vector<std::string> fewer = self.names;
  fewer.pop_back();
  EXPECT_THROW(mismatched_corners(self.built.layout, fewer), ParamError);
}

}  // namespace
}  // namespace xparam
