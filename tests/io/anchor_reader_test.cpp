#include "io/anchor_reader.h"

#include "core/anchor_placement.h"
#include "core/errors.h"
#include "core/provenance.h"
#include "support/expect_error.h"
#include "support/test_data.h"

#include <gtest/gtest.h>
#include <OpenMesh/Core/IO/MeshIO.hh>

#include <algorithm>
#include <fstream>
#include <limits>
#include <set>

namespace xparam {
namespace {

Mesh load(const std::filesystem::path& path) {
  Mesh mesh;
  EXPECT_TRUE(OpenMesh::IO::read_mesh(mesh, path.string())) << path;
  return mesh;
}

std::vector<std::string> names_of(const AnchorSet& set) {
  std::vector<std::string> names;
  for (const AnchorSpec& anchor : set.anchors) names.push_back(anchor.name);
  return names;
}

double bbox_diagonal(const Mesh& mesh) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (VertexHandle v : mesh.vertices()) {
    lo = lo.cwiseMin(position(mesh, v));
    hi = hi.cwiseMax(position(mesh, v));
  }
  return (hi - lo).norm();
}

// Fraction of the mesh's vertices strictly below vertex v in y (the meshes here are y-up).
double height_rank(const Mesh& mesh, int v) {
  const double y = mesh.point(mesh.vertex_handle(v))[1];
  int below = 0;
  for (VertexHandle w : mesh.vertices()) below += mesh.point(w)[1] < y;
  return static_cast<double>(below) / static_cast<double>(mesh.n_vertices());
}

int vertex_of(const AnchorSet& set, const std::string& name) {
  for (const AnchorSpec& anchor : set.anchors) {
    if (anchor.name == name) return std::get<AnchorVertex>(anchor.location).index;
  }
  ADD_FAILURE() << "no anchor " << name;
  return -1;
}

// ----------------------------------------------------------------------------------------
// The bundled files: one truth in three forms.

TEST(AnchorReader, HumanAnchorsAgreeAcrossJsonTextAndPickedPoints) {
  const AnchorSet json = read_anchors(test::data_path("human_man.anchors.json"));
  const AnchorSet text = read_anchors(test::data_path("anchors/human_man.txt"));
  const AnchorSet picked = read_anchors(test::data_path("anchors/human_man.pp"));
  ASSERT_EQ(json.anchors.size(), 29u);
  EXPECT_EQ(names_of(text), names_of(json));
  EXPECT_EQ(names_of(picked), names_of(json));  // the inactive point is skipped
  EXPECT_EQ(json.anchors[0].name, "HEAD_TOP");
  EXPECT_EQ(json.anchors[0].line, 4);
  EXPECT_EQ(json.anchors[28].name, "Rt. Ulnar Styloid");
  EXPECT_EQ(text.anchors[28].line, 32);

  const Mesh man = load(test::data_path("human_man.obj"));
  for (std::size_t i = 0; i < json.anchors.size(); ++i) {
    const int index = std::get<AnchorVertex>(json.anchors[i].location).index;
    EXPECT_EQ(std::get<AnchorVertex>(text.anchors[i].location).index, index) << json.anchors[i].name;
    // The picked points are the vertex positions as the OBJ file writes them (OpenMesh reads floats).
    const Eigen::Vector3d point = std::get<AnchorPosition>(picked.anchors[i].location).point;
    EXPECT_LT((point - position(man, man.vertex_handle(index))).norm(), 1e-6) << json.anchors[i].name;
  }

  // Placing the positions lands exactly on the indexed vertices, without refinement.
  Mesh refined = man;
  init_provenance(refined);
  const PlacedAnchors placed = place_anchors(refined, man, picked);
  EXPECT_EQ(placed.vertices_inserted, 0);
  EXPECT_TRUE(placed.warnings.empty());
  for (std::size_t i = 0; i < json.anchors.size(); ++i) {
    EXPECT_EQ(placed.anchors[i].vertex.idx(), std::get<AnchorVertex>(json.anchors[i].location).index)
        << json.anchors[i].name;
    EXPECT_LT(placed.anchors[i].snap_distance, 1e-6);
  }
  EXPECT_EQ(refined.n_vertices(), man.n_vertices());
}

TEST(AnchorReader, HumanAnchorsSitWhereTheirNamesSay) {
  const AnchorSet man_anchors = read_anchors(test::data_path("human_man.anchors.json"));
  const AnchorSet woman_anchors = read_anchors(test::data_path("human_woman.anchors.json"));
  EXPECT_EQ(names_of(match_anchors(man_anchors, woman_anchors)), names_of(man_anchors));
  for (const std::string name : {"human_man", "human_woman"}) {
    const Mesh mesh = load(test::data_path(name + ".obj"));
    const AnchorSet set = name == "human_man" ? man_anchors : woman_anchors;
    // Head top among the highest 0.5% of vertices, heels among the lowest 5%.
    EXPECT_GT(height_rank(mesh, vertex_of(set, "HEAD_TOP")), 0.995) << name;
    EXPECT_LT(height_rank(mesh, vertex_of(set, "LEFT_HEEL")), 0.05) << name;
    EXPECT_LT(height_rank(mesh, vertex_of(set, "RIGHT_HEEL")), 0.05) << name;
    // SMPL's left is +x: left landmarks on the left, right ones on the right.
    for (const std::string side :
         {"LEFT_WRIST", "LEFT_NIPPLE", "LEFT_SHOULDER", "LEFT_ELBOW", "LEFT_ANKLE"}) {
      EXPECT_GT(mesh.point(mesh.vertex_handle(vertex_of(set, side)))[0], 0.05) << name << " " << side;
    }
    for (const std::string side :
         {"RIGHT_WRIST", "RIGHT_NIPPLE", "RIGHT_SHOULDER", "Rt. Acromion", "Rt. Ulnar Styloid"}) {
      EXPECT_LT(mesh.point(mesh.vertex_handle(vertex_of(set, side)))[0], -0.05) << name << " " << side;
    }
    // Belly button in front of (greater z than) its back counterpart, crotch below the belly button.
    const auto at = [&](const std::string& anchor) {
      return mesh.point(mesh.vertex_handle(vertex_of(set, anchor)));
    };
    EXPECT_GT(at("BELLY_BUTTON")[2], at("BACK_BELLY_BUTTON")[2] + 0.1) << name;
    EXPECT_LT(at("CROTCH")[1], at("BELLY_BUTTON")[1] - 0.1) << name;
  }
}

TEST(AnchorReader, SpotAnchorsLieOnTheirMeshAndCorrespond) {
  const AnchorSet high = read_anchors(test::data_path("spot.anchors.json"));
  const AnchorSet low = read_anchors(test::data_path("spot_low_resolution.anchors.json"));
  ASSERT_EQ(high.anchors.size(), 12u);
  EXPECT_EQ(names_of(match_anchors(high, low)), names_of(high));
  struct Case {
    const AnchorSet* anchors;
    std::string own;
    std::string other;
  };
  for (const Case& c : {Case{&high, "spot.ply", "spot_low_resolution.obj"},
                        Case{&low, "spot_low_resolution.obj", "spot.ply"}}) {
    const Mesh own = load(test::data_path(c.own));
    const double diagonal = bbox_diagonal(own);
    Mesh refined = own;
    init_provenance(refined);
    const PlacedAnchors placed = place_anchors(refined, own, *c.anchors);
    std::set<AnchorInsertion> kinds;
    for (std::size_t i = 0; i < placed.anchors.size(); ++i) {
      EXPECT_LT(placed.anchors[i].snap_distance, 1e-6 * diagonal) << c.own << " " << placed.anchors[i].name;
      kinds.insert(placed.anchors[i].insertion);
      const Eigen::Vector3d p = position(refined, placed.anchors[i].vertex);
      const std::string& name = placed.anchors[i].name;
      // +x is Spot's right; hooves at the bottom, horn tips near the top.
      if (name.starts_with("Right")) {
        EXPECT_GT(p.x(), 0.1) << name;
      }
      if (name.starts_with("Left")) {
        EXPECT_LT(p.x(), -0.1) << name;
      }
      if (name.ends_with("hoof")) {
        EXPECT_LT(p.y(), -0.7) << name;
      }
      if (name.ends_with("horn tip")) {
        EXPECT_GT(p.y(), 0.9) << name;
      }
    }
    // Vertices, edge points (nose, tail) and face points (hooves, back, belly) all occur.
    EXPECT_EQ(kinds.size(), 3u) << c.own;

    // On the other Spot the same landmarks are within 3% of the diagonal (the two remeshes
    // differ in shape: horns, snout, ears).
    const Mesh other = load(test::data_path(c.other));
    Mesh other_refined = other;
    init_provenance(other_refined);
    const PlacedAnchors across = place_anchors(other_refined, other, *c.anchors);
    for (const PlacedAnchor& anchor : across.anchors) {
      EXPECT_LT(anchor.snap_distance, 0.03 * across.bbox_diagonal)
          << c.own << " on " << c.other << " " << anchor.name;
    }
  }
}

// ----------------------------------------------------------------------------------------
// The real landmark files of ../shared/data (flat JSON forms).

TEST(AnchorReader, FlatIndexFormOnSmplLandmarkTables) {
  const std::filesystem::path dir = test::shared_data_dir();
  if (dir.empty()) GTEST_SKIP() << "no ../shared/data";
  const AnchorSet caesar = read_anchors(dir / "faust_landmarks/smpl_caesar_landmark_indices.json");
  ASSERT_EQ(caesar.anchors.size(), 73u);
  EXPECT_EQ(vertex_of(caesar, "Lt. Axilla, Ant."), 1871);
  EXPECT_EQ(vertex_of(caesar, "Lt. Thelion/Bustpoint"), 598);
  EXPECT_EQ(caesar.anchors[0].name, "10th Rib Midspine");  // file order kept
  EXPECT_EQ(caesar.anchors[0].line, 2);

  // The bundled canonical file is a faithful transcription of the flat table.
  const AnchorSet flat = read_anchors(dir / "faust_landmarks/smpl_anthropometry_landmark_indices.json");
  const AnchorSet bundled = read_anchors(test::data_path("human_man.anchors.json"));
  ASSERT_EQ(names_of(flat), names_of(bundled));
  for (std::size_t i = 0; i < flat.anchors.size(); ++i) {
    EXPECT_EQ(std::get<AnchorVertex>(flat.anchors[i].location).index,
              std::get<AnchorVertex>(bundled.anchors[i].location).index);
  }

  // All 73 fit the SMPL vertex count and land on distinct vertices of the template.
  const Mesh man = load(test::data_path("human_man.obj"));
  Mesh refined = man;
  init_provenance(refined);
  EXPECT_EQ(place_anchors(refined, man, caesar).vertices_inserted, 0);
}

TEST(AnchorReader, FlatPositionFormSnapsFaustScanLandmarksOntoRegistrations) {
  const std::filesystem::path dir = test::shared_data_dir();
  if (dir.empty()) GTEST_SKIP() << "no ../shared/data";
  int meshes = 0;
  for (int scan = 0; scan < 100; ++scan) {
    char number[16];
    std::snprintf(number, sizeof number, "%03d", scan);
    const AnchorSet landmarks = read_anchors(dir / "faust_landmarks/scan_landmarks" /
                                             ("tr_scan_" + std::string(number) + "_landmarks.json"));
    ASSERT_EQ(landmarks.anchors.size(), 72u) << number;
    ASSERT_TRUE(std::holds_alternative<AnchorPosition>(landmarks.anchors[0].location));
    const std::filesystem::path registration =
        dir / "faust_registrations" / ("tr_reg_" + std::string(number) + ".ply");
    if (!std::filesystem::exists(registration)) continue;
    // SOURCE.txt: the scan landmarks lie within ~2 mm (max 11 mm) of the registration surface.
    const Mesh input = load(registration);
    Mesh refined = input;
    init_provenance(refined);
    const PlacedAnchors placed = place_anchors(refined, input, landmarks);
    double sum = 0.0;
    double most = 0.0;
    for (const PlacedAnchor& anchor : placed.anchors) {
      sum += anchor.snap_distance;
      most = std::max(most, anchor.snap_distance);
    }
    EXPECT_LT(sum / 72.0, 0.005) << registration;
    EXPECT_LT(most, 0.02) << registration;
    EXPECT_TRUE(placed.warnings.empty()) << registration;
    ++meshes;
  }
  EXPECT_GT(meshes, 0);
}

// ----------------------------------------------------------------------------------------
// JSON errors.

constexpr const char* kFourFlat = R"({"a": 1, "b": 2, "c": 3, "d": 4})";

TEST(AnchorReaderJson, CanonicalFormWithEveryLocationKind) {
  const AnchorSet set = parse_anchors_json(R"({
  "description": "test",
  "anchors": [
    {"name": "v", "vertex": 412},
    {"name": "p", "position": [1.5, -2, 3e-1]},
    {"name": "f", "face": 10, "barycentric": [0.25, 0.25, 0.5]},
    {"name": "whole", "vertex": 7.0}
  ]
})",
                                           "c.json");
  ASSERT_EQ(set.anchors.size(), 4u);
  EXPECT_EQ(std::get<AnchorVertex>(set.anchors[0].location).index, 412);
  EXPECT_EQ(std::get<AnchorPosition>(set.anchors[1].location).point, Eigen::Vector3d(1.5, -2, 0.3));
  EXPECT_EQ(std::get<SurfacePoint>(set.anchors[2].location).face, 10);
  EXPECT_EQ(std::get<SurfacePoint>(set.anchors[2].location).bary, Eigen::Vector3d(0.25, 0.25, 0.5));
  EXPECT_EQ(std::get<AnchorVertex>(set.anchors[3].location).index, 7);
  EXPECT_EQ(set.anchors[2].line, 6);
  EXPECT_EQ(set.anchors[2].file, "c.json");
}

TEST(AnchorReaderJson, ErrorsNameFileAndLine) {
  const auto error = [](const std::string& text) {
    return test::error_message_of([&] { parse_anchors_json(text, "e.json"); });
  };
  EXPECT_MESSAGE_HAS(error("{\"a\": 1,\n \"b\": }"), "e.json: invalid JSON at byte 16");
  EXPECT_MESSAGE_HAS(error("[1, 2]"), "e.json:1: expected a JSON object");
  EXPECT_MESSAGE_HAS(error("{\"a\": 1,\n\"b\": 2,\n\"c\": 3,\n\"a\": 4}"),
                     "e.json:4: duplicate member \"a\" (first at line 1)");
  EXPECT_MESSAGE_HAS(error("{\"a\": 1,\n\"b\": 2,\n\"c\": 3}"), "e.json: 3 anchors; at least 4 are needed");
  EXPECT_MESSAGE_HAS(error("{\"a\": 1, \"b\": 2,\n\"c\": -3, \"d\": 4}"),
                     "e.json:2: anchor \"c\": negative vertex index -3");
  EXPECT_MESSAGE_HAS(error("{\"a\": 1, \"b\": 2,\n\"c\": 1.5, \"d\": 4}"),
                     "e.json:2: anchor \"c\": expected an integer index, got 1.5");
  EXPECT_MESSAGE_HAS(error("{\"a\": 1, \"b\": 2,\n\"c\": [1, 2], \"d\": 4}"),
                     "e.json:2: anchor \"c\": expected an array of 3 numbers");
  EXPECT_MESSAGE_HAS(error("{\"a\": 1, \"b\": 2,\n\"c\": \"x\", \"d\": 4}"),
                     "e.json:2: anchor \"c\": expected a vertex index or [x, y, z]");
  EXPECT_MESSAGE_HAS(error("{\"a\": 1, \"b\": 2, \"c\": 3,\n\"d\": 1}"),
                     "e.json:2: anchor \"d\": same vertex 1 as anchor \"a\" (e.json:1)");
  EXPECT_MESSAGE_HAS(error("{\"a\": 1, \"b\": 2, \"c\": 3, \"d\": [0, 1e999, 0]}"),
                     "e.json: invalid JSON at byte");  // overflow

  const std::string head =
      "{\"anchors\": [\n{\"name\": \"a\", \"vertex\": 1},\n{\"name\": \"b\", \"vertex\": 2},\n{\"name\": "
      "\"c\", \"vertex\": 3},\n";
  EXPECT_MESSAGE_HAS(error(head + "{\"name\": \"a\", \"vertex\": 4}]}"),
                     "e.json:5: duplicate anchor name \"a\" (first at e.json:2)");
  EXPECT_MESSAGE_HAS(error(head + "{\"name\": \"d\", \"vertex\": 4, \"position\": [0, 0, 0]}]}"),
                     "e.json:5: anchor \"d\": give exactly one of \"vertex\", \"position\", or \"face\" with "
                     "\"barycentric\"");
  EXPECT_MESSAGE_HAS(error(head + "{\"name\": \"d\", \"face\": 4}]}"),
                     "e.json:5: anchor \"d\": \"face\" and \"barycentric\" go together");
  EXPECT_MESSAGE_HAS(error(head + "{\"name\": \"d\", \"face\": 4, \"barycentric\": [0.5, 0.6, 0]}]}"),
                     "e.json:5: anchor \"d\": barycentric coordinates sum to 1.1");
  EXPECT_MESSAGE_HAS(error(head + "{\"name\": \"d\",\n \"vertx\": 4}]}"),
                     "e.json:6: anchor \"d\": unknown member \"vertx\"");
  EXPECT_MESSAGE_HAS(error(head + "{\"vertex\": 4}]}"), "e.json:5: anchor without a string \"name\"");
  EXPECT_MESSAGE_HAS(error(head + "{\"name\": \"\", \"vertex\": 4}]}"),
                     "e.json:5: anchor with an empty name");
  EXPECT_MESSAGE_HAS(error(head + "7]}"), "e.json:5: an anchor must be an object");
  EXPECT_MESSAGE_HAS(error("{\"anchors\": {}}"), "e.json:1: \"anchors\" must be an array");
  EXPECT_MESSAGE_HAS(error("{\"anchors\": [],\n\"units\": \"m\"}"), "e.json:2: unknown member \"units\"");
}

TEST(AnchorReaderJson, SchemaExamplesAreReadAndSchemaMatchesTheReader) {
  const nlohmann::json schema = nlohmann::json::parse(
      read_text_file(std::filesystem::path(XPARAM_SOURCE_DIR) / "schemas" / "anchors.schema.json"));
  ASSERT_TRUE(schema.contains("examples"));
  for (const nlohmann::json& example : schema["examples"]) {
    EXPECT_NO_THROW(parse_anchors_json(example.dump(2), "schema example")) << example.dump();
  }
  // The members the schema allows are exactly the ones the reader knows.
  std::set<std::string> anchor_members;
  for (const auto& [member, value] : schema["$defs"]["anchor"]["properties"].items())
    anchor_members.insert(member);
  EXPECT_EQ(anchor_members, (std::set<std::string>{"name", "vertex", "position", "face", "barycentric"}));
  std::set<std::string> top_members;
  for (const auto& [member, value] : schema["$defs"]["canonical"]["properties"].items())
    top_members.insert(member);
  EXPECT_EQ(top_members, (std::set<std::string>{"$schema", "description", "anchors"}));
  EXPECT_EQ(schema["$defs"]["canonical"]["properties"]["anchors"]["minItems"].get<int>(), kMinAnchors);
  EXPECT_EQ(schema["$defs"]["flat"]["minProperties"].get<int>(), kMinAnchors);
}

// ----------------------------------------------------------------------------------------
// MeshLab picked points.

std::string picked(const std::string& points) {
  return "<!DOCTYPE PickedPoints>\n<PickedPoints>\n <DocumentData>\n  <DataFileName name=\"m.ply\"/>\n "
         "</DocumentData>\n" +
         points + "</PickedPoints>\n";
}

const std::string kThreePoints =
    " <point x=\"0\" y=\"0\" z=\"0\" active=\"1\" name=\"a\"/>\n"  // line 6
    " <point name=\"b\" x=\"1\" y=\"0\" z=\"0\"/>\n"               // line 7: no active = active
    " <point x='0' y='1' z='0' active='1' name='c'/>\n";           // line 8: single quotes

TEST(AnchorReaderPickedPoints, PointsInactivePointsCommentsAndEntities) {
  const AnchorSet set = parse_picked_points(
      picked(kThreePoints + " <point x=\"5\" y=\"5\" z=\"5\" active=\"0\" name=\"off\"/>\n"
                            " <!-- <point x=\"6\" y=\"6\" z=\"6\" name=\"commented\"/> -->\n"
                            " <point\n   x=\"-1.5e-3\" y=\"+2\" z=\"3\" active=\"1\" name=\"Lt. Axilla, Ant. "
                            "&amp; &#65;&#x42;\"/>\n"),
      "p.pp");
  ASSERT_EQ(names_of(set), (std::vector<std::string>{"a", "b", "c", "Lt. Axilla, Ant. & AB"}));
  EXPECT_EQ(set.anchors[1].line, 7);
  EXPECT_EQ(set.anchors[3].line, 11);
  EXPECT_EQ(std::get<AnchorPosition>(set.anchors[3].location).point, Eigen::Vector3d(-1.5e-3, 2, 3));
}

TEST(AnchorReaderPickedPoints, ErrorsNameFileAndLine) {
  const auto error = [](const std::string& text) {
    return test::error_message_of([&] { parse_picked_points(text, "e.pp"); });
  };
  EXPECT_MESSAGE_HAS(error("<points></points>"), "e.pp: not a MeshLab picked-points file");
  EXPECT_MESSAGE_HAS(error(picked(kThreePoints + " <point x=\"1\" y=\"1\" name=\"d\"/>\n")),
                     "e.pp:9: point \"d\" has no z attribute");
  EXPECT_MESSAGE_HAS(error(picked(kThreePoints + " <point x=\"1\" y=\"1,5\" z=\"0\" name=\"d\"/>\n")),
                     "e.pp:9: malformed number \"1,5\"");
  EXPECT_MESSAGE_HAS(error(picked(kThreePoints + " <point x=\"nan\" y=\"1\" z=\"0\" name=\"d\"/>\n")),
                     "e.pp:9: coordinate \"nan\" is not a finite number");
  EXPECT_MESSAGE_HAS(error(picked(kThreePoints + " <point x=\"1\" y=\"1\" z=\"1\"/>\n")),
                     "e.pp:9: <point> without a name attribute");
  EXPECT_MESSAGE_HAS(error(picked(kThreePoints + " <point x=\"1\" y=\"1\" z=\"1\" name=\"a\"/>\n")),
                     "e.pp:9: duplicate anchor name \"a\" (first at e.pp:6)");
  EXPECT_MESSAGE_HAS(
      error(picked(kThreePoints + " <point x=\"1\" y=\"1\" z=\"1\" active=\"yes\" name=\"d\"/>\n")),
      "e.pp:9: active=\"yes\"");
  EXPECT_MESSAGE_HAS(error(picked(kThreePoints + " <point x=\"1\" x=\"1\" y=\"1\" z=\"1\" name=\"d\"/>\n")),
                     "e.pp:9: attribute x given twice");
  EXPECT_MESSAGE_HAS(error(picked(kThreePoints + " <point x=\"1\" y=\"1\" z=\"1\" name=\"&bogus;\"/>\n")),
                     "e.pp:9: unknown XML entity \"&bogus;\"");
  EXPECT_MESSAGE_HAS(error(picked(kThreePoints + " <point x=1 y=\"1\" z=\"1\" name=\"d\"/>\n")),
                     "e.pp:9: attribute x of <point> has no quoted value");
  EXPECT_MESSAGE_HAS(error(picked(kThreePoints + " <point x=\"1\" y=\"1\" z=\"1\" name=\"d\"\n")),
                     "e.pp:9: unterminated <point> element");
  EXPECT_MESSAGE_HAS(error(picked(kThreePoints + " <!-- open\n")), "e.pp:9: unterminated XML comment");
  EXPECT_MESSAGE_HAS(error(picked(kThreePoints)), "e.pp: 3 anchors; at least 4 are needed");
}

// ----------------------------------------------------------------------------------------
// Plain text.

TEST(AnchorReaderText, IndicesPositionsQuotesAndComments) {
  const AnchorSet set = parse_anchors_text(
      "\xEF\xBB\xBF# header comment\n"
      "\n"
      "HEAD_TOP 412\n"
      "\"Lt. Acromion\" 1862   # trailing comment\r\n"
      "  tip -1.5 2e-3 +3\n"
      "\"say \\\"hi\\\" \\\\ there\" 7\n"
      "123 5\n",
      "t.txt");
  ASSERT_EQ(names_of(set),
            (std::vector<std::string>{"HEAD_TOP", "Lt. Acromion", "tip", "say \"hi\" \\ there", "123"}));
  EXPECT_EQ(set.anchors[1].line, 4);
  EXPECT_EQ(std::get<AnchorVertex>(set.anchors[1].location).index, 1862);
  EXPECT_EQ(std::get<AnchorPosition>(set.anchors[2].location).point, Eigen::Vector3d(-1.5, 2e-3, 3));
  EXPECT_EQ(std::get<AnchorVertex>(set.anchors[4].location).index, 5);
}

TEST(AnchorReaderText, ErrorsNameFileAndLine) {
  const auto error = [](const std::string& text) {
    return test::error_message_of([&] { parse_anchors_text(text, "e.txt"); });
  };
  const std::string three = "a 1\nb 2\n# c\nc 3\n";
  EXPECT_MESSAGE_HAS(error(three + "Lt. Acromion 1862\n"),
                     "e.txt:5: expected `name index` or `name x y z`, got 3 fields");
  EXPECT_MESSAGE_HAS(error(three + "d\n"), "e.txt:5: expected `name index` or `name x y z`, got 1 fields");
  EXPECT_MESSAGE_HAS(error(three + "\"Lt. Acromion 1862\n"), "e.txt:5: unterminated quoted name");
  EXPECT_MESSAGE_HAS(error(three + "\"d\"4\n"), "e.txt:5: missing space after the quoted name");
  EXPECT_MESSAGE_HAS(error(three + "d 4.5\n"),
                     "e.txt:5: anchor \"d\": vertex index \"4.5\" is not an integer");
  EXPECT_MESSAGE_HAS(error(three + "d four\n"), "e.txt:5: anchor \"d\": malformed vertex index \"four\"");
  EXPECT_MESSAGE_HAS(error(three + "d -4\n"), "e.txt:5: anchor \"d\": negative vertex index -4");
  EXPECT_MESSAGE_HAS(error(three + "d 99999999999\n"),
                     "e.txt:5: anchor \"d\": vertex index 99999999999 is out of range");
  EXPECT_MESSAGE_HAS(error(three + "d 1 nan 2\n"), "e.txt:5: coordinate \"nan\" is not a finite number");
  EXPECT_MESSAGE_HAS(error(three + "d 1 2 3x\n"), "e.txt:5: malformed number \"3x\"");
  EXPECT_MESSAGE_HAS(error(three + "b 4\n"), "e.txt:5: duplicate anchor name \"b\" (first at e.txt:2)");
  EXPECT_MESSAGE_HAS(error(three + "d 2\n"),
                     "e.txt:5: anchor \"d\": same vertex 2 as anchor \"b\" (e.txt:2)");
  EXPECT_MESSAGE_HAS(error(three + "\"\" 4\n"), "e.txt:5: anchor with an empty name");
  EXPECT_MESSAGE_HAS(error(three), "e.txt: 3 anchors; at least 4 are needed");
}

// ----------------------------------------------------------------------------------------
// Files.

TEST(AnchorReader, DispatchesOnTheExtensionCaseInsensitively) {
  const std::filesystem::path dir = test::fresh_temp_dir("anchor_reader");
  const auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir / name) << text;
    return dir / name;
  };
  EXPECT_EQ(read_anchors(write("a.JSON", kFourFlat)).anchors.size(), 4u);
  EXPECT_EQ(
      read_anchors(write("a.PP", picked(kThreePoints + " <point x=\"1\" y=\"1\" z=\"1\" name=\"d\"/>\n")))
          .anchors.size(),
      4u);
  EXPECT_EQ(read_anchors(write("a.landmarks", "a 1\nb 2\nc 3\nd 4\n")).anchors.size(), 4u);
  // A JSON file is not read as text: the error is a JSON one, naming the path.
  const std::filesystem::path broken = write("broken.json", "a 1\nb 2\nc 3\nd 4\n");
  EXPECT_MESSAGE_HAS(test::error_message_of([&] { read_anchors(broken); }),
                     broken.string() + ": invalid JSON at byte");
  EXPECT_MESSAGE_HAS(test::error_message_of([&] { read_anchors(dir / "missing.txt"); }),
                     "missing.txt: cannot open the file");
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace xparam
