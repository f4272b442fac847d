#include "measure/plane_section.h"

#include "support/prism_meshes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace xparam {
namespace {

TEST(PlaneSection, BoxCutAcrossIsItsPerimeter) {
  const double a = 0.3, b = 0.2;
  const Mesh box = test::prism({{-a / 2, -b / 2}, {a / 2, -b / 2}, {a / 2, b / 2}, {-a / 2, b / 2}}, {0.0, 1.0});
  const std::vector<SectionLoop> loops = plane_section(box, {0, 0, 0.37}, {0, 0, 1});
  ASSERT_EQ(loops.size(), 1U);
  EXPECT_TRUE(loops[0].closed);
  EXPECT_NEAR(loops[0].length(), 2 * (a + b), 1e-12);
}

TEST(PlaneSection, TiltedPlaneCutsTheBoxInALongerRectangle) {
  // Tilted about x by theta, the plane cuts the side faces in a rectangle a x b / cos(theta).
  const double a = 0.3, b = 0.2, theta = 0.4;
  const Mesh box = test::prism({{-a / 2, -b / 2}, {a / 2, -b / 2}, {a / 2, b / 2}, {-a / 2, b / 2}}, {0.0, 1.0});
  const Eigen::Vector3d normal(0, -std::sin(theta), std::cos(theta));
  const std::vector<SectionLoop> loops = plane_section(box, {0, 0, 0.5}, normal);
  ASSERT_EQ(loops.size(), 1U);
  EXPECT_NEAR(loops[0].length(), 2 * (a + b / std::cos(theta)), 1e-12);
}

TEST(PlaneSection, PlaneBesideTheSurfaceCutsNothing) {
  const Mesh cylinder = test::prism(test::regular_polygon(32, 1.0), {0.0, 2.0});
  EXPECT_TRUE(plane_section(cylinder, {0, 0, 3.0}, {0, 0, 1}).empty());
}

TEST(PlaneSection, ConvexHullOfAStarIsThePolygonOfItsTips) {
  // A five-pointed star: tips at radius 1, notches at radius 0.4.
  const int k = 5;
  std::vector<Eigen::Vector2d> star;
  for (int i = 0; i < 2 * k; ++i) {
    const double r = i % 2 == 0 ? 1.0 : 0.4;
    const double angle = M_PI * i / k;
    star.emplace_back(r * std::cos(angle), r * std::sin(angle));
  }
  const Mesh prism = test::prism(star, {0.0, 1.0});
  const std::vector<SectionLoop> loops = plane_section(prism, {0, 0, 0.5}, {0, 0, 1});
  ASSERT_EQ(loops.size(), 1U);
  EXPECT_NEAR(loops[0].length(), 2 * k * (star[1] - star[0]).norm(), 1e-12);
  EXPECT_NEAR(convex_hull_perimeter(loops[0].points, {0, 0, 1}), 2 * k * std::sin(M_PI / k), 1e-12);
}

TEST(PlaneSection, HullOfTwoPointsGoesThereAndBack) {
  EXPECT_NEAR(convex_hull_perimeter({{0, 0, 0}, {3, 4, 0}}, {0, 0, 1}), 10.0, 1e-12);
  EXPECT_EQ(convex_hull_perimeter({{1, 2, 3}}, {0, 0, 1}), 0.0);
}

TEST(PlaneSection, DistanceToLoopIsToItsNearestSegment) {
  SectionLoop square{{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, true};
  EXPECT_NEAR(distance_to_loop(square, {0.5, -2, 0}), 2.0, 1e-12);
  EXPECT_NEAR(distance_to_loop(square, {-0.5, 0.5, 0}), 0.5, 1e-12);  // the closing segment counts
  square.closed = false;
  EXPECT_NEAR(distance_to_loop(square, {-0.5, 0.5, 0}), std::hypot(0.5, 0.5), 1e-12);
}

}  // namespace
}  // namespace xparam
