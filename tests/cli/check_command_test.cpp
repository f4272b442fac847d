// Tests of the `xparam check` program itself: exit status, JSON keys and values, messages.
#include "check_program_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <string>

namespace xparam {
namespace {

using test::ProgramRun;
using test::quoted;
using test::run;

ProgramRun check(const std::string& arguments, const std::string& test_name) {
  return run(quoted(test::xparam_binary()) + " check " + arguments, test_name);
}

nlohmann::json parse(const ProgramRun& r) {
  try {
    return nlohmann::json::parse(r.out);
  } catch (const nlohmann::json::exception& e) {
    ADD_FAILURE() << "not JSON: " << e.what() << "\n" << r.out;
    return nlohmann::json::array();
  }
}

// A tetrahedron with a fin: edge (1, 2) has three faces.
std::filesystem::path write_fin(const std::filesystem::path& dir) {
  const auto path = dir / "fin.obj";
  std::ofstream(path) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 1 1 1\n"
                         "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\nf 2 3 5\n";
  return path;
}

bool mentions(const nlohmann::json& strings, const std::string& text) {
  for (const auto& s : strings)
    if (s.get<std::string>().find(text) != std::string::npos) return true;
  return false;
}

TEST(CheckCommand, GoodMeshJson) {
  const ProgramRun r = check("--json " + quoted(test::data_path("human_man.obj")), "check_good");
  EXPECT_EQ(r.status, 0) << r.out;
  const nlohmann::json all = parse(r);
  ASSERT_EQ(all.size(), 1u);
  const nlohmann::json& m = all[0];
  for (const char* key : {"file", "vertices", "faces", "edges", "components", "boundary_loops", "genus", "valid",
                          "problems", "non_manifold_edges", "non_manifold_vertices", "degenerate_faces",
                          "duplicate_vertices", "bbox_min", "bbox_max", "mean_edge_length"})
    EXPECT_TRUE(m.contains(key)) << key;
  EXPECT_EQ(m["file"], test::data_path("human_man.obj").string());
  EXPECT_EQ(m["vertices"], 6890);
  EXPECT_EQ(m["faces"], 13776);
  EXPECT_EQ(m["edges"], 6890 + 13776 - 2);  // Euler: V - E + F = 2
  EXPECT_EQ(m["components"], 1);
  EXPECT_EQ(m["boundary_loops"], 0);
  EXPECT_EQ(m["genus"], 0);
  EXPECT_EQ(m["valid"], true);
  EXPECT_TRUE(m["problems"].empty());
  EXPECT_EQ(m["non_manifold_edges"], 0);
  EXPECT_EQ(m["bbox_min"].size(), 3u);
  EXPECT_LT(m["bbox_min"][1].get<double>(), m["bbox_max"][1].get<double>());
  EXPECT_GT(m["mean_edge_length"].get<double>(), 0.0);
  EXPECT_GT(m["signed_volume"].get<double>(), 0.0);
}

TEST(CheckCommand, GenusOneIsValidButSaysSo) {
  const ProgramRun r = check("--json " + quoted(test::data_path("bob_small.ply")), "check_bob");
  EXPECT_EQ(r.status, 0) << r.out;
  const nlohmann::json m = parse(r)[0];
  EXPECT_EQ(m["valid"], true);
  EXPECT_EQ(m["genus"], 1);
  EXPECT_EQ(m["euler_characteristic"], 0);
  EXPECT_EQ(m["vertices"], 250);
  EXPECT_EQ(m["faces"], 500);
}

TEST(CheckCommand, OpenMeshIsNotUsableWhenStrict) {
  const ProgramRun r = check("--json --intake strict " + quoted(test::data_path("cat_head.obj")), "check_cat_head");
  EXPECT_EQ(r.status, 2) << r.out;  // some mesh unusable
  const nlohmann::json m = parse(r)[0];
  EXPECT_EQ(m["valid"], false);
  EXPECT_EQ(m["boundary_loops"], 1);
  EXPECT_EQ(m["genus"], 0);  // a disk
  EXPECT_TRUE(mentions(m["problems"], "cat_head.obj: not closed: boundary loop of 12 edges")) << m["problems"];
}

TEST(CheckCommand, OpenMeshIsUsableAfterTheIntakeFillsItsHole) {
  // The head is open at the neck: a border of 4.4, over the default limit (a quarter of the diagonal).
  const ProgramRun r = check("--json --max-hole 5 " + quoted(test::data_path("cat_head.obj")), "check_cat_head_intake");
  EXPECT_EQ(r.status, 0) << r.out;
  const nlohmann::json m = parse(r)[0];
  EXPECT_EQ(m["valid"], true);
  EXPECT_EQ(m["usable_as_is"], false);
  ASSERT_EQ(m["intake"]["holes_filled"].size(), 1u) << m["intake"];
  EXPECT_GT(m["intake"]["filled_faces"].get<int>(), 10);  // a 12-gon, refined
  EXPECT_EQ(m["intake"]["problems_after"].size(), 0u);
  EXPECT_EQ(m["intake"]["genus_after"], 0);

  // The default limit refuses, naming the hole, the limit and the fix.
  const ProgramRun limited = check(quoted(test::data_path("cat_head.obj")), "check_cat_head_max");
  EXPECT_EQ(limited.status, 2) << limited.out;
  EXPECT_NE(limited.out.find("cat_head.obj: NOT usable"), std::string::npos) << limited.out;
  EXPECT_NE(limited.out.find("hole of 4.36 perimeter is over --max-hole 0.749 (25% of the bounding-box diagonal): "
                             "close it in a mesh editor, or raise --max-hole"),
            std::string::npos)
      << limited.out;
}

TEST(CheckCommand, NonManifoldEdgeIsNamed) {
  const auto fin = write_fin(test::fresh_temp_dir("check_fin_input"));
  const ProgramRun r = check("--json --intake strict " + quoted(fin), "check_fin");
  EXPECT_EQ(r.status, 2) << r.out;  // some mesh unusable
  const nlohmann::json m = parse(r)[0];
  EXPECT_EQ(m["valid"], false);
  EXPECT_EQ(m["non_manifold_edges"], 1);
  EXPECT_TRUE(m["genus"].is_null());
  EXPECT_TRUE(mentions(m["problems"], "fin.obj: edge (1, 2) has 3 faces")) << m["problems"];
}

TEST(CheckCommand, UnreadableFileIsReportedAndTheOthersStillChecked) {
  const auto dir = test::fresh_temp_dir("check_garbage_input");
  std::ofstream(dir / "garbage.ply") << "ply\nformat nonsense\n";
  const ProgramRun r = check("--json " + quoted(test::data_path("fox.ply")) + " " + quoted(dir / "garbage.ply") + " " +
                          quoted(test::data_path("spot.ply")),
                      "check_garbage");
  EXPECT_EQ(r.status, 2) << r.out;  // some mesh unusable
  const nlohmann::json all = parse(r);
  ASSERT_EQ(all.size(), 3u);
  EXPECT_EQ(all[0]["valid"], true);
  EXPECT_EQ(all[1]["valid"], false);
  EXPECT_NE(all[1]["error"].get<std::string>().find("garbage.ply"), std::string::npos) << all[1];
  EXPECT_EQ(all[2]["valid"], true);
  EXPECT_EQ(all[2]["vertices"], 2930);
}

TEST(CheckCommand, HumanReadableOutput) {
  ProgramRun r = check(quoted(test::data_path("spot_low_resolution.obj")), "check_human_good");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("spot_low_resolution.obj: usable"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("829 vertices, 1654 faces"), std::string::npos) << r.out;

  const auto fin = write_fin(test::fresh_temp_dir("check_human_fin_input"));
  r = check("--intake strict " + quoted(test::data_path("fox.ply")) + " " + quoted(fin), "check_human_bad");
  EXPECT_EQ(r.status, 2) << r.out;  // some mesh unusable
  EXPECT_NE(r.out.find("fin.obj: NOT usable"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("  error: " + fin.string() + ": edge (1, 2) has 3 faces"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("1 of 2 meshes usable"), std::string::npos) << r.out;
}

TEST(CheckCommand, MissingFileIsACommandLineError) {
  const ProgramRun r = check(quoted(test::fresh_temp_dir("check_missing") / "nowhere.obj"), "check_missing_run");
  EXPECT_EQ(r.status, 1);  // a usage error (CLI11's validation), not "checked and unusable" (2)
  EXPECT_NE(r.out.find("nowhere.obj"), std::string::npos) << r.out;
}

using test::compare_script;
using test::have_python;

TEST(CheckSharedData, ComparisonScriptCatchesAWrongCount) {
  if (!have_python()) GTEST_SKIP() << "python3 not available";
  const auto data = test::fresh_temp_dir("check_script_data");
  std::filesystem::create_directories(data / "set");
  std::filesystem::copy_file(test::data_path("bob_small.ply"), data / "set" / "bob.ply");
  const auto write_table = [&](const std::string& row) {
    std::ofstream(data / "set" / "SOURCE.txt")
        << "DATASET: test\nMESH STATS (verified):\n"
        << "file     V      F      boundary_loops  components  nonmanifold_edges  genus(if 1 comp; chi-based)  faces\n"
        << row << "\n";
  };
  write_table("bob.ply  250    500    0               1           0                  1                            3-gon:500");
  ProgramRun r = compare_script(data, "check_script_good");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("compared 1 meshes from 1 tables (0 listed meshes absent): all agree"), std::string::npos)
      << r.out;

  write_table("bob.ply  250    500    0               1           0                  0                            3-gon:500");
  r = compare_script(data, "check_script_bad");
  EXPECT_EQ(r.status, 2) << r.out;  // some mesh unusable
  EXPECT_NE(r.out.find("MISMATCH set/bob.ply: Euler characteristic: table 2 (genus 0), xparam 0"), std::string::npos)
      << r.out;
}

}  // namespace
}  // namespace xparam
