#include "io/measurement_reader.h"

#include "core/errors.h"
#include "io/anchor_reader.h"
#include "io/mesh_loader.h"
#include "support/prism_meshes.h"
#include "support/expect_error.h"
#include "support/test_data.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace xparam {
namespace {

// Three anchors on a template of 100 vertices, vertex i at (i mod 10, i / 10, i / 50): vertices
// 1, 2, 3 on a line, the anchors not.
const MeasurementTemplate kTemplate = [] {
  MeasurementTemplate on{{"HEAD_TOP", "CROTCH", "NAVEL"}, {12, 40, 55}, Eigen::MatrixX3d(100, 3)};
  for (int i = 0; i < 100; ++i) on.vertices.row(i) << i % 10, i / 10, i / 50;
  return on;
}();

std::string parse_error(const std::string& text) {
  return test::error_message_of([&] { parse_measurements_json(text, "m.json", kTemplate); });
}

TEST(MeasurementReader, NamesResolveToLandmarksThenAnchorsThenVertices) {
  const MeasurementSet set = parse_measurements_json(R"({"unit": "m",
    "landmarks": {"Neck": {"vertex": 7}, "CROTCH": {"vertex": 9}},
    "measurements": [
      {"name": "a", "type": "straight", "points": ["Neck", "HEAD_TOP", {"vertex": 3}], "closed": true},
      {"name": "b", "type": "plane_girth", "through": ["CROTCH"], "normal": [0, 2, 0], "hull": true},
      {"name": "c", "type": "plane_girth", "through": ["Neck"], "normal_from_to": ["HEAD_TOP", {"vertex": 5}], "near": {"vertex": 6}},
      {"name": "d", "type": "plane_girth", "through": [{"vertex": 1}, {"vertex": 2}, "Neck"]},
      {"name": "e", "type": "height", "point": "HEAD_TOP", "up": [0, 0, 3]}]})",
                                                     "m.json", kTemplate);
  EXPECT_EQ(set.unit, "m");
  ASSERT_EQ(set.measurements.size(), 5U);
  const MeasurementDefinition& a = set.measurements[0];
  EXPECT_EQ(a.kind, MeasurementKind::Straight);
  EXPECT_EQ(a.points, (std::vector<int>{7, 12, 3}));
  EXPECT_TRUE(a.closed);
  const MeasurementDefinition& b = set.measurements[1];
  EXPECT_EQ(b.kind, MeasurementKind::PlaneGirth);
  EXPECT_EQ(b.plane.through, std::vector<int>{9});  // the file's landmark hides the anchor
  EXPECT_EQ(b.plane.normal, Eigen::Vector3d(0, 1, 0));  // normalized
  EXPECT_TRUE(b.convex_hull);
  EXPECT_EQ(b.near, 9);  // defaults to the plane's point
  const MeasurementDefinition& c = set.measurements[2];
  EXPECT_EQ(c.plane.normal_from, 12);
  EXPECT_EQ(c.plane.normal_to, 5);
  EXPECT_EQ(c.near, 6);
  EXPECT_FALSE(c.convex_hull);
  EXPECT_EQ(set.measurements[3].plane.through, (std::vector<int>{1, 2, 7}));
  const MeasurementDefinition& e = set.measurements[4];
  EXPECT_EQ(e.kind, MeasurementKind::Height);
  EXPECT_EQ(e.points, std::vector<int>{12});
  EXPECT_EQ(e.up, Eigen::Vector3d(0, 0, 1));
}

TEST(MeasurementReader, ErrorsNameFileLineMeasurementAndFix) {
  EXPECT_MESSAGE_HAS(parse_error("[]"), "m.json:1: expected a JSON object");
  EXPECT_MESSAGE_HAS(parse_error(R"({"measurements": []})"), "m.json:1: expected \"unit\"");
  EXPECT_MESSAGE_HAS(parse_error(R"({"unit": "m", "measurements": []})"), "non-empty \"measurements\" array");
  EXPECT_MESSAGE_HAS(parse_error("{\"unit\": \"m\", \"measurements\": [\n{\"name\": \"x\", \"type\": \"tape\"}]}"),
                     "m.json:2: measurement \"x\": unknown type \"tape\"");
  EXPECT_MESSAGE_HAS(
      parse_error("{\"unit\": \"m\", \"measurements\": [\n{\"name\": \"x\", \"type\": \"straight\", \"points\": [\"Nose\", 1]}]}"),
      "m.json:2: measurement \"x\": \"points\": \"Nose\" is neither a landmark of this file nor an anchor of the "
      "template: add it to \"landmarks\"");
  EXPECT_MESSAGE_HAS(parse_error("{\"unit\": \"m\", \"measurements\": [\n{\"name\": \"x\", \"type\": \"straight\", "
                                 "\"points\": [{\"vertex\": 100}, 1]}]}"),
                     "expected a template vertex index in [0, 100), got 100");
  EXPECT_MESSAGE_HAS(parse_error("{\"unit\": \"m\", \"measurements\": [\n{\"name\": \"x\", \"type\": \"plane_girth\", "
                                 "\"through\": [1, 2]}]}"),
                     "m.json:2: measurement \"x\": \"through\": expected a point name or {\"vertex\": i}, got 1");
  EXPECT_MESSAGE_HAS(parse_error("{\"unit\": \"m\", \"measurements\": [\n{\"name\": \"x\", \"type\": \"plane_girth\", "
                                 "\"through\": [{\"vertex\": 1}, {\"vertex\": 2}]}]}"),
                     "\"through\" must hold 1 point (with a normal) or 3 points");
  EXPECT_MESSAGE_HAS(parse_error("{\"unit\": \"m\", \"measurements\": [\n{\"name\": \"x\", \"type\": \"plane_girth\", "
                                 "\"through\": [\"CROTCH\"]}]}"),
                     "needs exactly one of \"normal\": [x, y, z] and \"normal_from_to\"");
  EXPECT_MESSAGE_HAS(parse_error("{\"unit\": \"m\", \"measurements\": [\n{\"name\": \"x\", \"type\": \"plane_girth\", "
                                 "\"through\": [\"CROTCH\"], \"normal\": [0, 0, 0]}]}"),
                     "the direction must be finite and not zero");
  EXPECT_MESSAGE_HAS(parse_error("{\"unit\": \"m\", \"measurements\": [\n{\"name\": \"x\", \"type\": \"height\", "
                                 "\"point\": \"CROTCH\", \"up\": [0, 1, 0], \"colour\": 1}]}"),
                     "m.json:2: measurement \"x\": unknown member \"colour\"");
  EXPECT_MESSAGE_HAS(parse_error("{\"unit\": \"m\", \"measurements\": [\n{\"name\": \"x\", \"type\": \"straight\", "
                                 "\"points\": [\"CROTCH\", \"HEAD_TOP\"]},\n{\"name\": \"x\", \"type\": \"straight\", "
                                 "\"points\": [\"CROTCH\", \"HEAD_TOP\"]}]}"),
                     "m.json:3: measurement \"x\" is defined twice");
}

TEST(MeasurementReader, TheFrameIsTheNamedPointsElseTheAnchors) {
  const std::string girth = R"({"name": "g", "type": "plane_girth", "through": ["CROTCH"], "normal": [0, 1, 0]})";
  // Default: the template's anchors, with their template positions.
  const MeasurementSet anchors =
      parse_measurements_json("{\"unit\": \"m\", \"measurements\": [" + girth + "]}", "m.json", kTemplate);
  EXPECT_EQ(anchors.frame.vertices, (std::vector<int>{12, 40, 55}));
  EXPECT_EQ(anchors.frame.template_points.row(1), kTemplate.vertices.row(40));
  // Named: landmarks, anchors or vertices, each once, in vertex order.
  const MeasurementSet named = parse_measurements_json(
      "{\"unit\": \"m\", \"landmarks\": {\"Neck\": {\"vertex\": 7}},\n\"frame\": [\"Neck\", \"HEAD_TOP\", "
      "{\"vertex\": 3}, \"Neck\"], \"measurements\": [" + girth + "]}",
      "m.json", kTemplate);
  EXPECT_EQ(named.frame.vertices, (std::vector<int>{3, 7, 12}));
  EXPECT_EQ(named.frame.template_points.row(0), kTemplate.vertices.row(3));
  // Points on one line fix no rotation: refused when a measurement has a fixed direction.
  EXPECT_MESSAGE_HAS(
      parse_error("{\"unit\": \"m\",\n\"frame\": [{\"vertex\": 1}, {\"vertex\": 2}, {\"vertex\": 3}], "
                  "\"measurements\": [" + girth + "]}"),
      "m.json:2: \"frame\" must hold at least 3 points not on one line: measurement \"g\" has a fixed direction");
  MeasurementTemplate two_anchors = kTemplate;
  two_anchors.anchor_names.pop_back();
  two_anchors.anchor_vertices.pop_back();
  EXPECT_MESSAGE_HAS(test::error_message_of([&] {
                       parse_measurements_json(R"({"unit": "m", "measurements": [
                         {"name": "h", "type": "height", "point": "CROTCH", "up": [0, 1, 0]}]})",
                                               "m.json", two_anchors);
                     }),
                     "m.json:1: the template's anchors (the default \"frame\") must hold at least 3 points not on one "
                     "line: measurement \"h\"");
  // Without a fixed direction the frame is never used, so nothing is asked of it.
  EXPECT_NO_THROW(parse_measurements_json(R"({"unit": "m", "frame": [{"vertex": 1}], "measurements": [
      {"name": "s", "type": "straight", "points": ["CROTCH", "HEAD_TOP"]}]})",
                                          "m.json", two_anchors));
}

TEST(MeasurementReader, GeodesicTakesPointsLikeStraight) {
  const MeasurementSet set = parse_measurements_json(R"({"unit": "m", "measurements": [
      {"name": "back", "type": "geodesic", "points": ["HEAD_TOP", {"vertex": 3}]},
      {"name": "loop", "type": "geodesic", "points": ["HEAD_TOP", "CROTCH", {"vertex": 3}], "closed": true}]})",
                                                     "m.json", kTemplate);
  ASSERT_EQ(set.measurements.size(), 2U);
  EXPECT_EQ(set.measurements[0].kind, MeasurementKind::Geodesic);
  EXPECT_EQ(set.measurements[0].points, (std::vector<int>{12, 3}));
  EXPECT_FALSE(set.measurements[0].closed);
  EXPECT_EQ(set.measurements[1].points, (std::vector<int>{12, 40, 3}));
  EXPECT_TRUE(set.measurements[1].closed);
  EXPECT_MESSAGE_HAS(
      parse_error("{\"unit\": \"m\", \"measurements\": [\n{\"name\": \"back\", \"type\": \"geodesic\", "
                  "\"points\": [\"HEAD_TOP\", \"Cervicale\"]}]}"),
      "m.json:2: measurement \"back\": \"points\": \"Cervicale\" is neither a landmark of this file nor "
      "an anchor of the template: add it to \"landmarks\" as {\"vertex\": i}");
  EXPECT_MESSAGE_HAS(
      parse_error("{\"unit\": \"m\", \"measurements\": [\n{\"name\": \"back\", \"type\": \"geodesic\", "
                  "\"points\": [\"HEAD_TOP\"]}]}"),
      "m.json:2: measurement \"back\": \"points\" needs at least 2 points (the geodesic path runs from "
      "the first to the last)");
  EXPECT_MESSAGE_HAS(
      parse_error("{\"unit\": \"m\", \"measurements\": [\n{\"name\": \"back\", \"type\": \"geodesic\", "
                  "\"points\": [\"HEAD_TOP\", \"CROTCH\"], \"closed\": true}]}"),
      "m.json:2: measurement \"back\": a closed path needs at least 3 points");
  EXPECT_MESSAGE_HAS(
      parse_error("{\"unit\": \"m\", \"measurements\": [\n{\"name\": \"back\", \"type\": \"geodesic\", "
                  "\"points\": [\"HEAD_TOP\", \"CROTCH\"], \"hull\": true}]}"),
      "m.json:2: measurement \"back\": unknown member \"hull\"");
}

TEST(MeasurementReader, CurveLengthNamesATemplateCurve) {
  MeasurementTemplate with_curves = kTemplate;
  with_curves.curve_names = {"waist", "left arm"};
  const MeasurementSet set = parse_measurements_json(R"({"unit": "m", "measurements": [
      {"name": "arm", "type": "curve_length", "curve": "left arm", "description": "shoulder to wrist"}]})",
                                                     "m.json", with_curves);
  ASSERT_EQ(set.measurements.size(), 1U);
  EXPECT_EQ(set.measurements[0].kind, MeasurementKind::CurveLength);
  EXPECT_EQ(set.measurements[0].curve, 1);
  const auto error = [&](const std::string& entry, const MeasurementTemplate& on) {
    return test::error_message_of([&] {
      parse_measurements_json("{\"unit\": \"m\", \"measurements\": [\n" + entry + "]}", "m.json", on);
    });
  };
  EXPECT_MESSAGE_HAS(
      error(R"({"name": "arm", "type": "curve_length", "curve": "right arm"})", with_curves),
      "m.json:2: measurement \"arm\": \"curve\": \"right arm\" is not a curve of the template's curve "
      "file (its curves: \"waist\", \"left arm\")");
  EXPECT_MESSAGE_HAS(
      error(R"({"name": "arm", "type": "curve_length", "curve": "left arm"})", kTemplate),
      "m.json:2: measurement \"arm\": \"curve\": \"left arm\" needs the template's feature curves: give "
      "the curve file (xparam batch --curves FILE)");
  EXPECT_MESSAGE_HAS(error(R"({"name": "arm", "type": "curve_length"})", with_curves),
                     "m.json:2: measurement \"arm\": expected \"curve\": the name of a feature curve");
  EXPECT_MESSAGE_HAS(
      error(R"({"name": "arm", "type": "curve_length", "curve": "waist", "points": [1, 2]})", with_curves),
      "m.json:2: measurement \"arm\": unknown member \"points\" (expected \"name\", \"type\", "
      "\"description\", \"curve\")");
}

TEST(MeasurementReader, TheBundledBodySetReadsOnTheSmplTemplate) {
  const AnchorSet anchors = read_anchors(test::data_path("human.anchors.json"));
  MeasurementTemplate smpl{{}, {}, test::vertex_rows(load_mesh(test::data_path("human_man.obj")).mesh)};
  for (const AnchorSpec& anchor : anchors.anchors) {
    smpl.anchor_names.push_back(anchor.name);
    smpl.anchor_vertices.push_back(std::get<AnchorVertex>(anchor.location).index);
  }
  const MeasurementSet set = read_measurements(test::data_path("human.measurements.json"), smpl);
  EXPECT_EQ(set.unit, "m");
  std::vector<std::string> names;
  for (const MeasurementDefinition& m : set.measurements) names.push_back(m.name);
  for (const char* required : {"stature", "neck_girth", "chest_girth", "waist_girth", "hip_girth", "thigh_girth",
                               "calf_girth", "upper_arm_girth", "arm_length", "inside_leg_height", "shoulder_width"})
    EXPECT_NE(std::find(names.begin(), names.end(), required), names.end()) << required;
}

}  // namespace
}  // namespace xparam
