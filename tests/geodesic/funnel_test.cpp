#include "geodesic/funnel.h"

#include "geodesic/face_strip.h"
#include "geodesic/test_meshes.h"

#include <gtest/gtest.h>

namespace xparam {
namespace {

Portal portal(int left, Eigen::Vector2d left_point, int right, Eigen::Vector2d right_point) {
  return {VertexHandle(left), VertexHandle(right), left_point, right_point};
}

// Two gates across the x axis: the path must bend up over the first gate's top (its left
// end, seen walking +x) and then down around the second gate's bottom (its right end).
TEST(Funnel, BendsAtTheGateEndsThatBlockTheStraightLine) {
  const std::vector<Portal> portals = {portal(1, {1.0, 0.5}, 2, {1.0, -1.0}),
                                       portal(3, {2.0, 3.0}, 4, {2.0, 2.0})};
  const FunnelApex start{-1, VertexHandle(0), {0.0, 0.0}};
  const FunnelApex end{2, VertexHandle(5), {4.0, 0.0}};
  const std::vector<FunnelApex> path = funnel_path(portals, start, end);
  ASSERT_EQ(path.size(), 4u);
  EXPECT_EQ(path[1].vertex, VertexHandle(1));
  EXPECT_EQ(path[1].portal, 0);
  EXPECT_EQ(path[2].vertex, VertexHandle(4));
  EXPECT_EQ(path[2].portal, 1);
  EXPECT_EQ(path[3].vertex, VertexHandle(5));
}

TEST(Funnel, WideGatesGiveTheStraightSegment) {
  const std::vector<Portal> portals = {portal(1, {1.0, 2.0}, 2, {1.0, -2.0}),
                                       portal(3, {2.0, 2.0}, 4, {2.0, -2.0})};
  const std::vector<FunnelApex> path =
      funnel_path(portals, {-1, VertexHandle(0), {0.0, 0.0}}, {2, VertexHandle(5), {3.0, 1.0}});
  ASSERT_EQ(path.size(), 2u);
}

// A strip fanning around one vertex: the portals all share it, so the path through them may
// pass through that vertex, and it does when the end lies behind it.
TEST(Funnel, PassesThroughTheVertexAStripTurnsAround) {
  const Eigen::Vector2d hub(0.0, 0.0);
  std::vector<Portal> portals;
  // Spokes from the hub (vertex 9, always on the left) at angles 200, 240, ..., 360 degrees;
  // the start lies beyond the first spoke, the end beyond the last: the hub is in the way.
  for (int k = 0; k < 5; ++k) {
    const double angle = (200.0 + 40.0 * k) * M_PI / 180.0;
    portals.push_back(portal(9, hub, k + 1, {std::cos(angle), std::sin(angle)}));
  }
  const FunnelApex start{-1, VertexHandle(0), {-1.0, 0.1}};
  const FunnelApex end{5, VertexHandle(7), {1.0, 0.1}};
  const std::vector<FunnelApex> path = funnel_path(portals, start, end);
  ASSERT_EQ(path.size(), 3u);
  EXPECT_EQ(path[1].vertex, VertexHandle(9));
}

TEST(FaceStrip, UnfoldingKeepsEdgeLengthsAndSharesPortals) {
  std::map<std::array<int, 3>, VertexHandle> index;
  const Mesh cube = test::subdivided_cube(2, &index);
  // The eight faces around the centre vertex of the top side, in rotation order.
  const VertexHandle top = index.at({1, 1, 2});
  HalfedgeHandle h = cube.halfedge_handle(top);
  std::vector<FaceHandle> ring;
  for (int k = 0; k < 8; ++k) {
    ring.push_back(cube.face_handle(h));
    h = cube.opposite_halfedge_handle(cube.prev_halfedge_handle(h));
  }
  const UnfoldedStrip strip = unfold_strip(cube, ring);
  ASSERT_EQ(strip.portals.size(), 7u);
  for (std::size_t k = 0; k < ring.size(); ++k) {
    for (int c = 0; c < 3; ++c) {
      const VertexHandle u = strip.corners[k][c];
      const VertexHandle w = strip.corners[k][(c + 1) % 3];
      EXPECT_NEAR((strip.points[k][c] - strip.points[k][(c + 1) % 3]).norm(),
                  (position(cube, u) - position(cube, w)).norm(), 1e-12);
    }
    // Counter-clockwise in the plane, like on the mesh.
    const Eigen::Vector2d e1 = strip.points[k][1] - strip.points[k][0];
    const Eigen::Vector2d e2 = strip.points[k][2] - strip.points[k][0];
    EXPECT_GT(e1.x() * e2.y() - e1.y() * e2.x(), 0.0);
  }
  for (std::size_t k = 0; k + 1 < ring.size(); ++k) {
    const Portal& p = strip.portals[k];
    EXPECT_NEAR((strip.point(static_cast<int>(k) + 1, p.left) - p.left_point).norm(), 0.0, 1e-12);
    EXPECT_NEAR((strip.point(static_cast<int>(k) + 1, p.right) - p.right_point).norm(), 0.0, 1e-12);
  }
  // Faces around one vertex unfold around one point.
  for (std::size_t k = 1; k < ring.size(); ++k) {
    EXPECT_NEAR((strip.point(static_cast<int>(k), top) - strip.point(0, top)).norm(), 0.0, 1e-12);
  }
}

}  // namespace
}  // namespace xparam
