#include "param/patch_parameterization.h"

#include "core/errors.h"
#include "param/convex_polygon.h"
#include "patch_fixtures.h"
#include "support/test_data.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <Eigen/Geometry>

#include <algorithm>

namespace xparam {
namespace {

using test::boundary_loop;
using test::even_corner_positions;
using test::regular_polygon;
using test::uv_signed_areas;

// Distance from p to segment ab.
double segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const double t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
  return (p - (a + t * (b - a))).norm();
}

// Every triangle positively oriented, every boundary vertex on its polygon side, corners on corners.
void expect_bijective_onto_polygon(const DiskPatch& patch, const PatchParameterizationResult& result) {
  ASSERT_EQ(result.uv.size(), patch.positions.size());
  const std::vector<double> areas = uv_signed_areas(patch, result.uv);
  const double smallest = *std::min_element(areas.begin(), areas.end());
  EXPECT_GT(smallest, 0.0) << patch.name << ": a flipped or degenerate uv triangle";
  const int k = static_cast<int>(patch.polygon.size());
  const int m = static_cast<int>(patch.boundary_loop.size());
  for (int j = 0; j < k; ++j) {
    EXPECT_EQ(result.uv[patch.boundary_loop[patch.corner_positions[j]]], patch.polygon[j]);
    const int end = j + 1 < k ? patch.corner_positions[j + 1] : patch.corner_positions[0] + m;
    for (int i = patch.corner_positions[j]; i <= end; ++i) {
      EXPECT_LT(segment_distance(result.uv[patch.boundary_loop[i % m]], patch.polygon[j],
                                 patch.polygon[(j + 1) % k]),
                1e-14);
    }
  }
  // The uv triangles tile the polygon: their areas add up to its area.
  double total = 0.0;
  for (double a : areas) total += a;
  double polygon_area2 = 0.0;
  for (int j = 0; j < k; ++j)
    polygon_area2 += signed_area2(Eigen::Vector2d::Zero(), patch.polygon[j], patch.polygon[(j + 1) % k]);
  EXPECT_NEAR(total, polygon_area2, 1e-12 * polygon_area2);
}

TEST(PatchParameterization, PlanarPatchOntoItsOwnShapeIsTheIdentity) {
  // Mean-value weights reproduce affine functions on a planar mesh, and arc length along a
  // straight side reproduces the side's vertices, so the map must be the rigid motion back.
  const Eigen::Matrix2d shapes[2] = {Eigen::Matrix2d::Identity(),
                                     (Eigen::Matrix2d() << 2.0, 0.7, 0.1, 1.3).finished()};
  for (int s = 0; s < 2; ++s) {
    DiskPatch patch = test::planar_grid_patch(12, shapes[s], 7 + s);
    std::vector<Eigen::Vector2d> plane;
    for (const auto& p : patch.positions) plane.emplace_back(p.x(), p.y());
    const std::vector<double> input_areas = uv_signed_areas(patch, plane);
    ASSERT_GT(*std::min_element(input_areas.begin(), input_areas.end()), 0.0);
    // Move the patch into a general position in space: the map only sees intrinsic geometry.
    const Eigen::Matrix3d rotation =
        Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, 2.0, -0.5).normalized()).toRotationMatrix();
    for (auto& p : patch.positions) p = rotation * p + Eigen::Vector3d(3.0, -1.0, 2.0);
    const PatchParameterizationResult result = parameterize_patch(patch);
    EXPECT_EQ(result.interior_vertices, 11 * 11);
    double worst = 0.0;
    for (std::size_t v = 0; v < plane.size(); ++v) worst = std::max(worst, (result.uv[v] - plane[v]).norm());
    EXPECT_LT(worst, 1e-12) << "shape " << s;
    expect_bijective_onto_polygon(patch, result);
  }
}

TEST(PatchParameterization, HemisphereOntoTriangleAndQuadIsBijective) {
  DiskPatch patch = test::hemisphere_patch(12, 40);
  const int m = static_cast<int>(patch.boundary_loop.size());
  ASSERT_EQ(m, 40);
  for (int k : {3, 4}) {
    patch.corner_positions = even_corner_positions(m, k);
    patch.polygon = regular_polygon(k);
    if (k == 4) {  // a convex quad that is not a square
      patch.polygon = {{0.0, 0.0}, {3.0, 0.2}, {2.5, 1.5}, {0.4, 2.0}};
    }
    const PatchParameterizationResult result = parameterize_patch(patch);
    expect_bijective_onto_polygon(patch, result);
  }
}

TEST(PatchParameterization, RealDiskMeshIsBijective) {
  DiskPatch patch;
  test::read_triangles(test::data_path("cat_head.obj").string(), patch.positions, patch.triangles);
  patch.boundary_loop = boundary_loop(patch.triangles);
  const int m = static_cast<int>(patch.boundary_loop.size());
  for (int k = 3; k <= 6; ++k) {
    patch.corner_positions = even_corner_positions(m, k);
    patch.polygon = regular_polygon(k);
    expect_bijective_onto_polygon(patch, parameterize_patch(patch));
  }
}

TEST(PatchParameterization, RegionsOfRealMeshesAreBijective) {
  int tested = 0;
  for (const char* file : {"human_man.obj", "spot.ply", "fox.ply"}) {
    std::vector<Eigen::Vector3d> positions;
    std::vector<std::array<int, 3>> triangles;
    test::read_triangles(test::data_path(file).string(), positions, triangles);
    for (int seed : {0, static_cast<int>(positions.size()) / 3, static_cast<int>(positions.size()) / 2}) {
      DiskPatch patch;
      try {
        patch = test::region_patch(positions, triangles, seed, 6);
      } catch (const std::runtime_error&) {
        continue;  // the grown region has two boundary loops: not a disk, not a test case
      }
      patch.name = std::string(file) + " around vertex " + std::to_string(seed);
      const int m = static_cast<int>(patch.boundary_loop.size());
      patch.corner_positions = even_corner_positions(m, 4);
      patch.polygon = regular_polygon(4);
      try {
        expect_bijective_onto_polygon(patch, parameterize_patch(patch));
        ++tested;
      } catch (const ParamError& error) {
        // Only a non-disk region may be refused; anything else is a failure.
        EXPECT_NE(std::string(error.what()).find("Euler"), std::string::npos) << error.what();
      }
    }
  }
  EXPECT_GE(tested, 6);
}

TEST(PatchParameterization, BatchIsBitIdenticalAtAnyThreadCount) {
  std::vector<DiskPatch> patches;
  for (int i = 0; i < 8; ++i) {
    DiskPatch patch = test::hemisphere_patch(6 + i, 20 + 3 * i);
    patch.corner_positions = even_corner_positions(static_cast<int>(patch.boundary_loop.size()), 3 + i % 2);
    patch.polygon = regular_polygon(3 + i % 2);
    patches.push_back(patch);
  }
  std::vector<PatchParameterizationResult> one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = parameterize_patches(patches);
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = parameterize_patches(patches);
  }
  ASSERT_EQ(one.size(), patches.size());
  for (std::size_t i = 0; i < patches.size(); ++i) {
    // Bitwise, not approximately: the same doubles, in the same slots.
    EXPECT_TRUE(one[i].uv == two[i].uv) << "patch " << i;
    EXPECT_TRUE(one[i].uv == parameterize_patch(patches[i]).uv) << "patch " << i;
  }
}

TEST(PatchParameterization, BatchReportsTheFirstFailingPatch) {
  std::vector<DiskPatch> patches(5, test::hemisphere_patch(4, 12));
  for (std::size_t i = 0; i < patches.size(); ++i) {
    patches[i].name = "patch " + std::to_string(i);
    patches[i].corner_positions = even_corner_positions(12, 3);
    patches[i].polygon = regular_polygon(3);
  }
  patches[1].polygon = {{0, 0}, {1, 0}, {2, 0}};  // collinear: not convex
  patches[3].polygon = {{0, 0}, {0, 1}, {1, 0}};  // clockwise
  try {
    parameterize_patches(patches);
    FAIL() << "no error";
  } catch (const ParamError& error) {
    EXPECT_EQ(std::string(error.what()).rfind("patch 1:", 0), 0u) << error.what();
  }
}

TEST(PatchParameterization, RejectsBadInput) {
  const DiskPatch good = [] {
    DiskPatch patch = test::hemisphere_patch(4, 12);
    patch.corner_positions = even_corner_positions(12, 4);
    patch.polygon = regular_polygon(4);
    return patch;
  }();
  EXPECT_NO_THROW(parameterize_patch(good));

  DiskPatch reversed = good;  // clockwise loop
  std::reverse(reversed.boundary_loop.begin(), reversed.boundary_loop.end());
  EXPECT_THROW(parameterize_patch(reversed), ParamError);

  DiskPatch unordered = good;
  std::swap(unordered.corner_positions[1], unordered.corner_positions[2]);
  EXPECT_THROW(parameterize_patch(unordered), ParamError);

  DiskPatch concave = good;
  concave.polygon = {{0, 0}, {2, 0}, {0.5, 0.5}, {0, 2}};
  EXPECT_THROW(parameterize_patch(concave), ParamError);

  DiskPatch star = good;  // left turns only, but winds twice
  star.corner_positions = even_corner_positions(12, 5);
  star.polygon.clear();
  for (int j = 0; j < 5; ++j) star.polygon.push_back(regular_polygon(5)[(2 * j) % 5]);
  EXPECT_THROW(parameterize_patch(star), ParamError);

  DiskPatch holed = good;  // remove one interior triangle: an annulus
  holed.triangles.erase(holed.triangles.begin());
  EXPECT_THROW(parameterize_patch(holed), ParamError);

  DiskPatch flipped = good;  // one triangle turned over: its edges run as its neighbours' do
  std::swap(flipped.triangles[0][1], flipped.triangles[0][2]);
  try {
    parameterize_patch(flipped);
    ADD_FAILURE() << "a turned-over triangle was accepted";
  } catch (const ParamError& error) {
    EXPECT_NE(std::string(error.what()).find("used twice in the same direction"), std::string::npos)
        << error.what();
  }

  DiskPatch collapsed = good;  // an interior vertex on top of its neighbour
  collapsed.positions[1] = collapsed.positions[0];
  EXPECT_THROW(parameterize_patch(collapsed), ParamError);
}

}  // namespace
}  // namespace xparam
