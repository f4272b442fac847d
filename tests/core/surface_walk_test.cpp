#include "core/surface_walk.h"

#include <gtest/gtest.h>

#include <cmath>

namespace xparam {
namespace {

// An n x n grid of squares over [0, 1]^2 in z = 0, bent by `fold` radians about the line x = 0.5
// (the half x > 0.5 tilts up): a crease a straight walk must unfold.
Mesh bent_grid(int n, double fold) {
  Mesh mesh;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const double x = static_cast<double>(i) / n;
      const double y = static_cast<double>(j) / n;
      if (x <= 0.5) {
        mesh.add_vertex({x, y, 0.0});
      } else {
        mesh.add_vertex({0.5 + (x - 0.5) * std::cos(fold), y, (x - 0.5) * std::sin(fold)});
      }
    }
  }
  const auto id = [n](int i, int j) { return VertexHandle(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      mesh.add_face(id(i, j), id(i + 1, j), id(i + 1, j + 1));
      mesh.add_face(id(i, j), id(i + 1, j + 1), id(i, j + 1));
    }
  }
  return mesh;
}

// The surface point of `mesh` at vertex `v`: a face of v, barycentric 1 at v's corner.
SurfacePoint at_vertex(const Mesh& mesh, int v) {
  const FaceHandle face = *mesh.vf_range(mesh.vertex_handle(v)).begin();
  SurfacePoint point{face.idx(), Eigen::Vector3d::Zero()};
  int corner = 0;
  for (VertexHandle u : mesh.fv_range(face)) {
    if (u.idx() == v) point.bary[corner] = 1.0;
    ++corner;
  }
  return point;
}

TEST(SurfaceWalk, OnAPlaneItEndsWhereTheStepDoes) {
  const Mesh plane = bent_grid(10, 0.0);
  const SurfacePoint start{44, Eigen::Vector3d(0.2, 0.3, 0.5)};
  const Eigen::Vector3d step(0.31, -0.17, 0.0);
  const std::optional<SurfacePoint> end = SurfaceWalker(plane).walk(start, step);
  ASSERT_TRUE(end);
  EXPECT_LT((position(plane, *end) - (position(plane, start) + step)).norm(), 1e-12);
  EXPECT_GE(end->bary.minCoeff(), 0.0);
  EXPECT_NEAR(end->bary.sum(), 1.0, 1e-12);
}

TEST(SurfaceWalk, AcrossACreaseItKeepsTheLengthAndTheAngleToTheCrease) {
  const double fold = 1.0;
  const Mesh bent = bent_grid(8, fold);
  const int v = 4 * 9 + 1;  // vertex (1, 4): (0.125, 0.5, 0) on the flat half
  // Walk 0.6 along x and 0.1 along y: 0.375 on the flat half, the rest up the tilted one.
  const std::optional<SurfacePoint> end = SurfaceWalker(bent).walk(at_vertex(bent, v), {0.6, 0.1, 0.0});
  ASSERT_TRUE(end);
  const double up = 0.6 - 0.375;  // the x part of the step left after the crease
  const Eigen::Vector3d expected(0.5 + up * std::cos(fold), 0.6, up * std::sin(fold));
  EXPECT_LT((position(bent, *end) - expected).norm(), 1e-12);
}

TEST(SurfaceWalk, ThroughAVertexItGoesOn) {
  const Mesh plane = bent_grid(4, 0.0);
  const int v = 2 * 5 + 2;  // the centre vertex (0.5, 0.5)
  const std::optional<SurfacePoint> end = SurfaceWalker(plane).walk(at_vertex(plane, 0), {0.7, 0.7, 0.0});
  ASSERT_TRUE(end);
  EXPECT_LT((position(plane, *end) - Eigen::Vector3d(0.7, 0.7, 0.0)).norm(), 1e-12);
  const std::optional<SurfacePoint> from_centre =
      SurfaceWalker(plane).walk(at_vertex(plane, v), {-0.3, 0.1, 0.0});
  ASSERT_TRUE(from_centre);
  EXPECT_LT((position(plane, *from_centre) - Eigen::Vector3d(0.2, 0.6, 0.0)).norm(), 1e-12);
}

TEST(SurfaceWalk, StopsAtTheBoundary) {
  const Mesh plane = bent_grid(4, 0.0);
  EXPECT_FALSE(SurfaceWalker(plane).walk(at_vertex(plane, 6), {2.0, 0.0, 0.0}));
}

}  // namespace
}  // namespace xparam
