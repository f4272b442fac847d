#include "param/map_relaxation.h"

#include "param/convex_polygon.h"
#include "param/patch_parameterization.h"
#include "patch_fixtures.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>

namespace xparam {
namespace {

// A target patch over the unit square whose 3-D surface is the unit square itself but whose
// parameterization is warped: the vertex at 3-D point x sits at warp^-1(x) in the domain, so
// the target's parameterization maps u to warp(u).
struct WarpedTarget {
  DiskPatch patch;
  std::vector<Eigen::Vector2d> uv;
  std::optional<PointLocator> locator;

  TargetPatchView view() const { return {&patch, &uv, &*locator}; }

  // The target surface point at domain point u (piecewise linear, as the map uses it).
  Eigen::Vector2d surface(const Eigen::Vector2d& u) const {
    const PointLocation hit = locator->locate(u);
    Eigen::Vector2d point = Eigen::Vector2d::Zero();
    for (int k = 0; k < 3; ++k)
      point += hit.bary[k] * patch.positions[patch.triangles[hit.triangle][k]].head<2>();
    return point;
  }
};

// warp(u, v) = (u + c sin(pi u) sin(pi v), v): a bijection of the unit square onto itself for
// c < 1/pi that is the identity on its boundary.
constexpr double kWarp = 0.2;

Eigen::Vector2d warp(const Eigen::Vector2d& u) {
  return {u.x() + kWarp * std::sin(std::numbers::pi * u.x()) * std::sin(std::numbers::pi * u.y()), u.y()};
}

// warp^-1 by Newton on the first coordinate (the second is unchanged).
Eigen::Vector2d unwarp(const Eigen::Vector2d& x) {
  double u = x.x();
  const double s = kWarp * std::sin(std::numbers::pi * x.y());
  for (int i = 0; i < 50; ++i) {
    const double f = u + s * std::sin(std::numbers::pi * u) - x.x();
    u -= f / (1.0 + s * std::numbers::pi * std::cos(std::numbers::pi * u));
  }
  return {u, x.y()};
}

WarpedTarget warped_target(int n, bool warped) {
  WarpedTarget target;
  target.patch = test::planar_grid_patch(n, Eigen::Matrix2d::Identity(), 2);
  for (const Eigen::Vector3d& x : target.patch.positions) {
    target.uv.push_back(warped ? unwarp(x.head<2>()) : Eigen::Vector2d(x.head<2>()));
    if (warped) {
      EXPECT_LT((warp(target.uv.back()) - x.head<2>()).norm(), 1e-12);
    }
  }
  target.locator.emplace(target.uv, target.patch.triangles);
  return target;
}

std::vector<Eigen::Vector2d> plane_positions(const DiskPatch& patch) {
  std::vector<Eigen::Vector2d> uv;
  for (const Eigen::Vector3d& x : patch.positions) uv.emplace_back(x.head<2>());
  return uv;
}

int flipped(const DiskPatch& patch, const std::vector<Eigen::Vector2d>& uv) {
  int count = 0;
  for (const std::array<int, 3>& t : patch.triangles) {
    if (!(signed_area2(uv[t[0]], uv[t[1]], uv[t[2]]) > 0.0)) ++count;
  }
  return count;
}

TEST(MapRelaxation, AnIsometryIsLeftAsItIsWithEnergyFourPerUnitArea) {
  const DiskPatch source = test::planar_grid_patch(10, Eigen::Matrix2d::Identity(), 1);
  const WarpedTarget target = warped_target(14, false);
  const std::vector<Eigen::Vector2d> start = plane_positions(source);
  const MapRelaxationResult result = relax_patch_map(source, start, target.view(), 1.0);
  EXPECT_NEAR(result.area, 1.0, 1e-12);
  EXPECT_NEAR(result.energy_before, 4.0, 1e-9);  // SD = |I|^2 + |I^-1|^2 = 4 on every face
  EXPECT_LE(result.energy_after, result.energy_before);
  for (size_t v = 0; v < start.size(); ++v) EXPECT_LT((result.uv[v] - start[v]).norm(), 1e-9) << v;
}

TEST(MapRelaxation, UndoesAWarpOfTheTargetParameterization) {
  // Placed by the identity, the template lands on warp(x) instead of x; the relaxation must
  // find uv = warp^-1(x), where the composed map is the identity again.
  const DiskPatch source = test::planar_grid_patch(10, Eigen::Matrix2d::Identity(), 1);
  const WarpedTarget target = warped_target(24, true);
  const std::vector<Eigen::Vector2d> start = plane_positions(source);
  double error_before = 0.0;
  for (const Eigen::Vector2d& u : start)
    error_before = std::max(error_before, (target.surface(u) - u).norm());
  ASSERT_GT(error_before, 0.15);

  const MapRelaxationResult result = relax_patch_map(source, start, target.view(), 1.0);
  EXPECT_GT(result.iterations, 0);
  EXPECT_LT(result.energy_after, result.energy_before);
  EXPECT_LT(result.energy_after / result.area, 4.02);
  EXPECT_EQ(flipped(source, result.uv), 0);
  double error_after = 0.0;
  for (size_t v = 0; v < start.size(); ++v) {
    error_after = std::max(error_after, (target.surface(result.uv[v]) - start[v]).norm());
  }
  EXPECT_LT(error_after, 0.1 * error_before);  // measured: 0.0073 against 0.199
  for (int v : source.boundary_loop) EXPECT_EQ(result.uv[v], start[v]) << v;
}

TEST(MapRelaxation, ScaleIsTheTargetToTemplateLengthRatio) {
  // The same warp on a target twice the size: with scale 2 the optimum is the same placement.
  const DiskPatch source = test::planar_grid_patch(8, Eigen::Matrix2d::Identity(), 3);
  WarpedTarget target = warped_target(16, true);
  const MapRelaxationResult unit = relax_patch_map(source, plane_positions(source), target.view(), 1.0);
  for (Eigen::Vector3d& x : target.patch.positions) x *= 2.0;
  const MapRelaxationResult doubled = relax_patch_map(source, plane_positions(source), target.view(), 2.0);
  EXPECT_NEAR(doubled.energy_before, unit.energy_before, 1e-9 * unit.energy_before);
  for (size_t v = 0; v < unit.uv.size(); ++v) EXPECT_LT((doubled.uv[v] - unit.uv[v]).norm(), 1e-9) << v;
}

TEST(MapRelaxation, LeavesAPlacementWithAFlippedTriangleAlone) {
  const DiskPatch source = test::planar_grid_patch(6, Eigen::Matrix2d::Identity(), 4);
  const WarpedTarget target = warped_target(10, true);
  std::vector<Eigen::Vector2d> start = plane_positions(source);
  const int interior = source.triangles[20][0];
  start[interior] = start[interior] + Eigen::Vector2d(0.5, 0.5);  // far past its neighbours
  ASSERT_GT(flipped(source, start), 0);
  const MapRelaxationResult result = relax_patch_map(source, start, target.view(), 1.0);
  EXPECT_EQ(result.iterations, 0);
  EXPECT_TRUE(std::isinf(result.energy_before));
  EXPECT_EQ(result.uv, start);
}

// The unit-square grid with a narrow finger of height 2 raised in its middle: the mean-value
// parameterization squeezes the finger into a spot of the square.
DiskPatch finger_patch() {
  DiskPatch patch = test::planar_grid_patch(40, Eigen::Matrix2d::Identity(), 5);
  for (Eigen::Vector3d& x : patch.positions) {
    x.z() = 2.0 * std::exp(-(x.head<2>() - Eigen::Vector2d(0.5, 0.5)).squaredNorm() / (2.0 * 0.05 * 0.05));
  }
  return patch;
}

// Share of the uv area taken by the faces whose 3-D centroid is high on the finger.
double finger_uv_share(const DiskPatch& patch, const std::vector<Eigen::Vector2d>& uv) {
  double finger = 0.0;
  double total = 0.0;
  for (const std::array<int, 3>& t : patch.triangles) {
    const double area = 0.5 * signed_area2(uv[t[0]], uv[t[1]], uv[t[2]]);
    total += area;
    if ((patch.positions[t[0]].z() + patch.positions[t[1]].z() + patch.positions[t[2]].z()) / 3.0 > 1.0)
      finger += area;
  }
  return finger / total;
}

TEST(PatchParameterizationRelaxation, GivesASqueezedFingerRoomInThePolygon) {
  const DiskPatch patch = finger_patch();
  const std::vector<Eigen::Vector2d> mean_value = parameterize_patch(patch).uv;
  const MapRelaxationResult result = relax_patch_parameterization(patch, mean_value, {300, 1e-4, 4.4});
  EXPECT_GT(result.energy_before, 100.0 * result.area);        // measured: mean SD 1773
  EXPECT_LT(result.energy_after, 0.1 * result.energy_before);  // measured: 17.2
  EXPECT_EQ(flipped(patch, result.uv), 0);
  for (int v : patch.boundary_loop) EXPECT_EQ(result.uv[v], mean_value[v]) << v;
  // The finger's faces hold a share of the 3-D area far above their mean-value share of the square.
  // Measured: 5.2% of the square against 0.23%.
  EXPECT_GT(finger_uv_share(patch, result.uv), 10.0 * finger_uv_share(patch, mean_value));
}

}  // namespace
}  // namespace xparam
