// `xparam layout` end to end: the written files, layout.json's verdict and counts, and a clear
// non-zero exit for a pair that cannot be laid out.
#include "support/test_data.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <sstream>
#include <string>

namespace xparam {
namespace {

namespace fs = std::filesystem;

// Eight SMPL vertices spread over the body, as a flat anchors JSON.
fs::path write_anchors(const fs::path& dir) {
  const fs::path path = dir / "anchors.json";
  std::ofstream(path) << R"({"head": 412, "left wrist": 2241, "right wrist": 5559, "left heel": 3458,
    "right heel": 6858, "belly": 3501, "back": 3022, "neck": 3050})";
  return path;
}

std::string ply_header(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string header, line;
  while (std::getline(in, line) && line != "end_header") header += line + "\n";
  return header;
}

nlohmann::json run_layout(const fs::path& dir, const std::string& extra) {
  const fs::path anchors = write_anchors(dir);
  std::string errors;
  const std::string arguments = "layout --source " + test::data_path("human_man.obj").string() +
                                " --source-anchors " + anchors.string() + " --target " +
                                test::data_path("human_woman.obj").string() + " --target-anchors " +
                                anchors.string() + " --out " + (dir / "out").string() + " --check " + extra;
  EXPECT_EQ(test::run_xparam(arguments, dir, errors), 0) << errors;
  std::ifstream in(dir / "out" / "layout.json");
  return nlohmann::json::parse(in);
}

TEST(LayoutCommand, WritesBothRefinedMeshesAndTheSummary) {
  const fs::path dir = test::fresh_temp_dir("layout_command");
  const nlohmann::json summary = run_layout(dir, "--optimize none --no-merge --no-stretch");
  // The layout as built: a triangulation of the 8 anchors.
  EXPECT_EQ(summary["anchors"], 8);
  EXPECT_EQ(summary["edges"], 18);
  EXPECT_EQ(summary["patches"], 12);
  EXPECT_EQ(summary["consistent"], true);
  EXPECT_TRUE(summary["violations"].empty());
  EXPECT_EQ(summary["optimization"]["swaps"], 0);
  EXPECT_EQ(summary["optimization"]["merges"], 0);
  EXPECT_GE(summary["refined_vertices"]["source"].get<int>(), 0);
  EXPECT_GE(summary["refined_vertices"]["target"].get<int>(), 0);
  for (const char* stage :
       {"load", "anchors", "candidates", "tree", "diagonals", "patches", "optimize", "check", "write"}) {
    EXPECT_TRUE(summary["seconds"].contains(stage)) << stage;
  }
  for (const char* side : {"source", "target"}) {
    const std::string header = ply_header(dir / "out" / (std::string(side) + ".ply"));
    EXPECT_NE(header.find("property int anchor"), std::string::npos) << header;
    EXPECT_NE(header.find("property int patch"), std::string::npos) << header;
    EXPECT_NE(header.find("property uchar red"), std::string::npos) << header;
    EXPECT_TRUE(fs::exists(dir / "out" / (std::string(side) + "_edges.obj")));
  }
}

TEST(LayoutCommand, ExportsTheOptimizedDomains) {
  const fs::path dir = test::fresh_temp_dir("layout_command_optimized");
  const nlohmann::json summary = run_layout(dir, "");
  EXPECT_EQ(summary["consistent"], true) << summary["violations"];
  EXPECT_EQ(summary["optimization"]["metric"], "balanced");
  const int merges = summary["optimization"]["merges"].get<int>();
  EXPECT_GE(merges, 1);  // merging is on by default, and the 8-anchor domains do merge
  // Every merge removes one curve and one patch; Euler's formula holds throughout.
  EXPECT_EQ(summary["edges"].get<int>(), 18 - merges);
  EXPECT_EQ(summary["patches"].get<int>(), 12 - merges);
  EXPECT_EQ(summary["patch_halfedges"].size(), summary["patches"].get<std::size_t>());
  EXPECT_GT(summary["optimization"]["vertices_added"][0].get<int>(), 0);  // the curves were stretched
}

TEST(LayoutCommand, GenusMismatchExitsNonZeroWithAClearMessage) {
  const fs::path dir = test::fresh_temp_dir("layout_command_genus");
  const fs::path anchors = dir / "anchors.txt";
  std::ofstream(anchors) << "a 0\nb 40\nc 80\nd 120\n";
  std::string errors;
  const std::string arguments = "layout --source " + test::data_path("spot_low_resolution.obj").string() +
                                " --source-anchors " + anchors.string() + " --target " +
                                test::data_path("bob_small.ply").string() + " --target-anchors " +
                                anchors.string() + " --out " + (dir / "out").string();
  EXPECT_NE(test::run_xparam(arguments, dir, errors), 0);
  EXPECT_NE(errors.find("target mesh has genus 1"), std::string::npos) << errors;
  EXPECT_FALSE(fs::exists(dir / "out" / "layout.json"));
}

}  // namespace
}  // namespace xparam
