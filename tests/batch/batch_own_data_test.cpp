// `xparam batch` on data laid out like FAUST's rather than by xparam's convention: meshes in one
// folder, landmark files named `{stem}_landmarks.json` in another, as `{"name": [x, y, z]}`, one
// template landmark missing on every scan; and --dry-run refusing what the run refuses.
#include "batch_test_support.h"

#include "io/archive_reader.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <sstream>

namespace xparam {
namespace {

using test::fs::path;
using test::quoted;

// Vertex positions of an OBJ file (its `v` lines).
std::vector<std::array<double, 3>> obj_vertices(const path& file) {
  std::vector<std::array<double, 3>> vertices;
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("v ", 0) != 0) continue;
    std::istringstream values(line.substr(2));
    std::array<double, 3> v{};
    values >> v[0] >> v[1] >> v[2];
    vertices.push_back(v);
  }
  return vertices;
}

// FAUST's landmark file of an SMPL-ordered mesh: {"name": [x, y, z]} at the template's landmark
// vertices (tests/data/human.anchors.json), without the landmark `dropped`.
std::string faust_landmarks(const path& mesh, const std::string& dropped) {
  const nlohmann::json anchors = nlohmann::json::parse(test::read_file(test::data_path("human.anchors.json")));
  const std::vector<std::array<double, 3>> vertices = obj_vertices(mesh);
  nlohmann::ordered_json landmarks;
  for (const auto& anchor : anchors["anchors"]) {
    if (anchor["name"] == dropped) continue;
    landmarks[anchor["name"].get<std::string>()] = vertices.at(anchor["vertex"].get<std::size_t>());
  }
  return landmarks.dump();
}

// targets/tr_scan_00{0,1}.obj and landmarks/tr_scan_00{0,1}_landmarks.json, CROTCH on neither.
void make_faust_like_folder(const path& dir) {
  std::filesystem::create_directories(dir / "targets");
  std::filesystem::create_directories(dir / "landmarks");
  const std::pair<const char*, const char*> scans[] = {{"tr_scan_000", "woman.obj"}, {"tr_scan_001", "man_bent.obj"}};
  for (const auto& [stem, sample] : scans) {
    std::filesystem::copy_file(test::sample_targets() / sample, dir / "targets" / (std::string(stem) + ".obj"));
    test::write_file(dir / "landmarks" / (std::string(stem) + "_landmarks.json"),
                     faust_landmarks(test::sample_targets() / sample, "CROTCH"));
  }
}

std::string faust_lookup(const path& dir) {
  return " --targets " + quoted(dir / "targets") + " --anchors-dir " + quoted(dir / "landmarks") +
         " --anchors-pattern '{stem}_landmarks.json'";
}

TEST(BatchOwnData, AnchorsPatternAndCommonAnchorsOnAFaustLikeFolder) {
  const path dir = test::fresh_temp_dir("own_data_faust");
  make_faust_like_folder(dir);
  const std::string out = " --out " + quoted(dir / "out.h5");

  // The pattern finds the landmark files; CROTCH, missing on both, fails them, naming it.
  EXPECT_EQ(test::batch(dir, test::template_options() + faust_lookup(dir) + out + " --dry-run"), 2);
  std::string report = test::read_file(dir / "stdout.txt");
  EXPECT_NE(report.find("check tr_scan_000: FAILS"), std::string::npos) << report;
  EXPECT_NE(report.find("CROTCH"), std::string::npos) << report;
  EXPECT_NE(report.find("tr_scan_001_landmarks.json"), std::string::npos) << report;

  // --common-anchors maps through the 40 shared names and says which one was left out.
  EXPECT_EQ(test::batch(dir, test::template_options() + faust_lookup(dir) + out + " --common-anchors --dry-run"), 0)
      << test::read_file(dir / "stderr.txt");
  report = test::read_file(dir / "stdout.txt");
  EXPECT_NE(report.find("anchors: 40 names shared by the template and every target"), std::string::npos) << report;
  EXPECT_NE(report.find("\"CROTCH\": missing on 2 target files"), std::string::npos) << report;
  EXPECT_NE(report.find("check tr_scan_001: ok"), std::string::npos) << report;
  // The effective options, as the run would record them, and where the anchors come from.
  EXPECT_NE(report.find("options: {\"intake\":{\"mode\":\"repair\""), std::string::npos) << report;
  EXPECT_NE(report.find("\"max_e_l2\":10.0"), std::string::npos) << report;
  EXPECT_NE(report.find("anchor files: in " + (dir / "landmarks").string() + " as {stem}_landmarks.json"), std::string::npos)
      << report;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.h5"));

  // The run: one scan (shard 0 of 2), mapped through the 40 shared anchors.
  ASSERT_EQ(test::batch(dir, test::template_options() + test::kQuick + " --max-maps 1" + faust_lookup(dir) + out +
                                 " --common-anchors --shard 0/2"),
            0)
      << test::read_file(dir / "stderr.txt");
  const ArchiveReader archive(dir / "out.h5");
  const TemplateRecord t = archive.read_template();
  EXPECT_EQ(t.anchor_names.size(), 40u);
  EXPECT_EQ(std::find(t.anchor_names.begin(), t.anchor_names.end(), "CROTCH"), t.anchor_names.end());
  ASSERT_EQ(archive.targets().size(), 1u);
  EXPECT_EQ(archive.targets()[0].name, "tr_scan_000");
  EXPECT_TRUE(archive.targets()[0].ok) << archive.targets()[0].error;
  EXPECT_NE(archive.targets()[0].anchors_file.find("landmarks/tr_scan_000_landmarks.json"), std::string::npos);
}

TEST(BatchOwnData, DryRunRefusesWhatTheRunRefuses) {
  const path dir = test::fresh_temp_dir("own_data_refusals");
  test::copy_sample_targets(dir / "targets", {"woman"});
  std::string anchors = test::read_file(test::sample_targets() / "woman.anchors.json");
  // An index past the mesh's 6890 vertices: only placing the anchors finds it.
  const std::size_t at = anchors.find("\"vertex\": 412");
  ASSERT_NE(at, std::string::npos);
  anchors.replace(at, 13, "\"vertex\": 99999");
  test::write_file(dir / "targets" / "woman.anchors.json", anchors);
  const std::string run = test::template_options() + test::kQuick + " --targets " + quoted(dir / "targets") +
                          " --out " + quoted(dir / "out.h5") + " --summary " + quoted(dir / "summary.json");

  EXPECT_EQ(test::batch(dir, run + " --dry-run"), 2);
  const std::string report = test::read_file(dir / "stdout.txt");
  EXPECT_NE(report.find("check woman: FAILS"), std::string::npos) << report;
  EXPECT_NE(report.find("99999"), std::string::npos) << report;

  EXPECT_EQ(test::batch(dir, run), 2);
  const nlohmann::json summary = nlohmann::json::parse(test::read_file(dir / "summary.json"));
  EXPECT_EQ(summary["targets"][0]["status"], "failed");
  EXPECT_NE(summary["targets"][0]["error"].get<std::string>().find("99999"), std::string::npos) << summary.dump();
}

TEST(BatchOwnData, LookupMistakesAreUsageErrors) {
  const path dir = test::fresh_temp_dir("own_data_usage");
  make_faust_like_folder(dir);
  const std::string out = " --out " + quoted(dir / "out.h5");
  // A pattern without {stem} would give every target the same file.
  EXPECT_EQ(test::batch(dir, test::template_options() + " --targets " + quoted(dir / "targets") +
                                 " --anchors-pattern landmarks.json" + out + " --dry-run"),
            1);
  EXPECT_NE(test::read_file(dir / "stderr.txt").find("{stem}"), std::string::npos);
  // An empty folder is an error, not a run over nothing.
  std::filesystem::create_directories(dir / "empty");
  EXPECT_EQ(test::batch(dir, test::template_options() + " --targets " + quoted(dir / "empty") + out), 1);
  EXPECT_NE(test::read_file(dir / "stderr.txt").find("no target meshes"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(dir / "out.h5"));
}

}  // namespace
}  // namespace xparam
