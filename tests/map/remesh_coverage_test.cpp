#include "map/remesh_coverage.h"

#include "layout/layout_fixtures.h"

#include <gtest/gtest.h>

#include <cmath>

namespace xparam {
namespace {

std::vector<Eigen::Vector3d> positions_of(const Mesh& mesh) {
  std::vector<Eigen::Vector3d> points;
  for (VertexHandle v : mesh.vertices()) points.push_back(position(mesh, v));
  return points;
}

TEST(RemeshCoverage, ARemeshOnTheTargetCoversEveryVertex) {
  const Mesh target = test::subdivided_octahedron(3);
  const RemeshCoverage coverage = measure_remesh_coverage(target, positions_of(target), triangles_of(target));
  EXPECT_EQ(coverage.uncovered_vertices, 0);
  EXPECT_EQ(coverage.max_gap, 0.0);
  EXPECT_EQ(coverage.uncovered_area, 0.0);
}

// The octahedron with its +z corner (vertex 4) pulled down to (0, 0, 0.5): the target's corner
// is 0.5 from the remesh (its nearest remesh point is the lowered apex, as the four faces round
// it slope away), every other vertex 0. Area 4 sqrt(3) (eight equilateral faces of edge sqrt 2);
// the corner's share is a third of its four faces: 1/6.
TEST(RemeshCoverage, ACutOffTipIsMeasuredFromTheTarget) {
  const Mesh target = test::subdivided_octahedron(1);
  std::vector<Eigen::Vector3d> remesh = positions_of(target);
  remesh[4] = Eigen::Vector3d(0.0, 0.0, 0.5);
  const RemeshCoverage coverage = measure_remesh_coverage(target, remesh, triangles_of(target));
  ASSERT_EQ(coverage.gap.size(), 6u);
  EXPECT_NEAR(coverage.gap[4], 0.5, 1e-12);
  for (int v : {0, 1, 2, 3, 5}) EXPECT_NEAR(coverage.gap[v], 0.0, 1e-12) << v;
  EXPECT_NEAR(coverage.max_gap, 0.5 / std::sqrt(4.0 * std::sqrt(3.0)), 1e-12);
  EXPECT_EQ(coverage.uncovered_vertices, 1);
  EXPECT_NEAR(coverage.uncovered_area, 1.0 / 6.0, 1e-12);
}

}  // namespace
}  // namespace xparam
