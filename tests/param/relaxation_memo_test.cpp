#include "param/relaxation_memo.h"

#include "param/patch_parameterization.h"
#include "patch_fixtures.h"

#include <gtest/gtest.h>

#include <cmath>

namespace xparam {
namespace {

// A grid over the unit square with a bump the mean-value parameterization squeezes.
DiskPatch bump_patch() {
  DiskPatch patch = test::planar_grid_patch(16, Eigen::Matrix2d::Identity(), 7);
  for (Eigen::Vector3d& x : patch.positions)
    x.z() = 0.6 * std::exp(-(x.head<2>() - Eigen::Vector2d(0.5, 0.5)).squaredNorm() / (2.0 * 0.08 * 0.08));
  return patch;
}

constexpr MapRelaxationSettings kSettings{300, 1e-4, 4.4};

TEST(RelaxationMemo, AnswersTheSameParameterizationWithTheSameResultAndRelaxesAChangedOne) {
  DiskPatch patch = bump_patch();
  const std::vector<Eigen::Vector2d> uv = parameterize_patch(patch).uv;
  const MapRelaxationResult direct = relax_patch_parameterization(patch, uv, kSettings);
  ASSERT_GT(direct.iterations, 0);

  RelaxationMemo memo;
  EXPECT_EQ(memo.relax_patch_parameterization(patch, uv, kSettings).uv, direct.uv);
  EXPECT_EQ(memo.reused(), 0);
  const MapRelaxationResult again = memo.relax_patch_parameterization(patch, uv, kSettings);
  EXPECT_EQ(memo.reused(), 1);
  EXPECT_EQ(again.uv, direct.uv);
  EXPECT_EQ(again.energy_after, direct.energy_after);
  EXPECT_EQ(again.iterations, direct.iterations);

  // Other settings, or one vertex raised a little: relaxed again, to what a direct call gives.
  MapRelaxationSettings shorter = kSettings;
  shorter.max_iterations = 2;
  EXPECT_EQ(memo.relax_patch_parameterization(patch, uv, shorter).uv,
            relax_patch_parameterization(patch, uv, shorter).uv);
  EXPECT_EQ(memo.reused(), 1);
  const int inner = patch.triangles[patch.triangles.size() / 2][0];
  patch.positions[inner].z() += 1e-3;
  const MapRelaxationResult changed = memo.relax_patch_parameterization(patch, uv, kSettings);
  EXPECT_EQ(memo.reused(), 1);
  EXPECT_EQ(changed.uv, relax_patch_parameterization(patch, uv, kSettings).uv);
  EXPECT_NE(changed.uv, direct.uv);
}

TEST(RelaxationMemo, AnswersTheSameMapWithTheSameResultAndRelaxesFromAnotherStart) {
  // The bump onto a flat square, placed by the bump's mean-value parameterization.
  const DiskPatch source = bump_patch();
  const std::vector<Eigen::Vector2d> start = parameterize_patch(source).uv;
  const DiskPatch target = test::planar_grid_patch(20, Eigen::Matrix2d::Identity(), 3);
  std::vector<Eigen::Vector2d> target_uv;
  for (const Eigen::Vector3d& x : target.positions) target_uv.emplace_back(x.head<2>());
  const PointLocator locator(target_uv, target.triangles);
  const TargetPatchView view{&target, &target_uv, &locator};
  const MapRelaxationResult direct = relax_patch_map(source, start, view, 1.0, kSettings);
  ASSERT_GT(direct.iterations, 0);

  RelaxationMemo memo;
  EXPECT_EQ(memo.relax_patch_map(source, start, view, 1.0, kSettings).uv, direct.uv);
  EXPECT_EQ(memo.relax_patch_map(source, start, view, 1.0, kSettings).uv, direct.uv);
  EXPECT_EQ(memo.reused(), 1);
  // The same patch and start as a parameterization is another relaxation.
  memo.relax_patch_parameterization(source, start, kSettings);
  EXPECT_EQ(memo.reused(), 1);
  // Another scale, or the start moved by the relaxation's own result: relaxed again.
  EXPECT_EQ(memo.relax_patch_map(source, start, view, 1.1, kSettings).uv,
            relax_patch_map(source, start, view, 1.1, kSettings).uv);
  EXPECT_EQ(memo.relax_patch_map(source, direct.uv, view, 1.0, kSettings).uv,
            relax_patch_map(source, direct.uv, view, 1.0, kSettings).uv);
  EXPECT_EQ(memo.reused(), 1);
}

}  // namespace
}  // namespace xparam
