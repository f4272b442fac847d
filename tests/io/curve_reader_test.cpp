#include "io/curve_reader.h"

#include "core/errors.h"
#include "io/anchor_reader.h"
#include "support/expect_error.h"
#include "support/test_data.h"

#include <gtest/gtest.h>
#include <OpenMesh/Core/IO/MeshIO.hh>

#include <fstream>
#include <set>

namespace xparam {
namespace {

const Mesh& human_man() {
  static const Mesh mesh = [] {
    Mesh m;
    EXPECT_TRUE(OpenMesh::IO::read_mesh(m, test::data_path("human_man.obj").string()));
    return m;
  }();
  return mesh;
}

TEST(CurveReader, HumanManCurvesAreWhereTheirDescriptionSays) {
  const FeatureCurveSet set = read_curves(test::data_path("human_man.curves.json"));
  ASSERT_EQ(set.curves.size(), 2u);
  const Mesh& mesh = human_man();
  const std::vector<FeatureCurve> curves = validate_curves(set, mesh);
  ASSERT_EQ(curves.size(), 2u);

  // The waist: a closed loop of points inside faces, on the plane 5 mm below the belly button.
  const FeatureCurve& waist = curves[0];
  EXPECT_EQ(waist.name, "waist");
  EXPECT_TRUE(waist.closed);
  ASSERT_EQ(waist.points.size(), 11u);
  const double height = mesh.point(mesh.vertex_handle(3501))[1] - 0.005;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const SurfacePoint& point : waist.points) {
    EXPECT_GT(point.bary.minCoeff(), 0.0);
    EXPECT_NEAR(position(mesh, point).y(), height, 1e-5);
    centre += position(mesh, point) / static_cast<double>(waist.points.size());
  }
  // Around the torso: within 25 cm of the body axis, surrounding it.
  std::set<int> quadrants;
  for (const SurfacePoint& point : waist.points) {
    const Eigen::Vector3d offset = position(mesh, point) - centre;
    EXPECT_LT(std::hypot(offset.x(), offset.z()), 0.25);
    quadrants.insert((offset.x() > 0 ? 1 : 0) + (offset.z() > 0 ? 2 : 0));
  }
  EXPECT_EQ(quadrants.size(), 4u);

  // The left arm: vertices 3011, 1643, 2241 and a face point between the first two.
  const FeatureCurve& arm = curves[1];
  EXPECT_EQ(arm.name, "left arm");
  EXPECT_FALSE(arm.closed);
  ASSERT_EQ(arm.points.size(), 4u);
  const int vertices[] = {3011, -1, 1643, 2241};
  for (int i = 0; i < 4; ++i) {
    if (vertices[i] < 0) continue;
    EXPECT_EQ(position(mesh, arm.points[i]), position(mesh, mesh.vertex_handle(vertices[i])));
  }
  EXPECT_EQ(arm.points[1].face, 4228);
  EXPECT_EQ(arm.points[1].bary, Eigen::Vector3d(0.2, 0.3, 0.5));
  for (int i = 0; i < 4; ++i) EXPECT_GT(position(mesh, arm.points[i]).x(), 0.15);  // on the left (+x)
}

TEST(CurveReader, SchemaExamplesAreReadAndValid) {
  const nlohmann::json schema = nlohmann::json::parse(
      read_text_file(std::filesystem::path(XPARAM_SOURCE_DIR) / "schemas" / "curves.schema.json"));
  ASSERT_TRUE(schema.contains("examples"));
  for (const nlohmann::json& example : schema["examples"]) {
    const FeatureCurveSet set = parse_curves_json(example.dump(2), "schema example");
    EXPECT_NO_THROW(validate_curves(set, human_man())) << example.dump();
  }
  std::set<std::string> members;
  for (const auto& [member, value] : schema["$defs"]["curve"]["properties"].items()) members.insert(member);
  EXPECT_EQ(members, (std::set<std::string>{"name", "closed", "points"}));
}

TEST(CurveReader, StructureErrorsNameFileAndLine) {
  const auto error = [](const std::string& text) {
    return test::error_message_of([&] { parse_curves_json(text, "c.json"); });
  };
  EXPECT_MESSAGE_HAS(error("{\"curves\": [\n"), "c.json: invalid JSON at byte");
  EXPECT_MESSAGE_HAS(error("[]"), "c.json:1: expected a JSON object");
  EXPECT_MESSAGE_HAS(error("{}"), "c.json:1: expected a \"curves\" array");
  EXPECT_MESSAGE_HAS(error("{\"curves\": [],\n\"anchors\": []}"), "c.json:2: unknown member \"anchors\"");
  EXPECT_MESSAGE_HAS(error("{\"curves\": [\n{\"points\": [1, 2]}]}"),
                     "c.json:2: a curve must be an object with a string \"name\"");
  EXPECT_MESSAGE_HAS(error("{\"curves\": [\n{\"name\": \"w\", \"points\": [1, 2], \"colour\": 1}]}"),
                     "c.json:2: curve \"w\": unknown member \"colour\"");
  EXPECT_MESSAGE_HAS(error("{\"curves\": [\n{\"name\": \"w\", \"closed\": 1, \"points\": [1, 2]}]}"),
                     "c.json:2: curve \"w\": \"closed\" must be true or false");
  EXPECT_MESSAGE_HAS(error("{\"curves\": [\n{\"name\": \"w\"}]}"),
                     "c.json:2: curve \"w\": expected a \"points\" array");
  EXPECT_MESSAGE_HAS(error("{\"curves\": [\n{\"name\": \"w\", \"points\": [\n1,\n2.5]}]}"),
                     "c.json:4: curve \"w\": point 1: expected an integer index, got 2.5");
  EXPECT_MESSAGE_HAS(
      error("{\"curves\": [\n{\"name\": \"w\", \"points\": [\n1,\n{\"face\": 2}]}]}"),
      "c.json:4: curve \"w\": point 1: expected a vertex index or {\"face\": f, \"barycentric\": [a, b, c]}");
  EXPECT_MESSAGE_HAS(
      error(
          "{\"curves\": [\n{\"name\": \"w\", \"points\": [\n1,\n{\"face\": 2, \"barycentric\": [1, 0]}]}]}"),
      "c.json:4: curve \"w\": point 1: \"barycentric\" must be an array of 3 numbers");
}

TEST(CurveReader, ValidationErrorsNameFileCurveAndPoint) {
  const Mesh& mesh = human_man();
  const auto error = [&](const std::string& curves) {
    return test::error_message_of(
        [&] { validate_curves(parse_curves_json("{\"curves\": [\n" + curves + "]}", "c.json"), mesh); });
  };
  EXPECT_MESSAGE_HAS(error("{\"name\": \"w\", \"points\": [1, 6890]}"),
                     "c.json:2: curve \"w\": point 1: vertex 6890 out of range (the mesh has 6890 vertices)");
  EXPECT_MESSAGE_HAS(error("{\"name\": \"w\", \"points\": [-1, 2]}"),
                     "c.json:2: curve \"w\": point 0: vertex -1 out of range");
  EXPECT_MESSAGE_HAS(
      error("{\"name\": \"w\", \"points\": [1, {\"face\": 13776, \"barycentric\": [1, 0, 0]}]}"),
      "c.json:2: curve \"w\": point 1: face 13776 out of range (the mesh has 13776 faces)");
  EXPECT_MESSAGE_HAS(
      error("{\"name\": \"w\", \"points\": [1, {\"face\": 3, \"barycentric\": [0.5, 0.4, 0]}]}"),
      "c.json:2: curve \"w\": point 1: barycentric coordinates sum to 0.9");
  EXPECT_MESSAGE_HAS(error("{\"name\": \"w\", \"points\": [1]}"),
                     "c.json:2: curve \"w\": 1 points; an open curve needs at least 2");
  EXPECT_MESSAGE_HAS(error("{\"name\": \"w\", \"closed\": true, \"points\": [1, 2]}"),
                     "c.json:2: curve \"w\": 2 points; a closed curve needs at least 3");
  EXPECT_MESSAGE_HAS(error("{\"name\": \"w\", \"points\": [1, 2]},\n{\"name\": \"w\", \"points\": [3, 4]}"),
                     "c.json:3: curve \"w\": duplicate name (first at line 2)");
  EXPECT_MESSAGE_HAS(error("{\"name\": \"\", \"points\": [1, 2]}"), "c.json:2: curve \"\": empty name");
  // Face 0 is (0, 1, 2) in human_man.obj: (0, 1, 0) on face 0 is vertex 1.
  EXPECT_MESSAGE_HAS(
      error("{\"name\": \"w\", \"points\": [5, 1, {\"face\": 0, \"barycentric\": [0, 1, 0]}]}"),
      "c.json:2: curve \"w\": points 1 and 2 are at the same place");
  EXPECT_MESSAGE_HAS(error("{\"name\": \"w\", \"closed\": true, \"points\": [1, 5, 6, 1]}"),
                     "c.json:2: curve \"w\": points 3 and 0 are at the same place");
  // Open, the same curve is fine: its last and first points are not joined.
  EXPECT_NO_THROW(validate_curves(
      parse_curves_json("{\"curves\": [{\"name\": \"w\", \"points\": [1, 5, 6, 1]}]}", "c.json"), mesh));
}

TEST(CurveReader, FileErrorsNameThePath) {
  EXPECT_MESSAGE_HAS(test::error_message_of([] { read_curves(test::data_path("no_such.curves.json")); }),
                     "no_such.curves.json: cannot open the file");
}

// 100 KB of '[' once took 2.3 GB (each open level kept its JSON pointer) and failed with a bare
// std::bad_alloc; now both readers stop at kMaxJsonDepth, naming the file. 64 levels still parse.
TEST(JsonReaders, NestingIsBoundedAndTheErrorNamesTheFile) {
  const std::filesystem::path dir = test::fresh_temp_dir("json_depth");
  for (const char* name : {"deep.anchors.json", "deep.curves.json"}) {
    std::ofstream(dir / name) << std::string(100000, '[');
  }
  EXPECT_MESSAGE_HAS(test::error_message_of([&] { read_anchors(dir / "deep.anchors.json"); }),
                     "deep.anchors.json:1: JSON nested deeper than 64 levels");
  EXPECT_MESSAGE_HAS(test::error_message_of([&] { read_curves(dir / "deep.curves.json"); }),
                     "deep.curves.json:1: JSON nested deeper than 64 levels");
  const std::string deepest = std::string(kMaxJsonDepth, '[') + std::string(kMaxJsonDepth, ']');
  EXPECT_MESSAGE_HAS(test::error_message_of([&] { parse_anchors_json(deepest, "ok.json"); }),
                     "ok.json:1: expected a JSON object");
}

}  // namespace
}  // namespace xparam
