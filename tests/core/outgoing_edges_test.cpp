#include "core/outgoing_edges.h"

#include <gtest/gtest.h>

#include <array>
#include <vector>

namespace xparam {
namespace {

// A square (0, 1, 2, 3) split along its diagonal 0-2, both triangles counter-clockwise, and
// vertex 4 used by no triangle.
const std::vector<std::array<int, 3>> kSquare = {{0, 1, 2}, {0, 2, 3}};

TEST(OutgoingEdges, AnInnerEdgeHasItsTwinAndABoundaryEdgeHasNone) {
  const OutgoingEdges edges(kSquare, 5);
  EXPECT_TRUE(edges.has(0, 2));
  EXPECT_TRUE(edges.has(2, 0));
  EXPECT_TRUE(edges.has(0, 1));
  EXPECT_FALSE(edges.has(1, 0));
  EXPECT_FALSE(edges.has(1, 3));
  EXPECT_FALSE(edges.has(4, 0));
}

TEST(OutgoingEdges, ListsEachVertexsEdgesInTriangleOrderWithTheCornerTheyLeave) {
  const OutgoingEdges edges(kSquare, 5);
  ASSERT_EQ(edges.n_vertices(), 5);
  const auto from_0 = edges.leaving(0);
  ASSERT_EQ(from_0.size(), 2u);
  EXPECT_EQ(from_0[0].head, 1);
  EXPECT_EQ(from_0[0].slot, 0u);  // triangle 0, corner 0
  EXPECT_EQ(from_0[1].head, 2);
  EXPECT_EQ(from_0[1].slot, 3u);  // triangle 1, corner 0
  const auto from_2 = edges.leaving(2);
  ASSERT_EQ(from_2.size(), 2u);
  EXPECT_EQ(from_2[0].head, 0);
  EXPECT_EQ(from_2[0].slot, 2u);  // triangle 0, corner 2
  EXPECT_EQ(from_2[1].head, 3);
  EXPECT_EQ(from_2[1].slot, 4u);  // triangle 1, corner 1
  EXPECT_TRUE(edges.leaving(4).empty());
}

TEST(OutgoingEdges, KeepsAnEdgeUsedTwiceInOneDirection) {
  // Two triangles wound alike over one edge (an orientation error the patch check names).
  const OutgoingEdges edges({{0, 1, 2}, {0, 1, 3}}, 4);
  const auto from_0 = edges.leaving(0);
  ASSERT_EQ(from_0.size(), 2u);
  EXPECT_EQ(from_0[0].head, 1);
  EXPECT_EQ(from_0[1].head, 1);
  EXPECT_FALSE(edges.has(1, 0));
}

}  // namespace
}  // namespace xparam
