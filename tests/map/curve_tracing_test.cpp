#include "map/curve_tracing.h"

#include "core/closest_point.h"
#include "core/feature_curves.h"
#include "io/curve_reader.h"
#include "io/mesh_loader.h"
#include "support/test_data.h"

#include <gtest/gtest.h>

namespace xparam {
namespace {

struct ManWithCurves {
  LoadedMesh mesh = load_mesh(test::data_path("human_man.obj"));
  std::vector<FeatureCurve> curves =
      validate_curves(read_curves(test::data_path("human_man.curves.json")), mesh.mesh);
};

const ManWithCurves& man() {
  static const ManWithCurves data;
  return data;
}

// Every point on the surface at its own face and barycentrics, and every piece of the polyline
// inside a face: the midpoint of each segment lies on the surface too.
void expect_on_surface(const Mesh& mesh, const MappedCurve& curve) {
  const ClosestPointIndex surface(mesh);
  const std::size_t n = curve.points.size();
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_LT((curve.positions[i] - position(mesh, curve.points[i])).norm(), 1e-12);
    if (i + 1 == n && !curve.closed) break;
    const Eigen::Vector3d middle = 0.5 * (curve.positions[i] + curve.positions[(i + 1) % n]);
    EXPECT_LT((surface.closest(middle).point - middle).norm(), 1e-9) << curve.name << " segment " << i;
  }
}

double chord_length(const Mesh& mesh, const FeatureCurve& curve) {
  std::vector<Eigen::Vector3d> points;
  for (const SurfacePoint& p : curve.points) points.push_back(position(mesh, p));
  return polyline_length(points, curve.closed);
}

TEST(CurveTracing, IdentityTracesTheCurveOnTheSurface) {
  const Mesh& mesh = man().mesh.mesh;
  for (const FeatureCurve& curve : man().curves) {
    const MappedCurve traced = trace_curve(curve, mesh, mesh, [](const SurfacePoint& p) { return p; });
    EXPECT_EQ(traced.chord_segments, 0) << curve.name;
    EXPECT_EQ(traced.closed, curve.closed);
    // A point per edge crossed: many more than the curve's own few points.
    EXPECT_GT(traced.points.size(), 3 * curve.points.size()) << curve.name;
    expect_on_surface(mesh, traced);
    // Along the surface the curve is no shorter than its chords, and not much longer (the
    // curve points are close together on a smooth body).
    const double chords = chord_length(mesh, curve);
    const double length = polyline_length(traced.positions, traced.closed);
    EXPECT_GE(length, chords) << curve.name;
    EXPECT_LT(length, 1.05 * chords) << curve.name;
  }
}

TEST(CurveTracing, ScaledCopyScalesTheLength) {
  const Mesh& mesh = man().mesh.mesh;
  const double scale = 1.6;
  Mesh scaled = mesh;
  for (const VertexHandle v : scaled.vertices()) scaled.set_point(v, to_point(scale * position(mesh, v)));
  // The map of a scaled copy: every surface point to the same face and barycentrics.
  const CurvePointMap same_point = [](const SurfacePoint& p) { return p; };
  for (const FeatureCurve& curve : man().curves) {
    const MappedCurve on_template = trace_curve(curve, mesh, mesh, same_point);
    const MappedCurve on_copy = trace_curve(curve, mesh, scaled, same_point);
    expect_on_surface(scaled, on_copy);
    EXPECT_NEAR(polyline_length(on_copy.positions, on_copy.closed),
                scale * polyline_length(on_template.positions, on_template.closed), 1e-9)
        << curve.name;
  }
}

}  // namespace
}  // namespace xparam
