// A target with a hole punched into it, mapped by `xparam pair` and by `xparam batch`: each
// template vertex's distance to the real scan is the same in correspondence.csv, in the archive
// and in the PLY `xparam export` writes (0 exactly off the filled-in surface, positive on it), and
// the batch's summary carries the intake's record and totals.
#include "intake/intake_damage.h"
#include "io/archive_reader.h"
#include "io/mesh_writer.h"

#include "support/correspondence_csv.h"
#include "support/test_data.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstring>
#include <fstream>
#include <iterator>

namespace xparam {
namespace {

namespace fs = std::filesystem;

// Spot (low resolution) with its right flank punched out (no anchor within 0.3), as a file beside
// Spot's own anchors under the batch's naming convention.
void write_damaged_spot(const fs::path& dir) {
  const TriangleSoup clean = test::clean_spot();
  const Eigen::Vector3d flank(0.35, -0.1, 0.4);
  int center = 0;
  for (std::size_t i = 1; i < clean.vertices.size(); ++i)
    if ((clean.vertices[i] - flank).norm() < (clean.vertices[center] - flank).norm())
      center = static_cast<int>(i);
  std::vector<int> removed;
  const TriangleSoup damaged = test::punch_hole(clean, center, 0.18, removed);
  fs::create_directories(dir);
  write_obj(dir / "damaged.obj", damaged.vertices, damaged.triangles);
  fs::copy_file(test::data_path("spot_low_resolution.anchors.json"), dir / "damaged.anchors.json");
}

// The per-vertex `distance_to_scan` of a binary PLY written by `xparam export`: each vertex is x, y,
// z (doubles), on_filled (int), distance_to_scan (double).
std::vector<double> exported_distances(const fs::path& path, std::size_t vertices) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t body = bytes.find("end_header\n");
  EXPECT_NE(bytes.substr(0, body).find("property int on_filled\nproperty double distance_to_scan\n"),
            std::string::npos);
  constexpr std::size_t kVertexBytes = 3 * 8 + 4 + 8;
  std::vector<double> values(vertices);
  for (std::size_t v = 0; v < vertices; ++v)
    std::memcpy(&values[v], bytes.data() + body + 11 + v * kVertexBytes + 3 * 8 + 4, sizeof(double));
  return values;
}

// The damaged Spot mapped once by `xparam pair` (into pair/) and once by `xparam batch` (into
// run.h5, with its summary and closing lines), shared by the tests below.
struct DamagedRun {
  fs::path dir;
  std::string batch_log;  // the batch's stderr
};

const DamagedRun& damaged_run() {
  static const DamagedRun run = [] {
    DamagedRun out{test::fresh_temp_dir("filled_surface_outputs"), {}};
    const fs::path& dir = out.dir;
    write_damaged_spot(dir / "targets");
    const std::string spot = test::quoted(test::data_path("spot_low_resolution.obj"));
    const std::string spot_anchors = test::quoted(test::data_path("spot_low_resolution.anchors.json"));
    // Spot's low-resolution faces are large: the hole's border (about 1.6) is longer than the
    // default limit (a quarter of the 2.7 diagonal).
    std::string errors;
    EXPECT_EQ(test::run_xparam("pair --quiet --source " + spot + " --source-anchors " + spot_anchors +
                                   " --target " + test::quoted(dir / "targets/damaged.obj") +
                                   " --target-anchors " + test::quoted(dir / "targets/damaged.anchors.json") +
                                   " --max-hole 3 --out " + test::quoted(dir / "pair"),
                               dir, errors),
              0)
        << errors;
    EXPECT_EQ(test::run_xparam("batch --template " + spot + " --template-anchors " + spot_anchors +
                                   " --targets " + test::quoted(dir / "targets") + " --max-hole 3 --out " +
                                   test::quoted(dir / "run.h5") + " --summary " +
                                   test::quoted(dir / "summary.json"),
                               dir, out.batch_log),
              0)
        << out.batch_log;
    return out;
  }();
  return run;
}

nlohmann::json read_json(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

TEST(FilledSurfaceOutputs, DistanceToTheScanIsTheSameInTheCsvTheArchiveAndTheExport) {
  const fs::path& dir = damaged_run().dir;
  const test::CorrespondenceCsv csv = test::read_correspondence_csv(dir / "pair/correspondence.csv");
  const ArchiveReader archive(dir / "run.h5");
  ASSERT_TRUE(archive.records_distance_to_scan());
  const TargetRecord target = archive.read_target(0);
  ASSERT_TRUE(target.ok) << target.error;
  ASSERT_EQ(static_cast<std::size_t>(target.distance_to_scan.size()), csv.rows.size());
  int on_filled = 0;
  for (std::size_t v = 0; v < csv.rows.size(); ++v) {
    const auto row = static_cast<Eigen::Index>(v);
    const double distance = target.distance_to_scan[row];
    EXPECT_EQ(distance, csv.rows[v][6]) << "vertex " << v;  // the csv is written to 17 digits
    const bool filled = target.corr_face[row] >= target.metrics.file_faces;
    EXPECT_EQ(filled, csv.rows[v][5] == 1.0) << "vertex " << v;
    if (filled)
      EXPECT_GT(distance, 0.0) << "vertex " << v;
    else
      EXPECT_EQ(distance, 0.0) << "vertex " << v;
    on_filled += filled;
  }
  EXPECT_GE(on_filled, 3);
  EXPECT_EQ(on_filled, target.metrics.on_filled_vertices);
  EXPECT_EQ(target.distance_to_scan.maxCoeff(), target.metrics.max_distance_to_scan);

  std::string errors;
  ASSERT_EQ(test::run_xparam("export " + test::quoted(dir / "run.h5") + " --target damaged --out " +
                                 test::quoted(dir / "damaged.ply"),
                             dir, errors),
            0)
      << errors;
  const std::vector<double> exported = exported_distances(dir / "damaged.ply", csv.rows.size());
  for (std::size_t v = 0; v < exported.size(); ++v)
    EXPECT_EQ(exported[v], target.distance_to_scan[static_cast<Eigen::Index>(v)]) << "vertex " << v;
}

TEST(FilledSurfaceOutputs, BatchSummaryCarriesTheIntakesFiguresPerTargetAndInAll) {
  const DamagedRun& run = damaged_run();
  const nlohmann::json summary = read_json(run.dir / "summary.json");
  const nlohmann::json metrics = read_json(run.dir / "pair/metrics.json");
  ASSERT_EQ(summary["targets"].size(), 1u);
  const nlohmann::json& target = summary["targets"][0];
  // The target's record is metrics.json's (the fill patches' geometry aside).
  ASSERT_TRUE(target.contains("intake")) << target.dump(1);
  for (const auto& [key, value] : target["intake"].items()) EXPECT_EQ(value, metrics["intake"][key]) << key;
  EXPECT_EQ(target["intake"]["steps"], metrics["intake"]["steps"]);
  EXPECT_EQ(target["intake"]["holes_filled"].size(), 1u);

  const nlohmann::json& totals = summary["intake"];
  EXPECT_EQ(totals["repaired"], 1);
  EXPECT_EQ(totals["with_parts_dropped"], 0);
  EXPECT_EQ(totals["with_holes_filled"], 1);
  EXPECT_EQ(totals["dropped_faces"], 0);
  EXPECT_EQ(totals["holes_filled"], 1);
  EXPECT_EQ(totals["filled_area"], target["metrics"]["filled_area"]);
  const int on_filled = target["metrics"]["on_filled_vertices"];
  EXPECT_GE(on_filled, 3);
  EXPECT_EQ(totals["on_filled_vertices"], on_filled);

  EXPECT_NE(run.batch_log.find(
                "xparam batch: the intake repaired 1 of 1 target: loose parts dropped from 0 (0 faces), "
                "holes filled in 1 (1 hole, area "),
            std::string::npos)
      << run.batch_log;
  EXPECT_NE(
      run.batch_log.find(std::to_string(on_filled) + " template vertices in all land on filled-in surface"),
      std::string::npos)
      << run.batch_log;
}

}  // namespace
}  // namespace xparam
