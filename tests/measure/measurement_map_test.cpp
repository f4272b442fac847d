// The bundled body measurements and feature curves through the map: a uniformly scaled, turned
// and moved copy of the template (the identity up to a similarity) measures the template's values
// times the scale, and its traced curves are the template's, that much longer.
#include "core/feature_curves.h"
#include "io/anchor_reader.h"
#include "io/curve_reader.h"
#include "io/measurement_reader.h"
#include "io/mesh_loader.h"
#include "map/pair_mapping.h"
#include "measure/body_measurements.h"
#include "support/prism_meshes.h"
#include "support/test_data.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace xparam {
namespace {

struct Body {
  LoadedMesh mesh = load_mesh(test::data_path("human_man.obj"));
  AnchorSet anchors = read_anchors(test::data_path("human.anchors.json"));
  MeasurementSet set = [this] {
    MeasurementTemplate on{{}, {}, test::vertex_rows(mesh.mesh)};
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

// A tape on the skin through template vertices.
MeasurementDefinition tape(const std::string& name, const std::vector<int>& points,
                           MeasurementKind kind = MeasurementKind::Geodesic) {
  MeasurementDefinition m;
  m.name = name;
  m.kind = kind;
  m.points = points;
  return m;
}

MeasurementDefinition curve_length(const std::string& name, int curve) {
  MeasurementDefinition m;
  m.name = name;
  m.kind = MeasurementKind::CurveLength;
  m.curve = curve;
  return m;
}

TEST(MeasurementMap, ScaledCopyThroughTheMapMeasuresScaleTimesTheTemplate) {
  Body body;
  // Beside the bundled set: neck to waist over the back (ISO 8559-1's cervicale to waist, both
  // anchors), across the back from shoulder to shoulder through the cervicale, a tape between
  // two points that are not anchors (the map's image of them), and the two feature curves.
  const std::size_t neck_to_waist = body.set.measurements.size();
  body.set.measurements.push_back(tape("cervicale_to_waist_back", {829, 3022}));
  body.set.measurements.push_back(
      tape("cervicale_to_waist_straight", {829, 3022}, MeasurementKind::Straight));
  body.set.measurements.push_back(tape("across_back", {3011, 829, 6470}));
  body.set.measurements.push_back(tape("thigh_side", {848, 1008}));
  body.set.measurements.push_back(curve_length("waist_curve", 0));
  body.set.measurements.push_back(curve_length("left_arm_curve", 1));
  const std::vector<FeatureCurve> curves =
      validate_curves(read_curves(test::data_path("human_man.curves.json")), body.mesh.mesh);
  // The curves, traced on the template by the identity.
  std::vector<double> template_curves;
  for (const FeatureCurve& curve : curves) {
    const MappedCurve on_self =
        trace_curve(curve, body.mesh.mesh, body.mesh.mesh, [](const SurfacePoint& p) { return p; });
    template_curves.push_back(polyline_length(on_self.positions, on_self.closed));
  }
  const std::vector<double> on_template =
      measure_surface(body.set, body.mesh.mesh, body.vertices, template_curves);
  // A tape over the back is longer than the straight line through the body.
  EXPECT_GT(on_template[neck_to_waist], on_template[neck_to_waist + 1] * 1.01);
  std::printf("cervicale to waist, back: geodesic %.4f m, straight %.4f m\n", on_template[neck_to_waist],
              on_template[neck_to_waist + 1]);
  // The SMPL man, in metres: every measurement there and of a plausible size.
  ASSERT_EQ(on_template.size(), body.set.measurements.size());
  for (std::size_t i = 0; i < on_template.size(); ++i) {
    EXPECT_GT(on_template[i], 0.05) << body.set.measurements[i].name;
    EXPECT_LT(on_template[i], 2.0) << body.set.measurements[i].name;
  }
  // Scaled, turned and moved: the set's frame turns the up axis of the heights and the torso
  // girths with the body.
  const double scale = 1.3;
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(1.1, Eigen::Vector3d(0.3, -1.0, 0.6).normalized()).toRotationMatrix();
  Mesh scaled = body.mesh.mesh;
  for (const VertexHandle v : scaled.vertices())
    scaled.set_point(v, to_point(scale * turn * position(scaled, v) + Eigen::Vector3d(0.2, -0.5, 1.0)));
  const PairMapping map = map_pair(body.mesh.mesh, body.anchors, scaled, body.anchors, curves);
  std::vector<double> target_curves;
  for (const MappedCurve& curve : map.curves)
    target_curves.push_back(polyline_length(curve.positions, curve.closed));
  const std::vector<double> through_map =
      measure_surface(body.set, scaled, map.remesh_vertices, target_curves);
  for (std::size_t i = 0; i < on_template.size(); ++i)
    EXPECT_NEAR(through_map[i], scale * on_template[i], 1e-6 * on_template[i]) << body.set.measurements[i].name;
  // The curves on the copy through the map, traced on its surface throughout.
  ASSERT_EQ(map.curves.size(), curves.size());
  for (std::size_t c = 0; c < curves.size(); ++c) {
    EXPECT_EQ(map.curves[c].chord_segments, 0);
    EXPECT_NEAR(target_curves[c], scale * template_curves[c], 1e-6 * template_curves[c]) << curves[c].name;
    EXPECT_EQ(on_template[neck_to_waist + 4 + c], template_curves[c]);
  }
}

}  // namespace
}  // namespace xparam
