// Decimation by multiple choice (DecimationSettings::choices), the working copy's: the bundled SMPL
// man subdivided once (27,554 vertices) down to 3,000, against the greedy decimation it replaces
// there. Long under the sanitizers (39 s), whose reach the fast working-copy tests, which decimate,
// already give this code: label `slow`.
#include "map/decimation.h"

#include "core/mesh_builder.h"
#include "core/midpoint_subdivision.h"
#include "core/validation.h"
#include "io/mesh_loader.h"
#include "support/test_data.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace xparam {
namespace {

constexpr int kVertices = 3000;

const Mesh& fine_man() {
  static const Mesh mesh = subdivide_midpoint(load_mesh(test::data_path("human_man.obj")).mesh);
  return mesh;
}

DecimationSettings sampled() {
  DecimationSettings settings;
  settings.choices = 8;
  settings.max_aspect_ratio = 20.0;
  return settings;
}

std::vector<VertexHandle> every_hundredth_vertex(const Mesh& mesh) {
  std::vector<VertexHandle> locked;
  for (int v = 0; v < static_cast<int>(mesh.n_vertices()); v += 100) locked.emplace_back(v);
  return locked;
}

TEST(SampledDecimation, ReachesTheCountKeepingLockedVerticesWhereTheyWere) {
  const std::vector<VertexHandle> locked = every_hundredth_vertex(fine_man());
  const DecimatedMesh decimated = decimate(fine_man(), kVertices, locked, sampled());
  ASSERT_EQ(decimated.mesh.n_vertices(), static_cast<std::size_t>(kVertices));
  ASSERT_EQ(decimated.source_vertex.size(), decimated.mesh.n_vertices());
  for (VertexHandle v : decimated.mesh.vertices()) {
    const VertexHandle source = fine_man().vertex_handle(decimated.source_vertex[v.idx()]);
    EXPECT_EQ(decimated.mesh.point(v), fine_man().point(source)) << v.idx();
  }
  std::vector<int> kept = decimated.source_vertex;
  std::sort(kept.begin(), kept.end());
  for (VertexHandle v : locked) EXPECT_TRUE(std::binary_search(kept.begin(), kept.end(), v.idx())) << v.idx();
  // Still a closed 2-manifold of genus 0, consistently oriented: what map_pair takes.
  EXPECT_TRUE(validate_soup(soup_of(decimated.mesh, "decimated")).usable);
}

TEST(SampledDecimation, IsTheSameMeshOnEveryRun) {
  const DecimatedMesh first = decimate(fine_man(), kVertices, {}, sampled());
  const DecimatedMesh second = decimate(fine_man(), kVertices, {}, sampled());
  EXPECT_EQ(first.source_vertex, second.source_vertex);
  ASSERT_EQ(first.mesh.n_faces(), second.mesh.n_faces());
  for (FaceHandle f : first.mesh.faces()) {
    std::vector<int> a, b;
    for (VertexHandle v : first.mesh.fv_range(f)) a.push_back(v.idx());
    for (VertexHandle v : second.mesh.fv_range(second.mesh.face_handle(f.idx()))) b.push_back(v.idx());
    EXPECT_EQ(a, b) << f.idx();
  }
}

// Multiple choice trades some evenness for speed, not the shape. Measured by the largest distance
// from a vertex of the input (every 29th) to the nearest kept one: one draw per collapse (a random
// order) gives twice the greedy decimation's and fails this.
TEST(SampledDecimation, KeepsVerticesAsSpreadAsTheGreedyDecimation) {
  DecimationSettings greedy = sampled();
  greedy.choices = 0;
  const auto spread = [](const DecimatedMesh& decimated) {
    double largest = 0.0;
    std::vector<Eigen::Vector3d> kept;
    for (VertexHandle v : decimated.mesh.vertices()) kept.push_back(position(decimated.mesh, v));
    for (int v = 0; v < static_cast<int>(fine_man().n_vertices()); v += 29) {
      const Eigen::Vector3d p = position(fine_man(), fine_man().vertex_handle(v));
      double nearest = std::numeric_limits<double>::infinity();
      for (const Eigen::Vector3d& q : kept) nearest = std::min(nearest, (p - q).squaredNorm());
      largest = std::max(largest, nearest);
    }
    return std::sqrt(largest);
  };
  const double of_greedy = spread(decimate(fine_man(), kVertices, {}, greedy));
  const double of_sampled = spread(decimate(fine_man(), kVertices, {}, sampled()));
  EXPECT_LT(of_sampled, 1.5 * of_greedy) << of_greedy;
}

}  // namespace
}  // namespace xparam
