// A garment is kept out of the target's own surface, not of its remesh: the remesh's chords cut
// inside a curved body (a sagitta), so a vertex can be outside the remesh and inside the body.
#include "warp/garment_warp.h"

#include "support/warp_shapes.h"

#include <gtest/gtest.h>

namespace xparam {
namespace {

TEST(GarmentWarp, PenetrationIsMeasuredOnTheTargetsOwnSurface) {
  // The template and its image (the identity map): a coarse sphere, 18 vertices on the unit
  // sphere, its faces' middles about 0.1 inside; the target's own surface: a fine unit sphere.
  const TriangleSoup coarse = test::sphere_soup(1);
  const TriangleSoup fine = test::sphere_soup(5);
  // A garment shell at 0.985: inside the true sphere everywhere, outside the coarse chords over
  // the middle of their faces.
  TriangleSoup garment = test::sphere_soup(3);
  for (Eigen::Vector3d& p : garment.vertices) p *= 0.985;
  int outside_chords = 0;
  for (const Eigen::Vector3d& p : garment.vertices) {
    ASSERT_GT(test::winding_number(fine, p), 0.5);
    outside_chords += test::winding_number(coarse, p) < 0.5 ? 1 : 0;
  }
  ASSERT_GT(outside_chords, 0);
  const auto n = static_cast<int>(garment.vertices.size());
  ASSERT_LT(outside_chords, n);

  const GarmentBinding binding = bind_garment(coarse, garment.vertices);
  WarpTarget on_remesh{"sphere", coarse};
  WarpTarget on_surface{"sphere", coarse, fine};
  // Against the remesh only the vertices under its chords count; against the surface, all.
  const WarpedGarment remesh = warp_garment(garment, binding, on_remesh, {});
  EXPECT_FALSE(remesh.against_surface);
  EXPECT_EQ(remesh.placed_penetration.count, n - outside_chords);
  const WarpedGarment surface = warp_garment(garment, binding, on_surface, {});
  EXPECT_TRUE(surface.against_surface);
  EXPECT_EQ(surface.placed_penetration.count, n);
  EXPECT_NEAR(surface.placed_penetration.max_depth, 0.015, 1e-3);  // the fine sphere's sagitta is below 1e-3
  // Placing is the same either way: on the image.
  for (int g = 0; g < n; ++g) EXPECT_EQ(surface.vertices[g], remesh.vertices[g]) << g;

  // The clearance pushes every vertex out of the surface itself, to E and beyond.
  WarpSettings clear;
  clear.clearance = ClearanceSettings{0.004};
  const WarpedGarment cleared = warp_garment(garment, binding, on_surface, clear);
  EXPECT_EQ(cleared.penetration.count, 0);
  EXPECT_EQ(cleared.clearance->pushed, n);
  EXPECT_EQ(cleared.clearance->still_close, 0);
  for (const Eigen::Vector3d& p : cleared.vertices) EXPECT_GT(p.norm(), 1.0 + 0.004 * (1 - 1e-9) - 1e-3);
}

}  // namespace
}  // namespace xparam
