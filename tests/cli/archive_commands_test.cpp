// `xparam inspect`, `xparam export` and `xparam merge` run as a user runs them, on archives
// written from synthetic records (the archive and the commands are what is under test; each
// target's arrays differ, so a row mix-up shows).
#include "io/archive_hdf5.h"
#include "io/archive_reader.h"
#include "io/archive_writer.h"
#include "io/mesh_reader.h"

#include "support/test_data.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

namespace xparam {
namespace {

namespace fs = std::filesystem;

struct CommandRun {
  int exit_code = -1;
  std::string out;
  std::string err;
};

CommandRun run_xparam(const std::string& arguments, const fs::path& dir) {
  const fs::path err_file = dir / "stderr.txt";
  const std::string command = test::xparam_binary().string() + " " + arguments + " 2> " + err_file.string();
  CommandRun run;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return run;
  char buffer[4096];
  while (const std::size_t n = fread(buffer, 1, sizeof(buffer), pipe)) run.out.append(buffer, n);
  const int status = pclose(pipe);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream err(err_file);
  std::ostringstream text;
  text << err.rdbuf();
  run.err = text.str();
  return run;
}

TemplateRecord make_template() {
  TemplateRecord t;
  t.mesh_file = "template.obj";
  t.anchors_file = "template.anchors.json";
  // An octahedron.
  t.vertices.resize(6, 3);
  t.vertices << 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1;
  t.faces.resize(8, 3);
  t.faces << 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5;
  t.anchor_names = {"a", "b", "c"};
  t.anchor_vertices = {0, 2, 4};
  return t;
}

TargetRecord make_target(const TemplateRecord& t, const std::string& name, int k) {
  TargetRecord r;
  r.name = name;
  r.ok = true;
  r.mesh_file = name + ".ply";
  r.anchors_file = name + ".json";
  // Positions with digits that only an exact writer keeps.
  r.remesh_vertices = t.vertices * (1.0 + k / 3.0);
  r.remesh_vertices.col(2).array() += 0.1 * k;
  r.corr_face = Eigen::VectorXi::LinSpaced(6, k, k + 5);
  r.corr_bary = Eigen::MatrixX3d::Constant(6, 3, 1.0 / 3.0);
  r.face_patch = Eigen::VectorXi::LinSpaced(8, 0, 7).unaryExpr([k](int f) { return (f + k) % 4; });
  r.face_l2_stretch = Eigen::VectorXd::Constant(8, 1.0 + k);
  r.face_angle_distortion = Eigen::VectorXd::Constant(8, 0.5 * k);
  r.anchor_miss = Eigen::VectorXd::Constant(3, std::numeric_limits<double>::quiet_NaN());
  r.metrics.e_l2 = 1.0 + k / 7.0;
  r.metrics.e_ang = 0.25 * k;
  r.metrics.flipped_faces = k;
  r.metrics.strictly_folded_faces = k - 1;
  r.metrics.released_anchors = k % 2;
  r.metrics.dropped_faces = 4 * k;
  r.metrics.dropped_area = 0.01 * k;
  r.metrics.holes_filled = k % 3;
  r.metrics.filled_area = 0.02 * k;
  // corr_face k..k+5 against a file of k + 3 faces: vertices 3, 4, 5 land on fill faces.
  r.distance_to_scan.resize(6);
  r.distance_to_scan << 0, 0, 0, 0.0004 * k, 0.0007 * k, 0.001 * k;
  r.metrics.on_filled_vertices = 3;
  r.metrics.max_distance_to_scan = 0.001 * k;
  r.metrics.file_faces = k + 3;
  r.metrics.gt_error = k == 2 ? std::numeric_limits<double>::quiet_NaN() : 0.01 * k;
  r.seconds.fill(0.5 * k);
  return r;
}

TargetRecord make_failed(const std::string& name) {
  TargetRecord r;
  r.name = name;
  r.error = name + ".ply: genus 1, the template has genus 0";
  r.mesh_file = name + ".ply";
  return r;
}

// dora (k = 3) is suspect: 2 strictly folded faces, over a limit of 0.
std::vector<TargetRecord> make_targets(const TemplateRecord& t) {
  TargetRecord dora = make_target(t, "dora", 3);
  dora.suspect = true;
  dora.diagnosis =
      R"json({"reasons":["2 folded faces by the strict count (limit 0), most nearest \"b\" (2)"],)json"
      R"json("folds_by_anchor":[{"anchor":"b","folded_faces":2}],"disagreeing_corners":[],)json"
      R"json("swapped_anchors":[["a","c"]],"released_anchors":[],"helper_anchors":[],"warnings":[]})json";
  return {make_target(t, "bob", 1), make_failed("carl"), make_target(t, "alice", 2), dora};
}

ArchiveProvenance provenance() { return current_provenance(R"({"metric":"SDL"})"); }

std::string file_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

TEST(InspectCommand, ListsEveryTargetWithStatusMetricsAndError) {
  const fs::path dir = test::fresh_temp_dir("cli_inspect");
  const TemplateRecord t = make_template();
  write_archive(dir / "run.h5", t, provenance(), make_targets(t));

  const CommandRun run = run_xparam("inspect " + (dir / "run.h5").string(), dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("6 vertices, 8 faces, 3 anchors, 0 curves"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("4 targets: 2 ok, 1 suspect, 1 failed"), std::string::npos) << run.out;
  // Rows in name order; bob has E_L2 = 1 + 1/7 printed with 3 significant digits.
  const std::size_t alice = run.out.find("\nalice ");
  const std::size_t bob = run.out.find("\nbob ");
  const std::size_t carl = run.out.find("\ncarl ");
  ASSERT_NE(alice, std::string::npos);
  ASSERT_NE(bob, std::string::npos);
  ASSERT_NE(carl, std::string::npos);
  EXPECT_LT(alice, bob);
  EXPECT_LT(bob, carl);
  const std::string bob_line = run.out.substr(bob + 1, run.out.find('\n', bob + 1) - bob - 1);
  EXPECT_NE(bob_line.find(" ok "), std::string::npos) << bob_line;
  EXPECT_NE(bob_line.find(" 1.14 "), std::string::npos) << bob_line;
  EXPECT_EQ(bob_line.find("1.142"), std::string::npos) << bob_line;
  const std::string carl_line = run.out.substr(carl + 1, run.out.find('\n', carl + 1) - carl - 1);
  EXPECT_NE(carl_line.find("failed"), std::string::npos) << carl_line;
  EXPECT_NE(carl_line.find("carl.ply: genus 1, the template has genus 0"), std::string::npos) << carl_line;
  const std::size_t dora = run.out.find("\ndora ");
  ASSERT_NE(dora, std::string::npos);
  const std::string dora_line = run.out.substr(dora + 1, run.out.find('\n', dora + 1) - dora - 1);
  EXPECT_NE(dora_line.find(" suspect "), std::string::npos) << dora_line;
  EXPECT_NE(dora_line.find("2 folded faces by the strict count"), std::string::npos) << dora_line;
  fs::remove_all(dir);
}

TEST(InspectCommand, TargetShowsItsDiagnosisAndAnUnknownNameIsAUsageError) {
  const fs::path dir = test::fresh_temp_dir("cli_inspect_target");
  const TemplateRecord t = make_template();
  write_archive(dir / "run.h5", t, provenance(), make_targets(t));
  const std::string archive = (dir / "run.h5").string();

  CommandRun run = run_xparam("inspect " + archive + " --target dora", dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("dora: suspect"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("suspect: 2 folded faces by the strict count (limit 0)"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("folded faces by nearest anchor: \"b\" 2"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("landmarks \"a\" and \"c\" look swapped"), std::string::npos) << run.out;

  run = run_xparam("inspect --json " + archive + " --target dora", dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json j = nlohmann::json::parse(run.out);
  EXPECT_EQ(j["status"], "suspect");
  EXPECT_EQ(j["metrics"]["strictly_folded_faces"], 2);
  EXPECT_EQ(j["diagnosis"]["swapped_anchors"][0][1], "c");

  run = run_xparam("inspect " + archive + " --target carl", dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("error: carl.ply: genus 1"), std::string::npos) << run.out;

  run = run_xparam("inspect " + archive + " --target nobody", dir);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("no target \"nobody\""), std::string::npos) << run.err;
  fs::remove_all(dir);
}

TEST(InspectCommand, JsonCarriesTheExactValues) {
  const fs::path dir = test::fresh_temp_dir("cli_inspect_json");
  const TemplateRecord t = make_template();
  const std::vector<TargetRecord> targets = make_targets(t);
  write_archive(dir / "run.h5", t, provenance(), targets);

  const CommandRun run = run_xparam("inspect --json " + (dir / "run.h5").string(), dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json j = nlohmann::json::parse(run.out);
  EXPECT_EQ(j["options"]["metric"], "SDL");
  EXPECT_EQ(j["succeeded"], 3);
  EXPECT_EQ(j["suspect"], 1);
  EXPECT_EQ(j["failed"], 1);
  EXPECT_EQ(j["targets"][3]["status"], "suspect");
  ASSERT_EQ(j["targets"].size(), 4u);
  EXPECT_EQ(j["targets"][0]["name"], "alice");
  EXPECT_EQ(j["targets"][1]["metrics"]["E_L2"].get<double>(), 1.0 + 1 / 7.0);  // bob, bit-exact
  EXPECT_TRUE(j["targets"][0]["metrics"]["gt_error"].is_null());               // alice has no ground truth
  EXPECT_EQ(j["targets"][1]["metrics"]["released_anchors"], 1);                // bob, k = 1
  EXPECT_TRUE(j["targets"][2]["metrics"]["released_anchors"].is_null());      // carl failed
  EXPECT_EQ(j["targets"][2]["status"], "failed");
  EXPECT_EQ(j["targets"][2]["error"], "carl.ply: genus 1, the template has genus 0");
  EXPECT_EQ(j["targets"][3]["seconds"]["total"].get<double>(), 1.5);
  fs::remove_all(dir);
}

TEST(ExportCommand, ObjAndPlyReadBackAsTheRemesh) {
  const fs::path dir = test::fresh_temp_dir("cli_export");
  const TemplateRecord t = make_template();
  const std::vector<TargetRecord> targets = make_targets(t);
  write_archive(dir / "run.h5", t, provenance(), targets);
  const TargetRecord& dora = targets[3];

  for (const char* extension : {".obj", ".ply"}) {
    SCOPED_TRACE(extension);
    const fs::path out = dir / (std::string("dora") + extension);
    const CommandRun run = run_xparam("export " + (dir / "run.h5").string() + " --target dora --out " + out.string(), dir);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const TriangleSoup soup = read_triangle_soup(out);
    ASSERT_EQ(soup.vertices.size(), 6u);
    for (int v = 0; v < 6; ++v) EXPECT_EQ(soup.vertices[v], Eigen::Vector3d(dora.remesh_vertices.row(v))) << v;
    ASSERT_EQ(soup.triangles.size(), 8u);
    for (int f = 0; f < 8; ++f)
      EXPECT_EQ(soup.triangles[f], (std::array<int, 3>{t.faces(f, 0), t.faces(f, 1), t.faces(f, 2)})) << f;
  }
  fs::remove_all(dir);
}

TEST(ExportCommand, PlyFlagsTheVerticesOnFilledInSurface) {
  const fs::path dir = test::fresh_temp_dir("cli_export_filled");
  const TemplateRecord t = make_template();
  write_archive(dir / "run.h5", t, provenance(), make_targets(t));
  const fs::path out = dir / "dora.ply";
  const CommandRun run = run_xparam("export " + (dir / "run.h5").string() + " --target dora --out " + out.string(), dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::ifstream in(out, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t body = bytes.find("end_header\n");
  ASSERT_NE(body, std::string::npos);
  const std::string header = bytes.substr(0, body);
  EXPECT_NE(header.find("element vertex 6\nproperty double x\nproperty double y\nproperty double z\n"
                        "property int on_filled\nproperty double distance_to_scan\n"),
            std::string::npos)
      << header;
  EXPECT_NE(header.find("property uchar red"), std::string::npos) << header;
  // Binary little endian: x, y, z as doubles, the flag, the distance; vertices 3, 4, 5 are on fill faces.
  const TargetRecord dora = make_targets(t)[3];
  for (int v = 0; v < 6; ++v) {
    std::int32_t flag = -1;
    double distance = -1.0;
    std::memcpy(&flag, bytes.data() + body + 11 + v * 36 + 24, sizeof flag);
    std::memcpy(&distance, bytes.data() + body + 11 + v * 36 + 28, sizeof distance);
    EXPECT_EQ(flag, v >= 3 ? 1 : 0) << "vertex " << v;
    EXPECT_EQ(distance, dora.distance_to_scan[v]) << "vertex " << v;
  }
  EXPECT_EQ(run.err.find("note:"), std::string::npos) << run.err;
  fs::remove_all(dir);
}

// The archive as xparam wrote it before schema 5: no /targets/distance_to_scan.
void make_schema_4(const fs::path& archive) {
  const h5::Handle file(H5Fopen(archive.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), H5Fclose, archive.string());
  h5::check(H5Ldelete(file.get(), "targets/distance_to_scan", H5P_DEFAULT), archive.string(), "delete");
  h5::check(H5Adelete(file.get(), "schema_version"), archive.string(), "delete");
  h5::write_attribute(file.get(), "schema_version", std::int64_t{4});
}

TEST(ExportCommand, AnArchiveOfSchema4ReadsWithoutDistancesAndSaysSo) {
  const fs::path dir = test::fresh_temp_dir("cli_export_schema_4");
  const TemplateRecord t = make_template();
  write_archive(dir / "run.h5", t, provenance(), make_targets(t));
  make_schema_4(dir / "run.h5");

  // Images off filled-in surface are on the scan (0); how far the others are was not recorded.
  const ArchiveReader reader(dir / "run.h5");
  EXPECT_FALSE(reader.records_distance_to_scan());
  const TargetRecord dora = reader.read_target(*reader.find("dora"));
  for (int v = 0; v < 6; ++v) EXPECT_EQ(std::isnan(dora.distance_to_scan[v]), v >= 3) << "vertex " << v;
  EXPECT_EQ(dora.distance_to_scan.head(3), Eigen::Vector3d::Zero());

  const std::string archive = (dir / "run.h5").string();
  CommandRun run =
      run_xparam("export " + archive + " --target dora --out " + (dir / "dora.ply").string(), dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("distance_to_scan is NaN where on_filled is 1"), std::string::npos) << run.err;
  run = run_xparam("export " + archive + " --target dora --out " + (dir / "dora.obj").string(), dir);
  EXPECT_EQ(run.err.find("note:"), std::string::npos) << run.err;

  run = run_xparam("inspect " + archive + " --target dora", dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(
      run.out.find("intake: 12 faces of loose parts dropped, 0 holes filled; template vertices on filled-in "
                   "surface: 3, at most 0.003 from the scan (each vertex's distance is not recorded in a "
                   "schema 4 archive)"),
      std::string::npos)
      << run.out;
  fs::remove_all(dir);
}

TEST(InspectCommand, TargetShowsItsIntakeRepairs) {
  const fs::path dir = test::fresh_temp_dir("cli_inspect_intake");
  const TemplateRecord t = make_template();
  write_archive(dir / "run.h5", t, provenance(), make_targets(t));
  const CommandRun run = run_xparam("inspect " + (dir / "run.h5").string() + " --target bob", dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  // bob (k = 1): 4 faces dropped, 1 hole filled, 3 vertices on it, the farthest 0.001 from the scan.
  EXPECT_NE(
      run.out.find("intake: 4 faces of loose parts dropped, 1 hole filled; template vertices on filled-in "
                   "surface: 3, at most 0.001 from the scan (each vertex's: export --out FILE.ply, "
                   "distance_to_scan)"),
      std::string::npos)
      << run.out;
  fs::remove_all(dir);
}

TEST(ExportCommand, MeasurementTableHasTheTemplateAndEveryTarget) {
  const fs::path dir = test::fresh_temp_dir("cli_export_measurements");
  TemplateRecord t = make_template();
  const std::string archive = (dir / "run.h5").string();
  write_archive(archive, t, provenance(), make_targets(t));
  // No measurements in the archive: the error says how to get them.
  CommandRun run = run_xparam("export " + archive + " --measurements --out " + (dir / "m.csv").string(), dir);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("run the batch with --measurements FILE"), std::string::npos) << run.err;

  t.measurements_file = "body.json";
  t.measurement_names = {"waist, natural", "height"};
  t.measurement_units = {"m", "m"};
  t.measurement_values = Eigen::Vector2d(0.75, 1.75);
  std::vector<TargetRecord> targets = make_targets(t);
  for (TargetRecord& target : targets)
    if (target.ok) target.measurements = Eigen::Vector2d(0.25 * static_cast<double>(target.name.size()), std::nan(""));
  fs::remove(archive);
  write_archive(archive, t, provenance(), targets);
  run = run_xparam("export " + archive + " --measurements --out " + (dir / "m.csv").string(), dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  // Rows in archive order; the name with a comma quoted; NaN and failed targets as empty cells.
  EXPECT_EQ(file_bytes(dir / "m.csv"),
            "name,status,\"waist, natural (m)\",height (m)\n"
            "template.obj,template,0.75,1.75\n"
            "alice,ok,1.25,\n"
            "bob,ok,0.75,\n"
            "carl,failed,,\n"
            "dora,suspect,1,\n");
  run = run_xparam("inspect " + archive + " --target bob", dir);
  EXPECT_NE(run.out.find("measurements: waist, natural 0.75 m, height - m"), std::string::npos) << run.out;
  run = run_xparam("export " + archive + " --measurements --target bob --out " + (dir / "m.csv").string(), dir);
  EXPECT_EQ(run.exit_code, 1);
  fs::remove_all(dir);
}

TEST(ExportCommand, FailedOrUnknownTargetsAndFormatsAreErrors) {
  const fs::path dir = test::fresh_temp_dir("cli_export_errors");
  const TemplateRecord t = make_template();
  write_archive(dir / "run.h5", t, provenance(), make_targets(t));
  const std::string archive = (dir / "run.h5").string();

  CommandRun run = run_xparam("export " + archive + " --target carl --out " + (dir / "carl.obj").string(), dir);
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.err.find("genus 1"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(dir / "carl.obj"));
  // What the user typed wrongly is a usage error (exit 1), naming what the archive holds.
  run = run_xparam("export " + archive + " --target nobody --out " + (dir / "x.obj").string(), dir);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("no target \"nobody\"; it holds alice, bob, carl, dora"), std::string::npos) << run.err;
  run = run_xparam("export " + archive + " --target bob --out " + (dir / "x.stl").string(), dir);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("x.stl"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(dir / "x.stl"));
  fs::remove_all(dir);
}

TEST(MergeCommand, ShardsMergeIntoTheSingleRunArchive) {
  const fs::path dir = test::fresh_temp_dir("cli_merge");
  const TemplateRecord t = make_template();
  const std::vector<TargetRecord> targets = make_targets(t);
  write_archive(dir / "single.h5", t, provenance(), targets);
  write_archive(dir / "s1.h5", t, provenance(), {targets[0], targets[3]});
  write_archive(dir / "s2.h5", t, provenance(), {targets[1], targets[2]});

  CommandRun run = run_xparam("merge " + (dir / "s1.h5").string() + " " + (dir / "s2.h5").string() + " --out " +
                           (dir / "merged.h5").string(),
                       dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("merged 4 targets from 2 shards"), std::string::npos) << run.out;
  EXPECT_EQ(file_bytes(dir / "merged.h5"), file_bytes(dir / "single.h5"));
  EXPECT_TRUE(fs::exists(dir / "merged.xdmf"));

  // An existing archive is replaced only with --force.
  run = run_xparam("merge " + (dir / "s2.h5").string() + " --out " + (dir / "merged.h5").string(), dir);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("already exists; nothing was changed. Add --force"), std::string::npos) << run.err;
  EXPECT_EQ(file_bytes(dir / "merged.h5"), file_bytes(dir / "single.h5"));
  run = run_xparam("merge " + (dir / "s2.h5").string() + " --force --out " + (dir / "merged.h5").string(), dir);
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(ArchiveReader(dir / "merged.h5").targets().size(), 2u);

  run = run_xparam("merge " + (dir / "s1.h5").string() + " " + (dir / "single.h5").string() + " --out " +
                       (dir / "overlap.h5").string(),
                   dir);
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.err.find("is in both"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(dir / "overlap.h5"));
  fs::remove_all(dir);
}

// Flip one byte in the middle of the stored chunk of row `row` of `dataset` in `archive`.
void flip_byte_in_chunk(const fs::path& archive, const std::string& dataset, hsize_t row) {
  haddr_t address = 0;
  hsize_t size = 0;
  {
    const h5::Handle file = h5::open_file(archive);
    const h5::Handle data = h5::open_dataset(file.get(), dataset);
    std::vector<hsize_t> offset(h5::shape(data.get()).size(), 0);
    offset[0] = row;
    unsigned filters = 0;
    h5::check(H5Dget_chunk_info_by_coord(data.get(), offset.data(), &filters, &address, &size), dataset,
              "no chunk");
  }
  std::fstream bytes(archive, std::ios::in | std::ios::out | std::ios::binary);
  const auto at = static_cast<std::streamoff>(address + size / 2);
  bytes.seekg(at);
  const char old = static_cast<char>(bytes.get());
  bytes.seekp(at);
  bytes.put(static_cast<char>(old ^ 0x10));
}

// Every numeric dataset carries a Fletcher-32 checksum: a flipped byte is found by inspect
// --verify, by export and by merge, each naming the dataset; nothing is written from it.
TEST(ArchiveIntegrity, FlippedByteIsDetectedAndTheDatasetNamed) {
  const fs::path dir = test::fresh_temp_dir("cli_integrity");
  const TemplateRecord t = make_template();
  write_archive(dir / "run.h5", t, provenance(), make_targets(t));
  const std::string archive = (dir / "run.h5").string();
  CommandRun run = run_xparam("inspect --verify " + archive, dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("every checksum matches"), std::string::npos) << run.err;

  flip_byte_in_chunk(dir / "run.h5", "targets/remesh_vertices", 1);  // bob's row
  run = run_xparam("inspect --verify " + archive, dir);
  EXPECT_EQ(run.exit_code, 3);
  EXPECT_NE(run.err.find(archive + ":/targets/remesh_vertices: cannot read rows: the dataset is damaged"),
            std::string::npos)
      << run.err;
  run = run_xparam("export " + archive + " --target bob --out " + (dir / "bob.obj").string(), dir);
  EXPECT_EQ(run.exit_code, 3);
  EXPECT_NE(run.err.find("/targets/remesh_vertices"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(dir / "bob.obj"));
  run = run_xparam("export " + archive + " --target alice --out " + (dir / "alice.obj").string(), dir);
  EXPECT_EQ(run.exit_code, 0) << run.err;  // the other rows are intact
  run = run_xparam("merge " + archive + " --out " + (dir / "merged.h5").string(), dir);
  EXPECT_EQ(run.exit_code, 3);
  EXPECT_NE(run.err.find("/targets/remesh_vertices"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(dir / "merged.h5"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace xparam
