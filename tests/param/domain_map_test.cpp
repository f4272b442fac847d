#include "param/domain_map.h"

#include "core/errors.h"
#include "param/convex_polygon.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

namespace xparam {
namespace {

// A random strictly convex k-gon: sorted angles on a random ellipse, rotated and moved.
std::vector<Eigen::Vector2d> random_convex_polygon(std::mt19937& rng, int k) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  while (true) {
    std::vector<double> t;
    for (int i = 0; i < k; ++i) t.push_back(2 * std::numbers::pi * unit(rng));
    std::sort(t.begin(), t.end());
    const double rx = 0.3 + 2 * unit(rng), ry = 0.3 + 2 * unit(rng), turn = 2 * std::numbers::pi * unit(rng);
    const Eigen::Vector2d shift(4 * unit(rng) - 2, 4 * unit(rng) - 2);
    std::vector<Eigen::Vector2d> polygon;
    for (double ti : t) {
      const Eigen::Vector2d e(rx * std::cos(ti), ry * std::sin(ti));
      polygon.push_back(Eigen::Vector2d(std::cos(turn) * e.x() - std::sin(turn) * e.y(),
                                        std::sin(turn) * e.x() + std::cos(turn) * e.y()) +
                        shift);
    }
    // Keep polygons that are clearly convex (no corner flatter than ~3 degrees) and have no
    // tiny side (a grid squeezed against a tiny side is too coarse to show the smooth map).
    bool clear = is_strictly_convex(polygon);
    double perimeter = 0.0;
    for (int i = 0; i < k; ++i) perimeter += (polygon[(i + 1) % k] - polygon[i]).norm();
    for (int i = 0; i < k && clear; ++i) {
      const Eigen::Vector2d a = polygon[(i + 1) % k] - polygon[i];
      const Eigen::Vector2d b = polygon[(i + 2) % k] - polygon[(i + 1) % k];
      clear =
          signed_area2(polygon[i], polygon[(i + 1) % k], polygon[(i + 2) % k]) > 0.05 * a.norm() * b.norm() &&
          a.norm() > 0.2 * perimeter / k;
    }
    if (clear) return polygon;
  }
}

// Bilinear grid of (n+1)^2 points in a convex quad, and its triangles.
void quad_grid(const std::vector<Eigen::Vector2d>& q, int n, std::vector<Eigen::Vector2d>& points,
               std::vector<std::array<int, 3>>& triangles) {
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const double s = static_cast<double>(i) / n, t = static_cast<double>(j) / n;
      points.push_back((1 - s) * (1 - t) * q[0] + s * (1 - t) * q[1] + s * t * q[2] + (1 - s) * t * q[3]);
    }
  }
  auto id = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
}

TEST(Wachspress, PartitionOfUnityLinearPrecisionAndBoundaryBehaviour) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int k = 3; k <= 7; ++k) {
    for (int trial = 0; trial < 20; ++trial) {
      const auto polygon = random_convex_polygon(rng, k);
      // A random interior point: a convex combination of the corners.
      Eigen::VectorXd mix(k);
      for (int i = 0; i < k; ++i) mix[i] = unit(rng) + 0.01;
      mix /= mix.sum();
      Eigen::Vector2d p = Eigen::Vector2d::Zero();
      for (int i = 0; i < k; ++i) p += mix[i] * polygon[i];
      const Eigen::VectorXd w = wachspress_coordinates(polygon, p);
      EXPECT_NEAR(w.sum(), 1.0, 1e-14);
      EXPECT_GT(w.minCoeff(), 0.0);  // positive inside a convex polygon
      Eigen::Vector2d back = Eigen::Vector2d::Zero();
      for (int i = 0; i < k; ++i) back += w[i] * polygon[i];
      EXPECT_NEAR((back - p).norm(), 0.0, 1e-13);
      // At a corner: the unit vector; on a side: linear between its two corners, zero elsewhere.
      const int c = trial % k;
      const Eigen::VectorXd at_corner = wachspress_coordinates(polygon, polygon[c]);
      for (int i = 0; i < k; ++i) EXPECT_EQ(at_corner[i], i == c ? 1.0 : 0.0);
      const double s = unit(rng);
      const Eigen::VectorXd on_side =
          wachspress_coordinates(polygon, (1 - s) * polygon[c] + s * polygon[(c + 1) % k]);
      for (int i = 0; i < k; ++i) {
        const double expected = i == c ? 1 - s : (i == (c + 1) % k ? s : 0.0);
        EXPECT_NEAR(on_side[i], expected, 1e-12);
      }
    }
  }
}

TEST(Wachspress, TriangleCoordinatesAreBarycentric) {
  const std::vector<Eigen::Vector2d> t = {{0.0, 0.0}, {4.0, 0.0}, {1.0, 3.0}};
  const Eigen::VectorXd w = wachspress_coordinates(t, {1.5, 1.0});
  // Hand-computed: areas opposite each corner over the total area 6.
  EXPECT_NEAR(w[0], (0.5 * std::abs((4.0 - 1.5) * (3.0 - 1.0) - (0.0 - 1.0) * (1.0 - 1.5))) / 6.0, 1e-15);
  EXPECT_NEAR(w[1], (0.5 * 1.5 * 3.0 - 0.5 * 1.0 * 1.0) / 6.0, 1e-15);
  EXPECT_NEAR(w[2], (0.5 * 4.0 * 1.0) / 6.0, 1e-15);
}

TEST(DomainMap, AffineForTrianglesIsExact) {
  const std::vector<Eigen::Vector2d> from = {{0.0, 0.0}, {2.0, 0.0}, {0.0, 1.0}};
  const std::vector<Eigen::Vector2d> to = {{1.0, 1.0}, {1.0, 3.0}, {-2.0, 1.0}};
  const DomainMap map(from, to);
  EXPECT_TRUE(map.is_affine());
  // Hand-computed: (x, y) -> (1 - 3y, 1 + x).
  for (const Eigen::Vector2d& p :
       {Eigen::Vector2d(0.5, 0.25), Eigen::Vector2d(1.0, 0.5), Eigen::Vector2d(0.1, 0.8)}) {
    const Eigen::Vector2d q = map(p);
    EXPECT_NEAR(q.x(), 1.0 - 3.0 * p.y(), 1e-15);
    EXPECT_NEAR(q.y(), 1.0 + p.x(), 1e-15);
  }
  for (int i = 0; i < 3; ++i) EXPECT_NEAR((map(from[i]) - to[i]).norm(), 0.0, 1e-15);
}

TEST(DomainMap, CornersToCornersAndSidesToSides) {
  std::mt19937 rng(5);
  for (int k = 4; k <= 6; ++k) {
    const auto from = random_convex_polygon(rng, k);
    const auto to = random_convex_polygon(rng, k);
    const DomainMap map(from, to);
    EXPECT_FALSE(map.is_affine());
    for (int i = 0; i < k; ++i) {
      EXPECT_EQ(map(from[i]), to[i]);
      // A point at fraction s of side i lands at fraction s of the target's side i.
      const Eigen::Vector2d on_side = 0.7 * from[i] + 0.3 * from[(i + 1) % k];
      EXPECT_NEAR((map(on_side) - (0.7 * to[i] + 0.3 * to[(i + 1) % k])).norm(), 0.0, 1e-12);
    }
  }
}

TEST(DomainMap, SamePolygonGivesTheIdentity) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto quad = random_convex_polygon(rng, 4);
  const DomainMap map(quad, quad);
  for (int trial = 0; trial < 50; ++trial) {
    const double a = unit(rng), b = unit(rng);
    const Eigen::Vector2d p =
        (1 - a) * (1 - b) * quad[0] + a * (1 - b) * quad[1] + a * b * quad[2] + (1 - a) * b * quad[3];
    EXPECT_NEAR((map(p) - p).norm(), 0.0, 1e-13);
  }
}

TEST(DomainMap, GridKeepsItsOrientationBetweenRandomConvexQuads) {
  std::mt19937 rng(20261123);
  int smallest_ratio_trial = -1;
  double smallest_ratio = 1e300;
  for (int trial = 0; trial < 300; ++trial) {
    const auto from = random_convex_polygon(rng, 4);
    const auto to = random_convex_polygon(rng, 4);
    std::vector<Eigen::Vector2d> points;
    std::vector<std::array<int, 3>> triangles;
    quad_grid(from, 24, points, triangles);
    const DomainMap map(from, to);
    std::vector<Eigen::Vector2d> images;
    for (const auto& p : points) images.push_back(map(p));
    for (const auto& t : triangles) {
      const double before = signed_area2(points[t[0]], points[t[1]], points[t[2]]);
      ASSERT_GT(before, 0.0);
      const double after = signed_area2(images[t[0]], images[t[1]], images[t[2]]);
      ASSERT_GT(after, 0.0) << "trial " << trial << ": a grid triangle flipped";
      if (after / before < smallest_ratio) {
        smallest_ratio = after / before;
        smallest_ratio_trial = trial;
      }
    }
  }
  EXPECT_GT(smallest_ratio, 0.0) << "worst trial " << smallest_ratio_trial;
}

TEST(DomainMap, JacobianIsPositiveEverywhereEvenForExtremeQuads) {
  // Floater & Kosinka's theorem is about the smooth map: check det(J) > 0 by central
  // differences on a fine sampling of quads with a tiny side and a nearly flat corner.
  const std::vector<std::vector<Eigen::Vector2d>> quads = {
      {{1.74775, -1.62282}, {2.12758, 0.256028}, {2.12604, 0.255803}, {1.85769, 0.175017}},
      {{0.0, 0.0}, {4.0, 0.0}, {4.0, 0.01}, {0.0, 1.0}},
      {{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {0.0, 1.0}},
      {{-0.3, -1.1}, {0.74, 0.35}, {0.45, 0.31}, {0.05, 0.17}}};
  for (std::size_t i = 0; i < quads.size(); ++i) {
    for (std::size_t j = 0; j < quads.size(); ++j) {
      const DomainMap map(quads[i], quads[j]);
      const auto& q = quads[i];
      const int n = 60;
      for (int b = 1; b < n; ++b) {
        for (int a = 1; a < n; ++a) {
          const double s = static_cast<double>(a) / n, t = static_cast<double>(b) / n;
          const Eigen::Vector2d p =
              (1 - s) * (1 - t) * q[0] + s * (1 - t) * q[1] + s * t * q[2] + (1 - s) * t * q[3];
          const double h = 1e-7;
          const Eigen::Vector2d dx = map(p + Eigen::Vector2d(h, 0)) - map(p - Eigen::Vector2d(h, 0));
          const Eigen::Vector2d dy = map(p + Eigen::Vector2d(0, h)) - map(p - Eigen::Vector2d(0, h));
          ASSERT_GT(dx.x() * dy.y() - dx.y() * dy.x(), 0.0)
              << "quad " << i << " -> " << j << " at " << s << ", " << t;
        }
      }
    }
  }
}

TEST(DomainMap, RejectsMismatchedOrConcaveDomains) {
  const std::vector<Eigen::Vector2d> square = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const std::vector<Eigen::Vector2d> triangle = {{0, 0}, {1, 0}, {0, 1}};
  const std::vector<Eigen::Vector2d> dart = {{0, 0}, {2, 0}, {0.5, 0.5}, {0, 2}};
  const std::vector<Eigen::Vector2d> clockwise = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
  EXPECT_THROW(DomainMap(square, triangle), ParamError);
  EXPECT_THROW(DomainMap(square, dart), ParamError);
  EXPECT_THROW(DomainMap(dart, square), ParamError);
  EXPECT_THROW(DomainMap(square, clockwise), ParamError);
  EXPECT_NO_THROW(DomainMap(square, square));
}

}  // namespace
}  // namespace xparam
