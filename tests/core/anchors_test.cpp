#include "core/anchors.h"

#include "core/errors.h"
#include "support/expect_error.h"
#include "support/small_meshes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace xparam {
namespace {

AnchorSpec vertex_anchor(const std::string& name, int index, const std::string& file = "a.txt",
                         int line = 1) {
  return {name, AnchorVertex{index}, file, line};
}

AnchorSet four_vertices(const std::string& file) {
  return {file,
          {vertex_anchor("Nose", 1, file, 1), vertex_anchor("Lt. Axilla, Ant.", 2, file, 2),
           vertex_anchor("tail", 3, file, 3), vertex_anchor("Tail", 4, file, 4)}};
}

TEST(Anchors, WhereNamesFileAndLine) {
  EXPECT_EQ(where(vertex_anchor("x", 0, "dir/a.txt", 12)), "dir/a.txt:12");
  EXPECT_EQ(where(vertex_anchor("x", 0, "a.json", 0)), "a.json");
  EXPECT_EQ(where(vertex_anchor("x", 0, "", 0)), "<code>");
}

TEST(Anchors, BarycentricProblems) {
  EXPECT_EQ(barycentric_problem({0.2, 0.3, 0.5}), "");
  EXPECT_EQ(barycentric_problem({1.0, 0.0, 0.0}), "");
  EXPECT_EQ(barycentric_problem({0.33333, 0.33333, 0.33333}), "");  // 5 decimals: within tolerance
  EXPECT_EQ(barycentric_problem({-5e-5, 0.5, 0.50005}), "");
  EXPECT_NE(barycentric_problem({0.3, 0.3, 0.3}).find("sum to 0.9"), std::string::npos);
  EXPECT_NE(barycentric_problem({-0.1, 0.6, 0.5}).find("negative"), std::string::npos);
  EXPECT_NE(barycentric_problem({std::nan(""), 0.5, 0.5}).find("not finite"), std::string::npos);
}

TEST(Anchors, CheckAnchorRejectsEachBadLocation) {
  EXPECT_NE(test::error_message_of([] {
              check_anchor(vertex_anchor("Nose", -3, "a.txt", 7));
            }).find("a.txt:7: anchor \"Nose\": negative vertex index -3"),
            std::string::npos);
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_NE(test::error_message_of([&] {
              check_anchor({"P", AnchorPosition{{0, inf, 0}}, "a.pp", 3});
            }).find("a.pp:3: anchor \"P\": position is not finite"),
            std::string::npos);
  EXPECT_NE(test::error_message_of([] {
              check_anchor({"F", SurfacePoint{-1, {1, 0, 0}}, "a.json", 2});
            }).find("negative face index -1"),
            std::string::npos);
  EXPECT_NE(test::error_message_of([] {
              check_anchor({"F", SurfacePoint{4, {0.5, 0.6, 0}}, "a.json", 2});
            }).find("a.json:2: anchor \"F\": barycentric coordinates sum to 1.1"),
            std::string::npos);
  EXPECT_NE(test::error_message_of([] {
              check_anchor(vertex_anchor("", 1, "a.txt", 5));
            }).find("a.txt:5: anchor with an empty name"),
            std::string::npos);
  EXPECT_NO_THROW(check_anchor({"F", SurfacePoint{4, {0.25, 0.25, 0.5}}, "a.json", 2}));
}

TEST(Anchors, CheckSetFindsDuplicatesAndTooFewAnchors) {
  // Names are case-sensitive and may hold punctuation: "tail" and "Tail" are two anchors.
  EXPECT_NO_THROW(check_anchor_set(four_vertices("a.txt")));

  AnchorSet duplicate_name = four_vertices("a.txt");
  duplicate_name.anchors.push_back(vertex_anchor("Nose", 9, "a.txt", 8));
  const std::string name_message = test::error_message_of([&] { check_anchor_set(duplicate_name); });
  EXPECT_NE(name_message.find("a.txt:8: duplicate anchor name \"Nose\" (first at a.txt:1)"),
            std::string::npos)
      << name_message;

  AnchorSet same_vertex = four_vertices("a.txt");
  same_vertex.anchors.push_back(vertex_anchor("Chin", 2, "a.txt", 9));
  const std::string vertex_message = test::error_message_of([&] { check_anchor_set(same_vertex); });
  EXPECT_NE(
      vertex_message.find("a.txt:9: anchor \"Chin\": same vertex 2 as anchor \"Lt. Axilla, Ant.\" (a.txt:2)"),
      std::string::npos)
      << vertex_message;

  AnchorSet three = four_vertices("a.txt");
  three.anchors.pop_back();
  EXPECT_EQ(test::error_message_of([&] { check_anchor_set(three); }),
            "a.txt: 3 anchors; at least 4 are needed");
}

TEST(Anchors, MatchReordersTheTargetIntoTheSourceOrder) {
  const AnchorSet source = four_vertices("template.json");
  AnchorSet target{"scan.pp", {}};
  // Same names, other order, positions instead of indices.
  for (int i : {2, 0, 3, 1}) {
    target.anchors.push_back({source.anchors[i].name, AnchorPosition{{double(i), 0, 0}}, "scan.pp", 10 + i});
  }
  const AnchorSet matched = match_anchors(source, target);
  EXPECT_EQ(matched.source, "scan.pp");
  ASSERT_EQ(matched.anchors.size(), 4u);
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(matched.anchors[i].name, source.anchors[i].name);
    EXPECT_EQ(matched.anchors[i].line, 10 + i);
    EXPECT_EQ(std::get<AnchorPosition>(matched.anchors[i].location).point.x(), double(i));
  }
}

TEST(Anchors, MatchListsTheNamesMissingOnEachSideWithBothFiles) {
  const AnchorSet source = four_vertices("template.json");
  AnchorSet target = four_vertices("scan.pp");
  target.anchors[0].name = "nose";  // case differs: missing on both sides
  target.anchors.push_back(vertex_anchor("Chin", 7, "scan.pp", 5));
  const std::string message = test::error_message_of([&] { match_anchors(source, target); });
  EXPECT_EQ(
      message,
      "anchors differ between template.json and scan.pp; missing in scan.pp: \"Nose\" (template.json:1); "
      "missing in template.json: \"nose\" (scan.pp:1), \"Chin\" (scan.pp:5)");
}

TEST(Anchors, MatchRefusesADuplicateName) {
  const AnchorSet source = four_vertices("template.json");
  AnchorSet target = four_vertices("scan.txt");
  target.anchors[3] = vertex_anchor("tail", 8, "scan.txt", 4);
  EXPECT_NE(test::error_message_of([&] {
              match_anchors(source, target);
            }).find("scan.txt:4: duplicate anchor name \"tail\" (first at scan.txt:3)"),
            std::string::npos);
}

TEST(Anchors, VertexSurfacePointIsTheVertex) {
  const Mesh mesh = test::tetrahedron_mesh();
  for (VertexHandle v : mesh.vertices()) {
    const SurfacePoint point = vertex_surface_point(mesh, v);
    int lowest = std::numeric_limits<int>::max();
    for (FaceHandle f : mesh.vf_range(v)) lowest = std::min(lowest, f.idx());
    EXPECT_EQ(point.face, lowest);
    EXPECT_EQ(point.bary.sum(), 1.0);
    EXPECT_EQ(point.bary.maxCoeff(), 1.0);
    EXPECT_EQ((position(mesh, point) - position(mesh, v)).norm(), 0.0);
  }
}

}  // namespace
}  // namespace xparam
