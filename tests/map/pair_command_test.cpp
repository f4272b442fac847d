// `xparam pair` end to end on the bundled man -> woman pair: the written files agree with each
// other (remesh vertex i is correspondence row i evaluated on the target file), the remesh has
// the template's faces, metrics.json reports the untangling, `--no-untangle` leaves the folds
// (listed, credited to anchors, marked in stretch.ply), and a failing pair exits 3 without
// writing results.
#include "support/correspondence_csv.h"
#include "support/plain_obj.h"
#include "support/test_data.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace xparam {
namespace {

namespace fs = std::filesystem;

std::string pair_arguments(const fs::path& out, const std::string& extra = "") {
  return "pair --quiet --source " + test::data_path("human_man.obj").string() + " --source-anchors " +
         test::data_path("human.anchors.json").string() + " --target " +
         test::data_path("sample_targets/woman.obj").string() + " --target-anchors " +
         test::data_path("sample_targets/woman.anchors.json").string() + " --out " + out.string() + " " +
         extra;
}

nlohmann::json read_json(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

// The mapped runs are shared by the tests below (each takes about a second).
const fs::path& default_run() {
  static const fs::path out = [] {
    const fs::path dir = test::fresh_temp_dir("pair_command_default");
    std::string errors;
    const std::string curves = " --curves " + test::data_path("human_man.curves.json").string();
    EXPECT_EQ(test::run_xparam(pair_arguments(dir / "out", curves), dir, errors), 0) << errors;
    return dir / "out";
  }();
  return out;
}

TEST(PairCommand, RemeshIsTheCorrespondenceOnTheTargetWithTheTemplatesFaces) {
  const fs::path out = default_run();
  const test::PlainObj remesh = test::read_plain_obj(out / "remesh.obj");
  const test::PlainObj source = test::read_plain_obj(test::data_path("human_man.obj"));
  const test::PlainObj target = test::read_plain_obj(test::data_path("sample_targets/woman.obj"));
  ASSERT_EQ(remesh.vertices.size(), source.vertices.size());
  EXPECT_EQ(remesh.faces, source.faces);

  const test::CorrespondenceCsv csv = test::read_correspondence_csv(out / "correspondence.csv");
  EXPECT_EQ(csv.header, "vertex,face,b0,b1,b2,filled,distance_to_scan");
  std::size_t rows = 0;
  for (const std::vector<double>& values : csv.rows) {
    const std::string line = "row " + std::to_string(rows);
    ASSERT_EQ(values.size(), 7u) << line;
    EXPECT_EQ(values[5], 0.0) << line;  // a clean target: nothing filled in
    const int vertex = static_cast<int>(values[0]);
    const int face = static_cast<int>(values[1]);
    ASSERT_EQ(vertex, static_cast<int>(rows));
    ASSERT_GE(face, 0);
    ASSERT_LT(face, static_cast<int>(target.faces.size()));
    EXPECT_NEAR(values[2] + values[3] + values[4], 1.0, 1e-12) << line;
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(values[2 + k], -1e-12) << line;
      x += values[2 + k] * target.vertices[target.faces[face][k]];
    }
    // The OBJ writes 17 significant digits: the same point up to rounding.
    EXPECT_LT((x - remesh.vertices[vertex]).norm(), 1e-9) << "vertex " << vertex;
    ++rows;
  }
  EXPECT_EQ(rows, source.vertices.size());
}

TEST(PairCommand, MetricsReportTheMapTheUntanglingAndTheStages) {
  const nlohmann::json metrics = read_json(default_run() / "metrics.json");
  EXPECT_EQ(metrics["flipped_faces"], 0);
  EXPECT_GT(metrics["E_L2"].get<double>(), 1.0);
  EXPECT_LT(metrics["E_L2"].get<double>(), 1.1);  // measured 1.004
  EXPECT_NEAR(metrics["area_ratio"].get<double>(), 1.0, 0.02);
  // The 41 given and the tips a round of them added (a round wins on this pair: 4 tips), but for
  // those the map was pulled onto (no layout through them).
  int pulled = 0;
  for (const nlohmann::json& tip : metrics["extremity_anchors"]) pulled += tip["pulled"].get<bool>();
  EXPECT_EQ(metrics["anchors"], 41 + metrics["extremity_anchors"].size() - pulled);
  EXPECT_EQ(metrics["layouts"]["built"], 1);  // no fold on the first layout: no later one
  EXPECT_EQ(metrics["layouts"]["kept"], 1);
  EXPECT_EQ(metrics["released_anchors"], nlohmann::json::array());  // no fold, and releasing is off
  EXPECT_TRUE(metrics["mismatched_corners"].is_array());
  EXPECT_EQ(metrics["tip_anchors"], nlohmann::json::array());  // no fold: no helper anchor tried
  EXPECT_EQ(metrics["relaxation"]["enabled"], true);
  EXPECT_LE(metrics["relaxation"]["energy_after"].get<double>(),
            metrics["relaxation"]["energy_before"].get<double>());
  EXPECT_GE(metrics["relaxation"]["energy_after"].get<double>(),
            4.0);  // an isometry's symmetric Dirichlet energy
  EXPECT_EQ(metrics["untangling"]["enabled"], true);
  // Gamma alone folds a few faces at the toes and the crotch; untangling moved some vertices.
  EXPECT_GE(metrics["untangling"]["flipped_before"].get<int>(), 1);
  EXPECT_GE(metrics["untangling"]["moved_vertices"].get<int>(), 1);
  EXPECT_EQ(metrics["optimization"]["metric"], "balanced");
  for (const char* stage :
       {"anchors", "layout", "optimize", "parameterize", "relax", "compose", "untangle", "metrics"})
    EXPECT_GE(metrics["seconds"][stage].get<double>(), 0.0) << stage;
  EXPECT_TRUE(fs::exists(default_run() / "stretch.ply"));
}

TEST(PairCommand, CurvesAreTracedOnTheTargetAsSurfacePointsAndPolylines) {
  const nlohmann::json curves = read_json(default_run() / "curves.json")["curves"];
  std::ifstream in(test::data_path("human_man.curves.json"));
  const nlohmann::json given = nlohmann::json::parse(in)["curves"];
  const test::PlainObj target = test::read_plain_obj(test::data_path("sample_targets/woman.obj"));
  ASSERT_EQ(curves.size(), given.size());
  for (std::size_t c = 0; c < curves.size(); ++c) {
    EXPECT_EQ(curves[c]["name"], given[c]["name"]);
    // Traced across the target's faces: a point wherever the curve crosses an edge, so more
    // points than the template curve's own.
    ASSERT_GT(curves[c]["points"].size(), given[c]["points"].size());
    // Every point is a target surface point, and its position is that point.
    for (const nlohmann::json& point : curves[c]["points"]) {
      const std::array<int, 3>& face = target.faces.at(point["face"].get<std::size_t>());
      Eigen::Vector3d x = Eigen::Vector3d::Zero();
      for (int k = 0; k < 3; ++k) x += point["barycentric"][k].get<double>() * target.vertices[face[k]];
      const Eigen::Vector3d written(point["position"][0].get<double>(), point["position"][1].get<double>(),
                                    point["position"][2].get<double>());
      EXPECT_LT((x - written).norm(), 1e-9);
    }
  }
  EXPECT_TRUE(fs::exists(default_run() / "curves.obj"));
}

TEST(PairCommand, NoUntangleLeavesTheFoldsOfGamma) {
  const fs::path dir = test::fresh_temp_dir("pair_command_tangled");
  std::string errors;
  // Optimizing the map unfolds too, and mapping again through protrusion tips makes another
  // map: both off, to see Gamma itself.
  const std::string gamma = "--no-optimize-map --no-extremity-anchors";
  ASSERT_EQ(test::run_xparam(pair_arguments(dir / "out", "--no-untangle " + gamma), dir, errors), 0) << errors;
  ASSERT_EQ(test::run_xparam(pair_arguments(dir / "untangled", gamma), dir, errors), 0) << errors;
  const nlohmann::json tangled = read_json(dir / "out" / "metrics.json");
  const nlohmann::json untangled = read_json(dir / "untangled" / "metrics.json");
  EXPECT_EQ(tangled["untangling"]["enabled"], false);
  EXPECT_EQ(tangled["untangling"]["moved_vertices"], 0);
  EXPECT_EQ(tangled["flipped_faces"], untangled["untangling"]["flipped_before"]);
  // Where the folds are: listed, and each credited to one anchor.
  ASSERT_GE(tangled["flipped_faces"].get<int>(), 1);
  EXPECT_EQ(tangled["flipped_face_ids"].size(), tangled["flipped_faces"].get<std::size_t>());
  int credited = 0;
  for (const nlohmann::json& near : tangled["folds_by_anchor"]) credited += near["folded_faces"].get<int>();
  EXPECT_EQ(credited, tangled["flipped_faces"].get<int>());
  std::ifstream ply(dir / "out" / "stretch.ply", std::ios::binary);
  std::string header;
  for (std::string line; std::getline(ply, line) && line != "end_header";) header += line + "\n";
  EXPECT_NE(header.find("property int flipped"), std::string::npos) << header;
}

TEST(PairCommand, RefusedInputsExitTwoAndWriteNoResults) {
  const fs::path dir = test::fresh_temp_dir("pair_command_failing");
  // Anchors the target does not have: the pair cannot be matched, a refused input (exit 2, as
  // check and batch give for inputs they refuse).
  const fs::path wrong = dir / "wrong.anchors.json";
  std::ofstream(wrong) << R"({"head": 412, "left wrist": 2241, "right wrist": 5559, "nowhere": 3458})";
  const std::string arguments = "pair --quiet --source " + test::data_path("human_man.obj").string() +
                                " --source-anchors " + test::data_path("human_man.anchors.json").string() +
                                " --target " + test::data_path("sample_targets/woman.obj").string() +
                                " --target-anchors " + wrong.string() + " --out " + (dir / "out").string();
  std::string errors;
  EXPECT_EQ(test::run_xparam(arguments, dir, errors), 2);
  EXPECT_NE(errors.find("nowhere"), std::string::npos) << errors;
  EXPECT_FALSE(fs::exists(dir / "out" / "metrics.json"));
  EXPECT_FALSE(fs::exists(dir / "out" / "correspondence.csv"));
}

TEST(PairCommand, ANegativeReleaseLimitIsRefusedBeforeMapping) {
  const fs::path dir = test::fresh_temp_dir("pair_command_release_limit");
  std::string errors;
  EXPECT_NE(test::run_xparam(pair_arguments(dir / "out", "--release-anchors -1"), dir, errors), 0);
  EXPECT_NE(errors.find("--release-anchors"), std::string::npos) << errors;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

}  // namespace
}  // namespace xparam
