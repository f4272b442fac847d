// One target job: broken inputs become failed records naming the file and the reason; a
// real pair fills every array, in the target file's corner order.
#include "batch/target_job.h"

#include "batch/target_discovery.h"
#include "batch_library_support.h"
#include "io/mesh_loader.h"
#include "map/curve_tracing.h"
#include "measure/surface_geodesic.h"
#include "support/plain_obj.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <sstream>
#include <utility>

namespace xparam {
namespace {

using test::fs::path;

using test::man;
using test::spec;

void expect_contains(const std::string& text, const std::string& part) {
  EXPECT_NE(text.find(part), std::string::npos) << "\"" << part << "\" not in: " << text;
}

TEST(TargetJob, BrokenTargetsFailWithTheirReasonAndFile) {
  const path dir = test::fresh_temp_dir("job_broken");
  test::add_broken_targets(dir);
  const std::vector<TargetSpec> targets = discover_targets(dir);
  ASSERT_EQ(targets.size(), 4u);

  struct Expectation {
    const char* name;
    const char* file;    // the file the error must name
    const char* reason;  // and a word of why
  };
  for (const Expectation& e : {Expectation{"truncated", "truncated.obj", "truncated.obj"},
                               Expectation{"no_anchors", "no_anchors.obj", "no anchors"},
                               Expectation{"torus", "torus.ply", "--max-handle"},
                               Expectation{"unknown_name", "unknown_name.anchors.json", "NOT_A_LANDMARK"}}) {
    SCOPED_TRACE(e.name);
    const TargetSpec& target = spec(targets, e.name);
    const TargetRecord record = run_target(man(), target);
    EXPECT_FALSE(record.ok);
    EXPECT_EQ(record.name, e.name);
    expect_contains(record.error, e.file);
    expect_contains(record.error, e.reason);
    EXPECT_EQ(record.mesh_file, target.mesh.string());
    EXPECT_EQ(record.remesh_vertices.rows(), 0);
    EXPECT_TRUE(std::isfinite(record.seconds.back()));
    // The dry-run check finds the same problem without mapping.
    EXPECT_EQ(check_target(man(), target), record.error);
  }
  EXPECT_EQ(spec(targets, "torus").problem, "");
  expect_contains(run_target(man(), spec(targets, "torus")).error, "genus 1");
  expect_contains(run_target(man(), spec(targets, "unknown_name")).error, "CROTCH");
}

TEST(TargetJob, GroundTruthThatDoesNotFitIsAFailure) {
  const path dir = test::fresh_temp_dir("job_bad_gt");
  test::copy_sample_targets(dir, {"woman"});
  test::write_file(dir / "woman.gt.txt", "0\n1\n2\n");
  const TargetSpec target = discover_targets(dir).at(0);
  expect_contains(check_target(man(), target), "3 ground-truth entries for 6890 template vertices");
  test::write_file(dir / "woman.gt.txt", "0\n1\nseven\n");
  expect_contains(check_target(man(), target), "woman.gt.txt:3:");
  EXPECT_EQ(check_target(man(), discover_targets(test::sample_targets()).at(0)), "");
}

// A target file whose faces point inward is flipped at load: the archive's barycentrics must
// still refer to the corners in the order the FILE lists them.
TEST(TargetJob, CorrespondenceIsInTheTargetFilesCornerOrder) {
  const path dir = test::fresh_temp_dir("job_inward_target");
  test::PlainObj obj = test::read_plain_obj(test::sample_targets() / "man_bent.obj");
  std::ostringstream reversed;
  reversed.precision(17);
  for (const Eigen::Vector3d& v : obj.vertices)
    reversed << "v " << v.x() << " " << v.y() << " " << v.z() << "\n";
  for (std::array<int, 3>& f : obj.faces) {
    std::swap(f[1], f[2]);
    reversed << "f " << f[0] + 1 << " " << f[1] + 1 << " " << f[2] + 1 << "\n";
  }
  test::write_file(dir / "inward.obj", reversed.str());
  std::filesystem::copy_file(test::sample_targets() / "man_bent.anchors.json", dir / "inward.anchors.json");
  const TargetRecord record = run_target(man(), discover_targets(dir).at(0));
  ASSERT_TRUE(record.ok) << record.error;
  for (Eigen::Index v = 0; v < record.corr_face.size(); ++v) {
    const auto& f = obj.faces[static_cast<std::size_t>(record.corr_face[v])];
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) p += record.corr_bary(v, k) * obj.vertices[static_cast<std::size_t>(f[k])];
    ASSERT_LT((p - record.remesh_vertices.row(v).transpose()).norm(), 1e-9) << "template vertex " << v;
  }
}

// The target's curve lengths are its transferred curves' (the archive's polylines), and its
// geodesic runs on its own surface between the remesh's images of the template's points.
TEST(TargetJob, CurveLengthsAndGeodesicsAreTakenOnTheTarget) {
  const path dir = test::fresh_temp_dir("job_curve_lengths");
  const PreparedTemplate prepared = prepare_template(test::man_template_with_tapes(dir));
  std::filesystem::copy_file(test::sample_targets() / "woman.obj", dir / "woman.obj");
  std::filesystem::copy_file(test::sample_targets() / "woman.anchors.json", dir / "woman.anchors.json");
  const TargetRecord record = run_target(prepared, discover_targets(dir).at(0));
  ASSERT_TRUE(record.ok) << record.error;
  ASSERT_EQ(record.measurements.size(), 4);
  ASSERT_EQ(record.curves.size(), 2U);
  for (std::size_t c = 0; c < 2; ++c) {
    std::vector<Eigen::Vector3d> polyline;
    for (Eigen::Index p = 0; p < record.curves[c].xyz.rows(); ++p)
      polyline.push_back(record.curves[c].xyz.row(p).transpose());
    // Measurement 0 is the second curve's length, measurement 1 the first's.
    EXPECT_EQ(record.measurements[static_cast<Eigen::Index>(1 - c)],
              polyline_length(polyline, prepared.curves[c].closed))
        << prepared.curves[c].name;
    // Not the template's value: another body.
    EXPECT_GT(std::abs(record.measurements[static_cast<Eigen::Index>(1 - c)] -
                       prepared.record.measurement_values[static_cast<Eigen::Index>(1 - c)]),
              0.01);
  }
  const Mesh woman = load_mesh(dir / "woman.obj").mesh;
  const SurfaceGeodesic back = surface_geodesic(
      woman, {record.remesh_vertices.row(829).transpose(), record.remesh_vertices.row(3022).transpose()},
      false);
  EXPECT_EQ(record.measurements[2], back.length);
  EXPECT_GT(record.measurements[2], record.measurements[3]);
}

}  // namespace
}  // namespace xparam
