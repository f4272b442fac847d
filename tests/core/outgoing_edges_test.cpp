#include "core/outgoing_edges.h"

#include <gtest/gtest.h>

#include <array>
#include <cstddef>
#include <utility>
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

// The edges leaving `v`, as (head, slot) pairs.
std::vector<std::pair<int, std::size_t>> leaving(const OutgoingEdges& edges, int v) {
  std::vector<std::pair<int, std::size_t>> listed;
  for (const OutgoingEdges::Edge& edge : edges.leaving(v)) listed.emplace_back(edge.head, edge.slot);
  return listed;
}

TEST(OutgoingEdges, ListsEachVertexsEdgesInTriangleOrderWithTheCornerTheyLeave) {
  const OutgoingEdges edges(kSquare, 5);
  ASSERT_EQ(edges.n_vertices(), 5);
  using Listed = std::vector<std::pair<int, std::size_t>>;
  EXPECT_EQ(leaving(edges, 0), (Listed{{1, 0}, {2, 3}}));  // triangle 0 corner 0, triangle 1 corner 0
  EXPECT_EQ(leaving(edges, 2), (Listed{{0, 2}, {3, 4}}));  // triangle 0 corner 2, triangle 1 corner 1
  EXPECT_TRUE(leaving(edges, 4).empty());
}

TEST(OutgoingEdges, KeepsAnEdgeUsedTwiceInOneDirection) {
  // Two triangles wound alike over one edge (an orientation error the patch check names).
  const OutgoingEdges edges({{0, 1, 2}, {0, 1, 3}}, 4);
  EXPECT_EQ(leaving(edges, 0), (std::vector<std::pair<int, std::size_t>>{{1, 0}, {1, 3}}));
  EXPECT_FALSE(edges.has(1, 0));
}

}  // namespace
}  // namespace xparam
