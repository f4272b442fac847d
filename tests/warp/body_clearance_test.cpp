// The clearance leaves no garment vertex inside (or nearer than E to) a sphere or a box body;
// the signed distance agrees with an independent inside test.
#include "warp/body_clearance.h"

#include "core/closest_point.h"
#include "warp/garment_metrics.h"
#include "support/warp_shapes.h"

#include <gtest/gtest.h>

#include <limits>

namespace xparam {
namespace {

double brute_distance(const TriangleSoup& body, const Eigen::Vector3d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& [a, b, c] : body.triangles)
    best = std::min(best, (closest_point_on_triangle(p, body.vertices[a], body.vertices[b], body.vertices[c]).point - p).norm());
  return best;
}

void expect_clear_of(const TriangleSoup& body, const std::vector<Eigen::Vector3d>& garment, double clearance) {
  for (std::size_t g = 0; g < garment.size(); ++g) {
    EXPECT_LT(test::winding_number(body, garment[g]), 0.5) << "vertex " << g << " is inside";
    EXPECT_GE(brute_distance(body, garment[g]), clearance * (1 - 1e-9)) << "vertex " << g;
  }
}

TEST(BodyDistance, SignAgreesWithTheWindingNumber) {
  const TriangleSoup box = test::box_soup(3, 1.0);
  const BodyDistance distance(box);
  // Points on a lattice through the box, its edges and corners included (exact feature hits).
  for (double x = -1.5; x <= 1.5; x += 0.25) {
    for (double y = -1.5; y <= 1.5; y += 0.5) {
      for (double z = -1.25; z <= 1.5; z += 0.75) {
        const Eigen::Vector3d p(x, y, z);
        const double d = distance.sample(p).signed_distance;
        if (std::abs(d) < 1e-12) continue;  // on the surface: no side
        EXPECT_EQ(d < 0.0, test::winding_number(box, p) > 0.5) << p.transpose();
        EXPECT_NEAR(std::abs(d), brute_distance(box, p), 1e-12);
      }
    }
  }
}

TEST(BodyClearance, SphereGarmentPushedOutOfASphere) {
  const TriangleSoup body = test::sphere_soup(3);
  TriangleSoup garment = test::sphere_soup(2, 1.0);
  // Alternate vertices sink 10 % in and rise 5 % out.
  for (std::size_t g = 0; g < garment.vertices.size(); ++g) garment.vertices[g] *= g % 2 == 0 ? 0.9 : 1.05;
  const BodyDistance distance(body);
  ASSERT_GT(penetration(garment.vertices, distance).count, 10);
  const ClearanceResult result = apply_clearance(garment.vertices, garment.triangles, distance, {0.02});
  EXPECT_EQ(result.still_close, 0);
  EXPECT_GT(result.pushed, 10);
  EXPECT_GE(result.moved, result.pushed);
  EXPECT_EQ(penetration(garment.vertices, distance).count, 0);
  expect_clear_of(body, garment.vertices, 0.02);
}

TEST(BodyClearance, BoxCornersPokingThroughASphereGarment) {
  // A sphere of radius 1.2 round the box [-1, 1]^3: the box's corners (at 1.73) and edges poke
  // through it, so garment vertices sit inside near corners, edges and faces alike.
  const TriangleSoup body = test::box_soup(4, 1.0);
  TriangleSoup garment = test::sphere_soup(3, 1.2);
  const BodyDistance distance(body);
  const Penetration before = penetration(garment.vertices, distance);
  ASSERT_GT(before.count, 20);
  const ClearanceResult result = apply_clearance(garment.vertices, garment.triangles, distance, {0.03});
  EXPECT_EQ(result.still_close, 0);
  EXPECT_GE(result.pushed, before.count);
  EXPECT_GE(result.max_move, before.max_depth + 0.03 - 1e-12);
  expect_clear_of(body, garment.vertices, 0.03);
}

}  // namespace
}  // namespace xparam
