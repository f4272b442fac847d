// The bundled body measurements and feature curves through the map: a uniformly scaled, moved
// copy of the template (the identity up to scale) measures the template's values times the
// scale, and its traced curves are the template's, that much longer.
#include "core/feature_curves.h"
#include "io/anchor_reader.h"
#include "io/curve_reader.h"
#include "io/measurement_reader.h"
#include "io/mesh_loader.h"
#include "map/pair_mapping.h"
#include "measure/body_measurements.h"
#include "support/test_data.h"

#include <gtest/gtest.h>

#include <cmath>

namespace xparam {
namespace {

struct Body {
  LoadedMesh mesh = load_mesh(test::data_path("human_man.obj"));
  AnchorSet anchors = read_anchors(test::data_path("human.anchors.json"));
  MeasurementSet set = [this] {
    MeasurementTemplate on{{}, {}, static_cast<int>(mesh.mesh.n_vertices())};
    for (const AnchorSpec& anchor : anchors.anchors) {
      on.anchor_names.push_back(anchor.name);
      on.anchor_vertices.push_back(std::get<AnchorVertex>(anchor.location).index);
    }
    return read_measurements(test::data_path("human.measurements.json"), on);
  }();
  Eigen::MatrixX3d vertices = [this] {
    Eigen::MatrixX3d rows(static_cast<Eigen::Index>(mesh.mesh.n_vertices()), 3);
    for (const VertexHandle v : mesh.mesh.vertices()) rows.row(v.idx()) = position(mesh.mesh, v).transpose();
    return rows;
  }();
};

TEST(MeasurementMap, ScaledCopyThroughTheMapMeasuresScaleTimesTheTemplate) {
  const Body body;
  const std::vector<double> on_template = measure_surface(body.set, body.mesh.mesh, body.vertices);
  // The SMPL man, in metres: every measurement there and of a plausible size.
  ASSERT_EQ(on_template.size(), body.set.measurements.size());
  for (std::size_t i = 0; i < on_template.size(); ++i) {
    EXPECT_GT(on_template[i], 0.05) << body.set.measurements[i].name;
    EXPECT_LT(on_template[i], 2.0) << body.set.measurements[i].name;
  }
  // A shift keeps the up axis; the torso planes are horizontal, so no rotation here.
  const double scale = 1.3;
  Mesh scaled = body.mesh.mesh;
  for (const VertexHandle v : scaled.vertices())
    scaled.set_point(v, to_point(scale * position(scaled, v) + Eigen::Vector3d(0.2, -0.5, 1.0)));
  const std::vector<FeatureCurve> curves =
      validate_curves(read_curves(test::data_path("human_man.curves.json")), body.mesh.mesh);
  const PairMapping map = map_pair(body.mesh.mesh, body.anchors, scaled, body.anchors, curves);
  const std::vector<double> through_map = measure_surface(body.set, scaled, map.remesh_vertices);
  for (std::size_t i = 0; i < on_template.size(); ++i)
    EXPECT_NEAR(through_map[i], scale * on_template[i], 1e-6 * on_template[i]) << body.set.measurements[i].name;
  // The curves, traced on the template by the identity, and on the copy through the map.
  ASSERT_EQ(map.curves.size(), curves.size());
  for (std::size_t c = 0; c < curves.size(); ++c) {
    const MappedCurve on_self =
        trace_curve(curves[c], body.mesh.mesh, body.mesh.mesh, [](const SurfacePoint& p) { return p; });
    const double length = polyline_length(on_self.positions, on_self.closed);
    EXPECT_EQ(map.curves[c].chord_segments, 0);
    EXPECT_NEAR(polyline_length(map.curves[c].positions, map.curves[c].closed), scale * length, 1e-6 * length)
        << curves[c].name;
  }
}

}  // namespace
}  // namespace xparam
