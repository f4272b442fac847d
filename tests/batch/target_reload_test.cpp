// A target loaded again after the batch: the intake settings come back from the recorded options
// as the batch wrote them, and a target whose file needs the intake is prepared again by it (a
// hole filled), so warp sees the closed surface the batch mapped.
#include "batch/batch_driver.h"
#include "batch/target_reload.h"

#include "core/errors.h"
#include "io/sha256.h"
#include "support/test_data.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

namespace xparam {
namespace {

namespace fs = std::filesystem;

TEST(TargetReload, IntakeSettingsComeBackFromTheRecordedOptions) {
  IntakeSettings written;
  written.mode = IntakeMode::Repair;
  written.max_dropped_area = 0.03;
  written.max_hole = 0.2;
  written.max_hole_relative = 0.1;
  written.max_handle = 0.04;
  written.max_handle_relative = 0.02;
  const IntakeSettings read = recorded_intake(batch_options_json({}, {}, written));
  EXPECT_EQ(read.mode, IntakeMode::Repair);
  EXPECT_EQ(read.max_dropped_area, 0.03);
  EXPECT_EQ(read.max_hole, 0.2);
  EXPECT_EQ(read.max_hole_relative, 0.1);
  EXPECT_EQ(read.max_handle, 0.04);
  EXPECT_EQ(read.max_handle_relative, 0.02);
  written.mode = IntakeMode::Strict;
  EXPECT_EQ(recorded_intake(batch_options_json({}, {}, written)).mode, IntakeMode::Strict);
  // Archives from before the intake took every target as it was.
  EXPECT_EQ(recorded_intake("{}").mode, IntakeMode::Strict);
  EXPECT_THROW(recorded_intake(R"({"intake": {"mode": "repair"}})"), ArchiveError);
  // Archives from before handles were cut refused every handle.
  const IntakeSettings before_handles = recorded_intake(
      R"({"intake": {"mode": "repair", "max_dropped_area": 0.1, "max_hole": 0, "max_hole_relative": 0.25}})");
  EXPECT_EQ(before_handles.mode, IntakeMode::Repair);
  EXPECT_EQ(before_handles.max_handle, 0.0);
  EXPECT_EQ(before_handles.max_handle_relative, 0.0);
}

TEST(TargetReload, AFileThatNeededTheIntakeIsPreparedAgain) {
  // An octahedron with one face missing: the intake fills the hole when the settings allow it.
  const fs::path dir = test::fresh_temp_dir("target_reload_intake");
  std::ofstream(dir / "open.obj") << "v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n"
                                     "f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\n";
  std::ofstream(dir / "open.json") << R"({"anchors": [{"name": "a", "vertex": 0}, {"name": "b", "vertex": 1},
                                         {"name": "c", "vertex": 2}, {"name": "d", "vertex": 4}]})";
  ArchiveTargetSummary target;
  target.name = "open";
  target.mesh_file = (dir / "open.obj").string();
  target.anchors_file = (dir / "open.json").string();
  target.mesh_sha256 = sha256_file_hex(target.mesh_file);
  target.anchors_sha256 = sha256_file_hex(target.anchors_file);
  // The hole is a third of the octahedron: filled only under the batch's settings that allowed it.
  IntakeSettings generous;
  generous.max_hole = 10.0;
  const ReloadedTarget repaired = reload_target(target, generous, {});
  ASSERT_TRUE(repaired.loaded) << repaired.explanation;
  EXPECT_EQ(repaired.problem, ReloadProblem::none);
  EXPECT_TRUE(repaired.loaded->intake.applied);
  EXPECT_EQ(repaired.loaded->intake.holes.size(), 1U);
  EXPECT_GE(repaired.loaded->mesh.n_faces(), 8U);  // the file's 7 and the hole's patch
  IntakeSettings strict;
  strict.mode = IntakeMode::Strict;
  for (const IntakeSettings& other : {strict, IntakeSettings{}}) {
    const ReloadedTarget refused = reload_target(target, other, {});
    EXPECT_EQ(refused.problem, ReloadProblem::refused);
    EXPECT_NE(refused.explanation.find("open.obj"), std::string::npos) << refused.explanation;
  }
}

}  // namespace
}  // namespace xparam
