#include "param/point_locator.h"

#include "core/errors.h"
#include "param/patch_parameterization.h"
#include "patch_fixtures.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <random>

namespace xparam {
namespace {

// The reference answer: every triangle in order, nearest wins, lowest index on ties.
PointLocation brute_force(const std::vector<Eigen::Vector2d>& uv,
                          const std::vector<std::array<int, 3>>& triangles, const Eigen::Vector2d& p) {
  PointLocation best;
  best.distance = std::numeric_limits<double>::infinity();
  for (int f = 0; f < static_cast<int>(triangles.size()); ++f) {
    const auto& t = triangles[f];
    PointLocation candidate = nearest_point_in_triangle(p, uv[t[0]], uv[t[1]], uv[t[2]]);
    if (candidate.distance < best.distance) {
      candidate.triangle = f;
      best = candidate;
    }
  }
  return best;
}

Eigen::Vector2d point_of(const std::vector<Eigen::Vector2d>& uv, const std::array<int, 3>& t,
                         const Eigen::Vector3d& bary) {
  return bary[0] * uv[t[0]] + bary[1] * uv[t[1]] + bary[2] * uv[t[2]];
}

// The jittered planar grid and the parameterized hemisphere: two real triangulations.
std::vector<std::pair<std::vector<Eigen::Vector2d>, std::vector<std::array<int, 3>>>> triangulations() {
  const DiskPatch grid = test::planar_grid_patch(30, (Eigen::Matrix2d() << 3.0, 0.5, 0.0, 1.0).finished(), 3);
  std::vector<Eigen::Vector2d> plane;
  for (const auto& p : grid.positions) plane.emplace_back(p.x(), p.y());
  DiskPatch hemisphere = test::hemisphere_patch(20, 60);
  hemisphere.corner_positions = test::even_corner_positions(60, 4);
  hemisphere.polygon = {{0.0, 0.0}, {2.0, 0.0}, {2.5, 1.0}, {-0.5, 1.5}};
  return {{plane, grid.triangles}, {parameterize_patch(hemisphere).uv, hemisphere.triangles}};
}

TEST(NearestPointInTriangle, HandComputed) {
  const Eigen::Vector2d a(0, 0), b(1, 0), c(0, 1);
  PointLocation in = nearest_point_in_triangle({0.25, 0.25}, a, b, c);
  EXPECT_EQ(in.distance, 0.0);
  EXPECT_NEAR((in.bary - Eigen::Vector3d(0.5, 0.25, 0.25)).norm(), 0.0, 1e-15);
  PointLocation beyond_hypotenuse = nearest_point_in_triangle({1, 1}, a, b, c);
  EXPECT_NEAR(beyond_hypotenuse.distance, std::sqrt(0.5), 1e-15);
  EXPECT_NEAR((beyond_hypotenuse.bary - Eigen::Vector3d(0, 0.5, 0.5)).norm(), 0.0, 1e-15);
  PointLocation beyond_corner = nearest_point_in_triangle({-1, -1}, a, b, c);
  EXPECT_NEAR(beyond_corner.distance, std::sqrt(2.0), 1e-15);
  EXPECT_EQ(beyond_corner.bary, Eigen::Vector3d(1, 0, 0));
  // A clockwise triangle gives the same answers (its barycentrics do not depend on orientation).
  in = nearest_point_in_triangle({0.25, 0.25}, a, c, b);
  EXPECT_NEAR((in.bary - Eigen::Vector3d(0.5, 0.25, 0.25)).norm(), 0.0, 1e-15);
  // A degenerate triangle is its sides: (0.5, 1) is 1 above the segment from (0,0) to (1,0).
  PointLocation flat = nearest_point_in_triangle({0.5, 1}, a, b, {2, 0});
  EXPECT_NEAR(flat.distance, 1.0, 1e-15);
  EXPECT_NEAR(point_of({a, b, {2, 0}}, {0, 1, 2}, flat.bary).x(), 0.5, 1e-15);
}

TEST(PointLocator, AgreesWithBruteForceOnRandomPoints) {
  std::mt19937 rng(42);
  for (const auto& [uv, triangles] : triangulations()) {
    const PointLocator locator(uv, triangles);
    Eigen::Vector2d low = uv[0], high = uv[0];
    for (const auto& p : uv) {
      low = low.cwiseMin(p);
      high = high.cwiseMax(p);
    }
    // Queries over a box twice the triangulation's, so many fall outside it.
    const Eigen::Vector2d margin = 0.5 * (high - low);
    std::uniform_real_distribution<double> ux(low.x() - margin.x(), high.x() + margin.x());
    std::uniform_real_distribution<double> uy(low.y() - margin.y(), high.y() + margin.y());
    int inside = 0;
    for (int q = 0; q < 2000; ++q) {
      const Eigen::Vector2d p(ux(rng), uy(rng));
      const PointLocation fast = locator.locate(p);
      const PointLocation slow = brute_force(uv, triangles, p);
      ASSERT_EQ(fast.triangle, slow.triangle) << "query " << q;
      EXPECT_EQ(fast.distance, slow.distance);
      EXPECT_EQ(fast.bary, slow.bary);
      EXPECT_GE(fast.bary.minCoeff(), 0.0);
      EXPECT_NEAR(fast.bary.sum(), 1.0, 1e-14);
      // The reported distance is the distance to the reported point.
      EXPECT_NEAR((point_of(uv, triangles[fast.triangle], fast.bary) - p).norm(), fast.distance, 1e-12);
      inside += fast.distance == 0.0;
    }
    EXPECT_GT(inside, 200);
    EXPECT_LT(inside, 1900);
  }
}

TEST(PointLocator, FindsVerticesEdgesAndBoundaryPointsOffByRounding) {
  for (const auto& [uv, triangles] : triangulations()) {
    const PointLocator locator(uv, triangles);
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int f = 0; f < static_cast<int>(triangles.size()); f += 7) {
      const auto& t = triangles[f];
      // Vertices and edge points: found at (rounding) distance 0 and reproduced by the barycentrics.
      for (int c = 0; c < 3; ++c) {
        const double s = unit(rng);
        for (const Eigen::Vector2d& p :
             {uv[t[c]], Eigen::Vector2d((1 - s) * uv[t[c]] + s * uv[t[(c + 1) % 3]])}) {
          const PointLocation found = locator.locate(p);
          EXPECT_LE(found.distance, 1e-15);
          EXPECT_NEAR((point_of(uv, triangles[found.triangle], found.bary) - p).norm(), 0.0, 1e-14);
          EXPECT_EQ(found.triangle, brute_force(uv, triangles, p).triangle);
        }
      }
    }
    // Boundary edges (used once): points pushed outward by 1e-12 come back with that distance.
    std::map<std::pair<int, int>, int> count;
    for (const auto& t : triangles) {
      for (int c = 0; c < 3; ++c) ++count[{std::min(t[c], t[(c + 1) % 3]), std::max(t[c], t[(c + 1) % 3])}];
    }
    int boundary_tested = 0;
    for (int f = 0; f < static_cast<int>(triangles.size()); ++f) {
      const auto& t = triangles[f];
      for (int c = 0; c < 3; ++c) {
        const int a = t[c], b = t[(c + 1) % 3];
        if (count[{std::min(a, b), std::max(a, b)}] != 1) continue;
        const Eigen::Vector2d edge = uv[b] - uv[a];
        const Eigen::Vector2d outward =
            Eigen::Vector2d(edge.y(), -edge.x()).normalized();  // right of a CCW edge
        const Eigen::Vector2d p = 0.5 * (uv[a] + uv[b]) + 1e-12 * outward;
        const PointLocation found = locator.locate(p);
        EXPECT_EQ(found.triangle, f);
        EXPECT_NEAR(found.distance, 1e-12, 1e-15);
        EXPECT_NEAR(found.bary[c], 0.5, 1e-9);
        EXPECT_NEAR(found.bary[(c + 1) % 3], 0.5, 1e-9);
        ++boundary_tested;
      }
    }
    EXPECT_GT(boundary_tested, 50);
  }
}

TEST(PointLocator, GridResolutionDoesNotChangeAnswers) {
  const auto meshes = triangulations();
  const auto& [uv, triangles] = meshes[1];
  const PointLocator coarse(uv, triangles, {.cells_per_triangle = 0.01});
  const PointLocator fine(uv, triangles, {.cells_per_triangle = 8.0});
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 3.0);
  for (int q = 0; q < 500; ++q) {
    const Eigen::Vector2d p(u(rng), u(rng));
    const PointLocation a = coarse.locate(p), b = fine.locate(p);
    EXPECT_EQ(a.triangle, b.triangle);
    EXPECT_EQ(a.bary, b.bary);
  }
}

TEST(PointLocator, RejectsBadInput) {
  EXPECT_THROW(PointLocator({{0, 0}}, {}), ParamError);
  EXPECT_THROW(PointLocator({{0, 0}, {1, 0}, {0, 1}}, {{0, 1, 3}}), ParamError);
  EXPECT_THROW(PointLocator({{0, 0}, {1, 0}, {0, std::nan("")}}, {{0, 1, 2}}), ParamError);
}

}  // namespace
}  // namespace xparam
