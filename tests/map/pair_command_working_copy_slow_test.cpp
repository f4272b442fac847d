// `xparam pair --work-vertices` end to end: the bundled woman refined once (the same surface,
// 27,554 vertices) written as a file and mapped through an 8,000-vertex working copy. Every output
// refers to that file: correspondence rows are points of its faces at the remesh's vertices, the
// anchors (vertex ids of the file) are its vertices exactly, and metrics.json says a working copy
// was used, its size and the carry-back distance.
#include "core/midpoint_subdivision.h"
#include "io/mesh_loader.h"
#include "io/mesh_writer.h"
#include "support/correspondence_csv.h"
#include "support/plain_obj.h"
#include "support/test_data.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <string>
#include <vector>

namespace xparam {
namespace {

namespace fs = std::filesystem;

TEST(PairCommandWorkingCopy, OutputsReferToTheLargeFileAndItsAnchorsAreExact) {
  const fs::path dir = test::fresh_temp_dir("pair_command_working_copy");
  const fs::path target = dir / "woman_fine.obj";
  write_obj(target, subdivide_midpoint(load_mesh(test::data_path("sample_targets/woman.obj")).mesh));
  const fs::path out = dir / "out";
  std::string errors;
  ASSERT_EQ(test::run_xparam("pair --quiet --source " + test::data_path("human_man.obj").string() +
                                 " --source-anchors " + test::data_path("human.anchors.json").string() +
                                 " --target " + target.string() + " --target-anchors " +
                                 test::data_path("sample_targets/woman.anchors.json").string() +
                                 " --work-vertices 8000 --out " + out.string(),
                             dir, errors),
            0)
      << errors;

  std::ifstream metrics_file(out / "metrics.json");
  const nlohmann::json metrics = nlohmann::json::parse(metrics_file);
  ASSERT_TRUE(metrics.contains("working_copy"));
  const nlohmann::json& copy = metrics["working_copy"];
  EXPECT_EQ(copy["target_vertices"], 27554);
  EXPECT_EQ(copy["vertices"], 8000);
  EXPECT_GE(copy["max_carry_distance"].get<double>(), copy["mean_carry_distance"].get<double>());

  const test::PlainObj file = test::read_plain_obj(target);
  const test::PlainObj remesh = test::read_plain_obj(out / "remesh.obj");
  const test::CorrespondenceCsv csv = test::read_correspondence_csv(out / "correspondence.csv");
  ASSERT_EQ(csv.rows.size(), remesh.vertices.size());
  for (std::size_t v = 0; v < csv.rows.size(); ++v) {
    const std::vector<double>& values = csv.rows[v];
    ASSERT_EQ(values.size(), 7u) << "row " << v;
    const int face = static_cast<int>(values[1]);
    ASSERT_GE(face, 0);
    ASSERT_LT(face, static_cast<int>(file.faces.size())) << "a face of the working copy, not of the file";
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) x += values[2 + k] * file.vertices[file.faces[face][k]];
    EXPECT_LT((x - remesh.vertices[v]).norm(), 1e-9) << "row " << v;
  }

  // Each landmark of the template (a vertex) lands on the woman's landmark, a vertex of the file.
  std::ifstream template_anchors(test::data_path("human.anchors.json"));
  std::ifstream target_anchors(test::data_path("sample_targets/woman.anchors.json"));
  const nlohmann::json on_template = nlohmann::json::parse(template_anchors);
  const nlohmann::json on_target = nlohmann::json::parse(target_anchors);
  int checked = 0;
  for (const nlohmann::json& anchor : on_template["anchors"]) {
    for (const nlohmann::json& other : on_target["anchors"]) {
      if (other["name"] != anchor["name"] || !other.contains("vertex")) continue;
      const Eigen::Vector3d& landmark = file.vertices[other["vertex"].get<int>()];
      EXPECT_LT((remesh.vertices[anchor["vertex"].get<int>()] - landmark).norm(), 1e-15) << anchor["name"];
      ++checked;
    }
  }
  EXPECT_GT(checked, 0);
}

}  // namespace
}  // namespace xparam
