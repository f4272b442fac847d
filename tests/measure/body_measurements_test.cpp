#include "measure/body_measurements.h"

#include "core/closest_point.h"
#include "core/feature_curves.h"
#include "map/curve_tracing.h"
#include "support/prism_meshes.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>

namespace xparam {
namespace {

constexpr int kSides = 512;

MeasurementDefinition girth_through(int vertex, const Eigen::Vector3d& normal, bool hull = false) {
  MeasurementDefinition m;
  m.name = "girth";
  m.kind = MeasurementKind::PlaneGirth;
  m.plane.through = {vertex};
  m.plane.normal = normal.normalized();
  m.near = vertex;
  m.convex_hull = hull;
  return m;
}

TEST(BodyMeasurements, CylinderGirthIsTwoPiR) {
  const double r = 0.15;
  // Rings at 0, 0.5 and 1.2: the plane runs through the middle ring's vertices.
  const Mesh cylinder = test::prism(test::regular_polygon(kSides, r), {0.0, 0.5, 1.2});
  const double girth = measure_one(girth_through(kSides + 7, {0, 0, 1}), cylinder, test::vertex_rows(cylinder));
  // The inscribed 512-gon's perimeter, within its known shortfall of the circle.
  EXPECT_NEAR(girth, 2 * kSides * r * std::sin(M_PI / kSides), 1e-12);
  EXPECT_NEAR(girth, 2 * M_PI * r, 2 * M_PI * r * (M_PI * M_PI / (6.0 * kSides * kSides)) * 1.01);
}

TEST(BodyMeasurements, NormalFromTwoPointsTiltsThePlane) {
  // Through the middle ring, the normal from a bottom vertex to a top vertex across the axis:
  // the section of a cylinder by a plane tilted by theta is an ellipse with axes r and r/cos(theta).
  const double r = 0.1;
  const Mesh cylinder = test::prism(test::regular_polygon(kSides, r), {0.0, 0.5, 1.0});
  MeasurementDefinition m = girth_through(kSides, {0, 0, 1});
  const int bottom_centre = 3 * kSides, top_across = 2 * kSides;  // (0,0,0) and (r,0,1)
  m.plane.normal_from = bottom_centre;
  m.plane.normal_to = top_across;
  const double theta = std::atan(r / 1.0);
  const double a = r / std::cos(theta), b = r;
  // Ramanujan's second approximation; its error is far below the polygon's here.
  const double h = (a - b) * (a - b) / ((a + b) * (a + b));
  const double ellipse = M_PI * (a + b) * (1 + 3 * h / (10 + std::sqrt(4 - 3 * h)));
  EXPECT_NEAR(measure_one(m, cylinder, test::vertex_rows(cylinder)), ellipse, ellipse * 1e-4);
}

TEST(BodyMeasurements, TheLoopNearestTheReferencePointIsMeasured) {
  // Two cylinders side by side, radii 0.1 and 0.2, both cut by the plane z = 0.5.
  Mesh both = test::prism(test::regular_polygon(kSides, 0.1), {0.0, 0.5, 1.0});
  const Mesh wide = test::prism(test::regular_polygon(kSides, 0.2), {0.0, 0.5, 1.0}, {1.0, 0.0, 0.0});
  const int offset = static_cast<int>(both.n_vertices());
  std::vector<VertexHandle> added;
  for (const VertexHandle v : wide.vertices()) added.push_back(both.add_vertex(wide.point(v)));
  for (const FaceHandle f : wide.faces()) {
    std::vector<VertexHandle> corners;
    for (const VertexHandle v : wide.fv_range(f)) corners.push_back(added[static_cast<std::size_t>(v.idx())]);
    both.add_face(corners);
  }
  const Eigen::MatrixX3d rows = test::vertex_rows(both);
  MeasurementDefinition m = girth_through(kSides, {0, 0, 1});
  EXPECT_NEAR(measure_one(m, both, rows), 2 * M_PI * 0.1, 1e-4);
  m.near = offset + kSides + 3;
  EXPECT_NEAR(measure_one(m, both, rows), 2 * M_PI * 0.2, 1e-4);
}

TEST(BodyMeasurements, HullGirthBridgesTheHollows) {
  // A cross-shaped section (a plus sign of arm width w and span s): the tape goes round the
  // octagon of its eight outer corners.
  const double w = 0.2, s = 1.0;
  const double h = w / 2, e = s / 2;
  const std::vector<Eigen::Vector2d> plus = {{e, -h}, {e, h},   {h, h},   {h, e},   {-h, e},  {-h, h},
                                             {-e, h}, {-e, -h}, {-h, -h}, {-h, -e}, {h, -e},  {h, -h}};
  const Mesh mesh = test::prism(plus, {0.0, 0.5, 1.0});
  const Eigen::MatrixX3d rows = test::vertex_rows(mesh);
  const int middle = static_cast<int>(plus.size());
  EXPECT_NEAR(measure_one(girth_through(middle, {0, 0, 1}), mesh, rows), 8 * (e - h) + 4 * w, 1e-12);
  const double octagon = 4 * w + 4 * std::sqrt(2.0) * (e - h);
  EXPECT_NEAR(measure_one(girth_through(middle, {0, 0, 1}, true), mesh, rows), octagon, 1e-12);
}

TEST(BodyMeasurements, StraightDistanceIsTheFormula) {
  const Mesh cylinder = test::prism(test::regular_polygon(8, 1.0), {0.0, 2.0});
  const Eigen::MatrixX3d rows = test::vertex_rows(cylinder);
  MeasurementDefinition m;
  m.kind = MeasurementKind::Straight;
  m.points = {0, 4, 12};  // (1,0,0), (-1,0,0), (-1,0,2)
  EXPECT_NEAR(measure_one(m, cylinder, rows), 2.0 + 2.0, 1e-12);
  m.closed = true;
  EXPECT_NEAR(measure_one(m, cylinder, rows), 4.0 + std::sqrt(8.0), 1e-12);
}

TEST(BodyMeasurements, HeightIsAboveTheLowestPoint) {
  const Mesh cylinder = test::prism(test::regular_polygon(8, 1.0), {-0.25, 1.5}, {0, 0, 3.0});
  MeasurementDefinition m;
  m.kind = MeasurementKind::Height;
  m.points = {9};  // a top-ring vertex
  m.up = Eigen::Vector3d(0, 0, 1);
  EXPECT_NEAR(measure_one(m, cylinder, test::vertex_rows(cylinder)), 1.75, 1e-12);
}

TEST(BodyMeasurements, NoPlaneOrNoSectionGivesNaN) {
  const Mesh cylinder = test::prism(test::regular_polygon(8, 1.0), {0.0, 2.0});
  const Eigen::MatrixX3d rows = test::vertex_rows(cylinder);
  MeasurementDefinition collinear;
  collinear.kind = MeasurementKind::PlaneGirth;
  collinear.plane.through = {0, 8, 16};  // (1,0,0), (1,0,2) and the bottom centre (0,0,0): the plane y = 0
  collinear.near = 0;
  EXPECT_TRUE(std::isfinite(measure_one(collinear, cylinder, rows)));
  Eigen::MatrixX3d squashed = rows;
  squashed.row(16) = Eigen::RowVector3d(1, 0, 1);  // now on the line through the other two
  EXPECT_TRUE(std::isnan(measure_one(collinear, cylinder, squashed)));
  MeasurementDefinition beside = girth_through(0, {0, 0, 1});
  Eigen::MatrixX3d lifted = rows;
  lifted.row(0) = Eigen::RowVector3d(1, 0, 5);  // the plane z = 5 misses the cylinder
  EXPECT_TRUE(std::isnan(measure_one(beside, cylinder, lifted)));
}

TEST(BodyMeasurements, ClosedCurveRoundAPrismMeasuresItsPolygonsPerimeter) {
  const int n = 16;
  const double r = 0.5;
  const Mesh prism = test::prism(test::regular_polygon(n, r), {0.0, 1.0, 2.0});
  // Four points inside side faces at z = 0.8, a quarter of the way round from each other: the
  // traced curve follows the horizontal section between them, round the 16-gon.
  const ClosestPointIndex index(prism);
  FeatureCurve curve{"waistline", {}, true};
  for (const double along : {0.5, 4.5, 8.5, 12.5}) {
    const double a0 = 2.0 * M_PI * std::floor(along) / n, a1 = 2.0 * M_PI * (std::floor(along) + 1) / n;
    const Eigen::Vector3d p =
        0.5 * Eigen::Vector3d(r * (std::cos(a0) + std::cos(a1)), r * (std::sin(a0) + std::sin(a1)), 1.6);
    curve.points.push_back(index.closest(p).location);
  }
  const auto same_place = [](const SurfacePoint& p) { return p; };
  const MappedCurve on_template = trace_curve(curve, prism, prism, same_place);
  MeasurementDefinition m;
  m.name = "waistline";
  m.kind = MeasurementKind::CurveLength;
  m.curve = 1;  // the second curve of the template's file
  const double perimeter = n * 2.0 * r * std::sin(M_PI / n);
  const Eigen::MatrixX3d rows = test::vertex_rows(prism);
  EXPECT_NEAR(measure_one(m, prism, rows, {0.25, polyline_length(on_template.positions, on_template.closed)}),
              perimeter, 1e-12);
  // Not the four points' chords (a square inside the 16-gon).
  EXPECT_LT(polyline_length({position(prism, curve.points[0]), position(prism, curve.points[1]),
                             position(prism, curve.points[2]), position(prism, curve.points[3])},
                            true),
            perimeter - 0.1);
  // On a copy scaled by 1.7 (the map the identity of faces and barycentrics): 1.7 times.
  Mesh scaled = prism;
  for (const VertexHandle v : scaled.vertices()) scaled.set_point(v, to_point(1.7 * position(prism, v)));
  const MappedCurve on_target = trace_curve(curve, prism, scaled, same_place);
  EXPECT_NEAR(
      measure_one(m, scaled, 1.7 * rows, {0.25, polyline_length(on_target.positions, on_target.closed)}),
      1.7 * perimeter, 1e-12);
}

TEST(BodyMeasurements, ScalingTheBodyScalesEveryMeasurement) {
  const Mesh body = test::prism(test::regular_polygon(64, 0.2), {0.0, 0.4, 1.0});
  Mesh scaled = body;
  const double s = 1.7;
  for (const VertexHandle v : scaled.vertices()) scaled.set_point(v, to_point(s * position(body, v)));
  MeasurementSet set;
  MeasurementDefinition height;
  height.kind = MeasurementKind::Height;
  height.points = {64 + 5};
  height.up = Eigen::Vector3d(0, 0, 1);
  MeasurementDefinition straight;
  straight.kind = MeasurementKind::Straight;
  straight.points = {0, 150};
  MeasurementDefinition geodesic = straight;
  geodesic.kind = MeasurementKind::Geodesic;
  set.measurements = {girth_through(64, {0, 0, 1}), girth_through(64, {0, 0, 1}, true), height, straight,
                      geodesic};
  const std::vector<double> before = measure_surface(set, body, test::vertex_rows(body));
  const std::vector<double> after = measure_surface(set, scaled, test::vertex_rows(scaled));
  ASSERT_EQ(after.size(), before.size());
  for (std::size_t i = 0; i < before.size(); ++i) {
    EXPECT_GT(before[i], 0.0);
    EXPECT_NEAR(after[i], s * before[i], 1e-12) << i;
  }
}

// The body moved by x -> s R x + t, and where its vertices go.
struct Moved {
  Mesh mesh;
  Eigen::MatrixX3d rows;
};

Moved moved(const Mesh& body, double s, const Eigen::Matrix3d& rotation, const Eigen::Vector3d& shift) {
  Moved out{body, {}};
  for (const VertexHandle v : out.mesh.vertices())
    out.mesh.set_point(v, to_point(s * rotation * position(body, v) + shift));
  out.rows = test::vertex_rows(out.mesh);
  return out;
}

TEST(BodyMeasurements, FixedDirectionsFollowTheFrameOfATurnedBody) {
  // A cylinder (r 0.15, rings at 0, 0.5 and 1.2) measured with the template's up axis z: the
  // girth round the middle ring and its height, and a plane and a height fixed in the
  // template's frame; the frame is four ring vertices at several angles and heights.
  const double r = 0.15;
  const Mesh body = test::prism(test::regular_polygon(kSides, r), {0.0, 0.5, 1.2});
  const Eigen::MatrixX3d rows = test::vertex_rows(body);
  MeasurementSet set;
  MeasurementDefinition height;
  height.kind = MeasurementKind::Height;
  height.points = {kSides + 7};
  height.up = Eigen::Vector3d(0, 0, 1);
  MeasurementDefinition across = height;  // a height along a slanted direction
  across.up = Eigen::Vector3d(1, 0, 1).normalized();
  set.measurements = {girth_through(kSides + 7, {0, 0, 1}), girth_through(kSides + 7, {0, 0, 1}, true), height,
                      girth_through(kSides + 7, {1, 0, 2}), across};
  set.frame.vertices = {0, kSides / 4, kSides / 2, 2 * kSides + kSides / 8};
  set.frame.template_points.resize(4, 3);
  for (int i = 0; i < 4; ++i) set.frame.template_points.row(i) = rows.row(set.frame.vertices[i]);
  const std::vector<double> upright = measure_surface(set, body, rows);
  const double polygon = 2 * kSides * r * std::sin(M_PI / kSides);
  EXPECT_NEAR(upright[0], polygon, 1e-12);
  EXPECT_NEAR(upright[2], 0.5, 1e-12);

  const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Vector3d shift(0.3, -1.0, 2.0);
  for (const double s : {1.0, 1.6}) {
    const Moved target = moved(body, s, turn, shift);
    const std::vector<double> through = measure_surface(set, target.mesh, target.rows);
    ASSERT_EQ(through.size(), upright.size());
    for (std::size_t i = 0; i < upright.size(); ++i) EXPECT_NEAR(through[i], s * upright[i], 1e-6 * s * upright[i]) << i;
    EXPECT_NEAR(through[0], s * polygon, 1e-9);
    EXPECT_NEAR(through[2], s * 0.5, 1e-9);
  }
  // Without the frame the directions stay the file's: the turned cylinder is cut aslant.
  MeasurementSet unframed = set;
  unframed.frame = {};
  const Moved target = moved(body, 1.0, turn, shift);
  EXPECT_GT(std::abs(measure_surface(unframed, target.mesh, target.rows)[0] - polygon), 0.01 * polygon);
}

}  // namespace
}  // namespace xparam
