// Geodesic lengths on prisms, against the unrolled surface: a prism's side is developable, so the
// shortest path between two side points is the straight line of the unrolled side (exact on the
// polyhedron, within the polygon's shortfall of the smooth cylinder), and on a flat cap it is the
// straight distance.
#include "measure/surface_geodesic.h"

#include "measure/body_measurements.h"
#include "support/prism_meshes.h"

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include <cmath>

namespace xparam {
namespace {

// A point of the side of test::prism(regular_polygon(n, r), ...): `along` sides round from
// polygon vertex 0 (fractions lie inside a side), at height z.
Eigen::Vector3d side_point(int n, double r, double along, double z) {
  const int i = static_cast<int>(std::floor(along));
  const double t = along - i;
  const auto corner = [&](int k) {
    const double angle = 2.0 * M_PI * k / n;
    return Eigen::Vector3d(r * std::cos(angle), r * std::sin(angle), z);
  };
  return (1.0 - t) * corner(i) + t * corner(i + 1);
}

TEST(SurfaceGeodesic, BetweenSideVerticesOfAPrismIsTheUnrolledHelix) {
  const int n = 64;
  const double r = 0.2;
  const Mesh prism = test::prism(test::regular_polygon(n, r), {0.0, 0.5, 1.0, 1.5, 2.0});
  // Ring 1 vertex 0 to ring 3 vertex 9: 9 sides round, 1.0 up, far from both caps.
  const double side = 2.0 * r * std::sin(M_PI / n);
  const double unrolled = std::hypot(9 * side, 1.0);
  const SurfaceGeodesic g = surface_geodesic(
      prism, {position(prism, VertexHandle(n)), position(prism, VertexHandle(3 * n + 9))}, false);
  EXPECT_TRUE(g.converged);
  EXPECT_NEAR(g.length, unrolled, 1e-12);
  // The smooth cylinder's helix sqrt((r dtheta)^2 + dz^2) is longer by at most the 9 arcs' excess
  // over their chords (the polygon's shortfall).
  const double helix = std::hypot(r * 2.0 * M_PI * 9 / n, 1.0);
  EXPECT_GT(helix, g.length);
  EXPECT_LT(helix - g.length, 9 * (r * 2.0 * M_PI / n - side) + 1e-12);
  // Dijkstra's edge path is a staircase of side edges and diagonals: the funnel shortened it.
  EXPECT_GT(g.edge_path_length, 1.05 * g.length);
  ASSERT_EQ(g.segment_lengths.size(), 1U);
  EXPECT_LT(g.max_point_distance, 1e-15);
}

TEST(SurfaceGeodesic, BetweenPointsInsideSideFacesIsTheUnrolledLine) {
  const int n = 64;
  const double r = 0.2;
  const Mesh prism = test::prism(test::regular_polygon(n, r), {0.0, 0.5, 1.0, 1.5, 2.0});
  // Neither point is a vertex: 3.25 sides round at z = 0.7, 20.6 sides round at z = 1.35.
  const double side = 2.0 * r * std::sin(M_PI / n);
  const SurfaceGeodesic g =
      surface_geodesic(prism, {side_point(n, r, 3.25, 0.7), side_point(n, r, 20.6, 1.35)}, false);
  EXPECT_NEAR(g.length, std::hypot((20.6 - 3.25) * side, 0.65), 1e-12);
  // A point off the surface is measured at its nearest surface point: pushed out along side 3's
  // normal (half way round it), the same value.
  const double normal_angle = 2.0 * M_PI * 3.5 / n;
  const Eigen::Vector3d outward = 0.01 * Eigen::Vector3d(std::cos(normal_angle), std::sin(normal_angle), 0.0);
  const SurfaceGeodesic off =
      surface_geodesic(prism, {side_point(n, r, 3.25, 0.7) + outward, side_point(n, r, 20.6, 1.35)}, false);
  EXPECT_NEAR(off.length, g.length, 1e-12);
  EXPECT_NEAR(off.max_point_distance, 0.01, 1e-12);
}

TEST(SurfaceGeodesic, OnAFlatCapIsTheStraightDistance) {
  // A box: the square |x| + |y| <= 1 extruded from z = 0 to 1; its top cap is a fan of four triangles.
  const Mesh box = test::prism(test::regular_polygon(4, 1.0), {0.0, 1.0});
  const Eigen::Vector3d a(0.3, 0.1, 1.0), b(-0.2, -0.4, 1.0), c(0.1, 0.5, 1.0);
  EXPECT_NEAR(surface_geodesic(box, {a, b}, false).length, (b - a).norm(), 1e-12);
  // A closed triangle on the cap: its perimeter.
  const SurfaceGeodesic closed = surface_geodesic(box, {a, b, c}, true);
  EXPECT_NEAR(closed.length, (b - a).norm() + (c - b).norm() + (a - c).norm(), 1e-12);
  ASSERT_EQ(closed.segment_lengths.size(), 3U);
  EXPECT_NEAR(closed.segment_lengths[2], (a - c).norm(), 1e-12);
  // Over the cap's edge: (0.5, 0.5, 1) on the rim to (0.5, 0.5, 0.4) down the side face is 0.6.
  EXPECT_NEAR(
      surface_geodesic(box, {Eigen::Vector3d(0.2, 0.2, 1.0), Eigen::Vector3d(0.5, 0.5, 0.4)}, false).length,
      std::sqrt(0.18) + 0.6, 1e-12);
}

TEST(SurfaceGeodesic, ClosedRoundAPrismIsThePolygonsPerimeter) {
  const int n = 48;
  const double r = 0.2;
  const Mesh prism = test::prism(test::regular_polygon(n, r), {0.0, 1.0, 2.0});
  // Three middle-ring vertices a third of the way round each other: the tape goes round the
  // ring, not over a cap (at least 2 up and down).
  const SurfaceGeodesic g =
      surface_geodesic(prism,
                       {position(prism, VertexHandle(n)), position(prism, VertexHandle(n + 16)),
                        position(prism, VertexHandle(n + 32))},
                       true);
  const double perimeter = n * 2.0 * r * std::sin(M_PI / n);
  EXPECT_NEAR(g.length, perimeter, 1e-12);
  // The straight closed polyline through the same points cuts across: three chords of 120 degrees.
  EXPECT_NEAR(3 * r * std::sqrt(3.0), 1.039, 1e-3);
  EXPECT_GT(g.length, 3 * r * std::sqrt(3.0) + 0.1);
}

TEST(SurfaceGeodesic, PointsOnPartsNoPathJoinsGiveNaN) {
  const Mesh one = test::prism(test::regular_polygon(8, 1.0), {0.0, 1.0});
  Mesh both = one;
  const Mesh other = test::prism(test::regular_polygon(8, 1.0), {0.0, 1.0}, {5.0, 0.0, 0.0});
  std::vector<VertexHandle> added;
  for (const VertexHandle v : other.vertices()) added.push_back(both.add_vertex(other.point(v)));
  for (const FaceHandle f : other.faces()) {
    std::vector<VertexHandle> corners;
    for (const VertexHandle v : other.fv_range(f))
      corners.push_back(added[static_cast<std::size_t>(v.idx())]);
    both.add_face(corners);
  }
  const SurfaceGeodesic g =
      surface_geodesic(both, {Eigen::Vector3d(1, 0, 0.5), Eigen::Vector3d(6, 0, 0.5)}, false);
  EXPECT_TRUE(std::isnan(g.length));
  EXPECT_EQ(surface_geodesic(both, {Eigen::Vector3d(1, 0, 0.5), Eigen::Vector3d(1, 0, 0.5)}, false).length,
            0.0);
}

TEST(SurfaceGeodesic, MeasuredOnTheTemplateAndThroughAMap) {
  const int n = 64;
  const double r = 0.2;
  const Mesh body = test::prism(test::regular_polygon(n, r), {0.0, 0.5, 1.0, 1.5, 2.0});
  MeasurementDefinition tape;
  tape.kind = MeasurementKind::Geodesic;
  tape.points = {n, 3 * n + 9};
  const double side = 2.0 * r * std::sin(M_PI / n);
  // The identity map: the template's own vertices.
  const Eigen::MatrixX3d rows = test::vertex_rows(body);
  EXPECT_NEAR(measure_one(tape, body, rows), std::hypot(9 * side, 1.0), 1e-12);
  // A target that is the template scaled by 1.7, turned about z and moved, its remesh vertices the
  // template vertices' images: 1.7 times the value.
  const double s = 1.7;
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d shift(0.3, -1.0, 2.0);
  Mesh target = body;
  for (const VertexHandle v : target.vertices())
    target.set_point(v, to_point(s * turn * position(body, v) + shift));
  EXPECT_NEAR(measure_one(tape, target, test::vertex_rows(target)), s * std::hypot(9 * side, 1.0), 1e-12);
  // The tape through a third point, closed, against the straight polyline through the same points.
  tape.points = {n, 3 * n + 9, 2 * n + 40};
  tape.closed = true;
  MeasurementDefinition straight = tape;
  straight.kind = MeasurementKind::Straight;
  EXPECT_GT(measure_one(tape, body, rows), measure_one(straight, body, rows));
  EXPECT_NEAR(measure_one(tape, target, test::vertex_rows(target)), s * measure_one(tape, body, rows), 1e-12);
}

}  // namespace
}  // namespace xparam
