// The anchors' Voronoi cells on a tube, where an anchor at its front and one at its back meet on
// both sides, and the layout tree that must not wind round the tube one way on one mesh and the
// other way on the other: not built from such a pair, and its target paths kept near the source's.
#include "layout/anchor_voronoi.h"
#include "layout/consistent_layout.h"
#include "layout_fixtures.h"
#include "support/prism_meshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace xparam {
namespace {

// A closed tube of radius 1 and height 6 (24 sides, a ring every 0.5), capped by fans.
constexpr int kSides = 24;
constexpr int kMiddleRing = 6;  // z = 3
Mesh tube() {
  std::vector<double> heights;
  for (int r = 0; r <= 12; ++r) heights.push_back(0.5 * r);
  return test::prism(test::regular_polygon(kSides, 1.0), heights);
}

// Vertex at angle 360 * i / 24 degrees on the middle ring (i = 0: the front, +x).
int on_middle_ring(int i) { return kMiddleRing * kSides + i; }
constexpr int kBottom = 13 * kSides;  // the bottom cap's centre
constexpr int kTop = kBottom + 1;     // the top cap's centre

const AnchorNeighbours* pair_of(const AnchorVoronoi& voronoi, int a, int b) {
  for (const AnchorNeighbours& pair : voronoi.neighbours) {
    if (pair.a == a && pair.b == b) return &pair;
  }
  return nullptr;
}

TEST(AnchorVoronoi, CellsMeetingOnBothSidesOfATubeShareTwoStretchesOfBorder) {
  const Mesh mesh = tube();
  // front, back, bottom, top
  const AnchorVoronoi voronoi = anchor_voronoi(mesh, test::handles({on_middle_ring(0), on_middle_ring(12), kBottom, kTop}));
  // The front and back cells make a belt round the tube: the caps' cells do not touch.
  ASSERT_EQ(voronoi.neighbours.size(), 5u);
  EXPECT_EQ(pair_of(voronoi, 2, 3), nullptr);
  const AnchorNeighbours* front_back = pair_of(voronoi, 0, 1);
  ASSERT_NE(front_back, nullptr);
  EXPECT_EQ(front_back->borders, 2);  // at y = 1 and at y = -1
  for (const auto& [a, b] : {std::pair{0, 2}, {0, 3}, {1, 2}, {1, 3}}) {
    const AnchorNeighbours* pair = pair_of(voronoi, a, b);
    ASSERT_NE(pair, nullptr) << a << "-" << b;
    EXPECT_EQ(pair->borders, 1) << a << "-" << b;
  }
}

TEST(AnchorCells, EachVertexLiesInTheCellOfTheAnchorNearestAlongTheEdges) {
  const Mesh mesh = tube();
  const std::vector<VertexHandle> anchors =
      test::handles({on_middle_ring(0), on_middle_ring(12), kBottom, kTop});
  const AnchorVoronoi cells = anchor_cells(mesh, anchors);
  EXPECT_TRUE(cells.neighbours.empty());
  std::vector<std::vector<double>> from_each;
  for (VertexHandle anchor : anchors) from_each.push_back(anchor_cells(mesh, {anchor}).distance);
  for (VertexHandle v : mesh.vertices()) {
    const std::size_t i = static_cast<std::size_t>(v.idx());
    double nearest = std::numeric_limits<double>::infinity();
    for (const std::vector<double>& distance : from_each) nearest = std::min(nearest, distance[i]);
    EXPECT_NEAR(cells.distance[i], nearest, 1e-12) << v.idx();
    EXPECT_NEAR(from_each[cells.cell[i]][i], nearest, 1e-12) << v.idx();
  }
}

// The mean y of layout edge e's chain on one side.
double mean_y(const Layout& layout, int side, int e) {
  const LayoutSide& s = layout.sides[side];
  double sum = 0.0;
  for (const VertexHandle v : s.chains[e]) sum += position(s.mesh, v).y();
  return sum / static_cast<double>(s.chains[e].size());
}

TEST(ConsistentLayout, AnEdgeThatMayPassEitherSideOfATubePassesTheSameSideOnBothMeshes) {
  // The back anchor a little towards +y on the source and towards -y on the target: the shortest
  // path from the front passes at y = 1 on the source and at y = -1 on the target. Traced first,
  // as the shortest candidate, it would make the layout wind round the tube one way on one mesh
  // and the other way on the other.
  const Mesh mesh = tube();
  const auto source_anchors = test::handles({on_middle_ring(0), on_middle_ring(11), kBottom, kTop});
  const auto target_anchors = test::handles({on_middle_ring(0), on_middle_ring(13), kBottom, kTop});
  const ConsistentLayoutResult result = build_consistent_layout(mesh, source_anchors, mesh, target_anchors);
  test::expect_consistent(result.layout, "tube");
  const Layout& layout = result.layout;
  int front_back = -1;
  for (int e = 0; e < static_cast<int>(layout.edges.size()); ++e) {
    const auto [a, b] = layout.edges[e].anchors;
    if (std::min(a, b) == 0 && std::max(a, b) == 1) front_back = e;
  }
  ASSERT_GE(front_back, 0);
  EXPECT_GE(front_back, result.tree_edges) << "the front-back edge is a diagonal, not a tree edge";
  const double source_y = mean_y(layout, 0, front_back);
  const double target_y = mean_y(layout, 1, front_back);
  EXPECT_GT(std::abs(source_y), 0.5);
  EXPECT_GT(source_y * target_y, 0.0) << "source " << source_y << ", target " << target_y;
}

TEST(ConsistentLayout, ATreeEdgeRoundATubeKeepsToTheTemplatesSideOnTheTarget) {
  // The same anchors with the tree in key order: the front-back edge, the shortest pair, is now
  // the first tree edge, traced freely on the source; on the target its path keeps near the
  // source's (the corridor), not on the side its own shortest path would take.
  const Mesh mesh = tube();
  ConsistentLayoutSettings settings;
  settings.unambiguous_tree_first = false;
  const ConsistentLayoutResult result =
      build_consistent_layout(mesh, test::handles({on_middle_ring(0), on_middle_ring(11), kBottom, kTop}), mesh,
                              test::handles({on_middle_ring(0), on_middle_ring(13), kBottom, kTop}), settings);
  test::expect_consistent(result.layout, "tube, tree in key order");
  const Layout& layout = result.layout;
  ASSERT_EQ(std::min(layout.edges[0].anchors[0], layout.edges[0].anchors[1]), 0);
  ASSERT_EQ(std::max(layout.edges[0].anchors[0], layout.edges[0].anchors[1]), 1);
  const double source_y = mean_y(layout, 0, 0);
  const double target_y = mean_y(layout, 1, 0);
  EXPECT_GT(source_y, 0.5);  // the source's back anchor lies towards +y
  EXPECT_GT(target_y, 0.5) << "the target's own shortest path runs at y < 0";
}

}  // namespace
}  // namespace xparam
