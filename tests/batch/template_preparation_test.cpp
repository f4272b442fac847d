// The template prepared once per batch: its archive record mirrors the files exactly.
#include "batch/template_preparation.h"

#include "batch_test_support.h"
#include "core/errors.h"
#include "io/sha256.h"
#include "map/curve_tracing.h"
#include "support/plain_obj.h"

#include <gtest/gtest.h>

#include <array>
#include <sstream>

namespace xparam {
namespace {

using test::fs::path;

// A point given on `faces` (corner order of that array) with barycentrics.
Eigen::Vector3d point_on(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces, int face,
                         const Eigen::Vector3d& bary) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) p += bary[k] * vertices.row(faces(face, k)).transpose();
  return p;
}

TEST(TemplatePreparation, RecordMirrorsTheFiles) {
  const TemplateInputs inputs = test::man_template();
  const PreparedTemplate prepared = prepare_template(inputs);
  const TemplateRecord& record = prepared.record;
  const test::PlainObj obj = test::read_plain_obj(inputs.mesh);

  EXPECT_EQ(prepared.loaded.file_order.reversed_count(), 0);
  ASSERT_EQ(record.vertices.rows(), 6890);
  ASSERT_EQ(static_cast<std::size_t>(record.faces.rows()), obj.faces.size());
  for (std::size_t v = 0; v < obj.vertices.size(); ++v)
    ASSERT_EQ(record.vertices.row(static_cast<Eigen::Index>(v)).transpose(), obj.vertices[v]) << v;
  for (std::size_t f = 0; f < obj.faces.size(); ++f)
    for (int k = 0; k < 3; ++k)
      ASSERT_EQ(record.faces(static_cast<Eigen::Index>(f), k), obj.faces[f][k]) << f;

  EXPECT_EQ(record.mesh_file, inputs.mesh.string());
  EXPECT_EQ(record.mesh_sha256, sha256_file_hex(inputs.mesh));
  EXPECT_EQ(record.anchors_sha256, sha256_file_hex(inputs.anchors));
  EXPECT_EQ(record.curves_sha256, sha256_file_hex(inputs.curves));
  ASSERT_EQ(record.anchor_names.size(), 41u);
  EXPECT_EQ(record.anchor_names.front(), "HEAD_TOP");
  EXPECT_EQ(record.anchor_vertices.front(), 412);

  // "left arm" starts at LEFT_SHOULDER (vertex 3011) and ends at LEFT_WRIST (2241).
  ASSERT_EQ(record.curves.size(), 2u);
  const TemplateCurve& arm = record.curves[1];
  EXPECT_EQ(arm.name, "left arm");
  ASSERT_EQ(arm.face.size(), 4u);
  EXPECT_LT(
      (point_on(record.vertices, record.faces, arm.face[0], arm.bary.row(0)) - obj.vertices[3011]).norm(),
      1e-12);
  EXPECT_LT(
      (point_on(record.vertices, record.faces, arm.face[3], arm.bary.row(3)) - obj.vertices[2241]).norm(),
      1e-12);
}

TEST(TemplatePreparation, PositionAnchorsAreRecordedAtTheirVertex) {
  // The .pp file holds the 29 landmarks of human_man.anchors.json as positions copied from the vertices.
  TemplateInputs inputs = test::man_template();
  inputs.anchors = test::data_path("human_man.anchors.json");
  const std::vector<int> by_index = prepare_template(inputs).record.anchor_vertices;
  inputs.anchors = test::data_path("anchors/human_man.pp");
  const TemplateRecord record = prepare_template(inputs).record;
  ASSERT_EQ(record.anchor_vertices.size(), by_index.size());
  EXPECT_EQ(record.anchor_vertices, by_index);
}

// An inward-facing template is flipped at load; the record still holds the file's faces, and
// face + barycentric inputs (written against the file) keep meaning the same points.
TEST(TemplatePreparation, InwardFacingTemplateKeepsFileCornerOrder) {
  const path dir = test::fresh_temp_dir("template_inward");
  const test::PlainObj obj = test::read_plain_obj(test::data_path("human_man.obj"));
  std::ostringstream reversed;
  reversed.precision(17);
  for (const Eigen::Vector3d& v : obj.vertices)
    reversed << "v " << v.x() << " " << v.y() << " " << v.z() << "\n";
  for (const auto& f : obj.faces) reversed << "f " << f[0] + 1 << " " << f[2] + 1 << " " << f[1] + 1 << "\n";
  test::write_file(dir / "inward.obj", reversed.str());
  // Face 10 of the reversed file is (a, c, b) of the original face (a, b, c).
  test::write_file(dir / "inward.curves.json", R"({"curves": [{"name": "c", "points": [
      {"face": 10, "barycentric": [0.2, 0.3, 0.5]}, {"face": 11, "barycentric": [0.6, 0.3, 0.1]}, 5]}]})");
  test::write_file(dir / "inward.anchors.json", R"({"anchors": [{"name": "A", "vertex": 412},
      {"name": "B", "face": 100, "barycentric": [0.1, 0.1, 0.8]}, {"name": "C", "vertex": 3458},
      {"name": "D", "vertex": 2241}, {"name": "E", "vertex": 5559}]})");

  const PreparedTemplate prepared =
      prepare_template({dir / "inward.obj", dir / "inward.anchors.json", dir / "inward.curves.json", {}, {}});
  ASSERT_EQ(prepared.loaded.file_order.reversed_count(), static_cast<int>(obj.faces.size()));
  const TemplateRecord& record = prepared.record;
  for (std::size_t f = 0; f < obj.faces.size(); ++f) {
    const auto row = static_cast<Eigen::Index>(f);
    ASSERT_EQ(record.faces(row, 0), obj.faces[f][0]);
    ASSERT_EQ(record.faces(row, 1), obj.faces[f][2]);
    ASSERT_EQ(record.faces(row, 2), obj.faces[f][1]);
  }
  // The point "face 10, (0.2, 0.3, 0.5)" of the reversed file, computed by hand.
  const auto& f10 = obj.faces[10];
  const Eigen::Vector3d expected =
      0.2 * obj.vertices[f10[0]] + 0.3 * obj.vertices[f10[2]] + 0.5 * obj.vertices[f10[1]];
  const TemplateCurve& curve = record.curves.at(0);
  EXPECT_LT((point_on(record.vertices, record.faces, curve.face[0], curve.bary.row(0)) - expected).norm(),
            1e-12);
  // The curve handed to the pipeline is in the mesh's corner order: the same point.
  const SurfacePoint& on_mesh = prepared.curves.at(0).points[0];
  EXPECT_LT((position(prepared.loaded.mesh, on_mesh) - expected).norm(), 1e-12);
  // Anchor B (a face point) is recorded at the corner with barycentric 0.8: file corner 2 of face 100.
  EXPECT_EQ(record.anchor_vertices[1], obj.faces[100][1]);
}

// A curve_length is the template's curve traced on its own faces; without a curve file the
// measurement file is refused, naming the option that gives one.
TEST(TemplatePreparation, CurveLengthsAndGeodesicsAreMeasuredOnTheTemplate) {
  const path dir = test::fresh_temp_dir("template_curve_lengths");
  TemplateInputs inputs = test::man_template_with_tapes(dir);
  const PreparedTemplate prepared = prepare_template(inputs);
  ASSERT_EQ(prepared.curves.size(), 2U);
  ASSERT_EQ(prepared.measurements.measurements.size(), 4U);
  EXPECT_EQ(prepared.measurements.measurements[0].curve, 1);
  EXPECT_EQ(prepared.measurements.measurements[1].curve, 0);
  const Eigen::VectorXd& values = prepared.record.measurement_values;
  ASSERT_EQ(values.size(), 4);
  for (int c = 0; c < 2; ++c) {
    const FeatureCurve& curve = prepared.curves[static_cast<std::size_t>(1 - c)];
    const MappedCurve traced = trace_curve(curve, prepared.loaded.mesh, prepared.loaded.mesh,
                                           [](const SurfacePoint& p) { return p; });
    EXPECT_EQ(values[c], polyline_length(traced.positions, curve.closed)) << curve.name;
    // Longer than the chords through the curve's own points (it follows the surface between them).
    std::vector<Eigen::Vector3d> chords;
    for (const SurfacePoint& p : curve.points) chords.push_back(position(prepared.loaded.mesh, p));
    EXPECT_GT(values[c], polyline_length(chords, curve.closed)) << curve.name;
  }
  EXPECT_GT(values[2], values[3]);  // the tape over the back against the straight line

  inputs.curves.clear();
  try {
    prepare_template(inputs);
    ADD_FAILURE() << "a curve_length without curves was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "tapes.json:2: measurement \"arm\": \"curve\": \"left arm\" needs the "
                  "template's feature curves: give the curve file (xparam batch --curves FILE)"),
              std::string::npos)
        << e.what();
  }
}

TEST(TemplatePreparation, UnusableTemplatesAreInputErrors) {
  const path dir = test::fresh_temp_dir("template_bad");
  TemplateInputs torus = test::man_template();
  torus.mesh = test::data_path("bob_small.ply");
  torus.curves.clear();
  try {
    prepare_template(torus);
    ADD_FAILURE() << "a genus-1 template was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("genus 1"), std::string::npos) << e.what();
  }

  TemplateInputs far = test::man_template();
  far.anchors = dir / "far.json";
  test::write_file(far.anchors, R"({"anchors": [{"name": "A", "vertex": 1}, {"name": "B", "vertex": 2},
      {"name": "C", "vertex": 3}, {"name": "D", "vertex": 99999}]})");
  EXPECT_THROW(prepare_template(far), InputError);

  TemplateInputs missing = test::man_template();
  missing.curves = dir / "missing.curves.json";
  EXPECT_THROW(prepare_template(missing), InputError);
}

}  // namespace
}  // namespace xparam
