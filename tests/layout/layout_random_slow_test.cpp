// Randomized layouts with fixed seeds: hundreds of anchor sets (spread, clustered, with mesh
// neighbours) on two mesh pairs; the checker must pass on every one. Long under the sanitizers
// (35 s), whose reach the fast layout tests already give this code: label `slow`.
#include "layout/consistent_layout.h"
#include "layout/layout_check.h"
#include "layout_fixtures.h"
#include "support/test_data.h"

#include <gtest/gtest.h>

#include <random>
#include <set>

namespace xparam {
namespace {

using test::handles;

// Anchor set number `seed`: n distinct vertices of `mesh`, of one of three kinds by seed:
// uniform over the mesh, clustered in a ball around one vertex, or uniform plus mesh neighbours.
std::vector<int> random_anchors(const Mesh& mesh, std::uint32_t seed, int n) {
  std::mt19937 random(seed);
  const int n_vertices = static_cast<int>(mesh.n_vertices());
  const auto any_vertex = [&] { return static_cast<int>(random() % static_cast<std::uint32_t>(n_vertices)); };
  std::vector<int> ids;
  std::set<int> used;
  const auto take = [&](int v) {
    if (static_cast<int>(ids.size()) < n && used.insert(v).second) ids.push_back(v);
  };
  switch (seed % 3) {
    case 0:
      while (static_cast<int>(ids.size()) < n) take(any_vertex());
      break;
    case 1: {
      // The n * 8 vertices nearest a random centre, sampled uniformly.
      const Eigen::Vector3d centre = position(mesh, VertexHandle(any_vertex()));
      std::vector<std::pair<double, int>> by_distance;
      for (VertexHandle v : mesh.vertices())
        by_distance.emplace_back((position(mesh, v) - centre).norm(), v.idx());
      std::sort(by_distance.begin(), by_distance.end());
      const std::uint32_t pool = static_cast<std::uint32_t>(std::min<std::size_t>(by_distance.size(), 8 * n));
      while (static_cast<int>(ids.size()) < n) take(by_distance[random() % pool].second);
      break;
    }
    default:
      while (static_cast<int>(ids.size()) < n) {
        const int v = any_vertex();
        take(v);
        take(mesh.to_vertex_handle(mesh.halfedge_handle(VertexHandle(v))).idx());
      }
  }
  return ids;
}

TEST(LayoutRandom, SpotAgainstItsOtherTriangulation) {
  const Mesh low = test::load(test::data_path("spot_low_resolution.obj"));
  const Mesh high = test::load(test::data_path("spot.ply"));
  int laid_out = 0;
  for (std::uint32_t seed = 1; seed <= 150; ++seed) {
    const int n = 4 + static_cast<int>(seed * 7 % 37);
    const std::vector<int> ids = random_anchors(low, seed, n);
    const std::vector<int> twins = test::nearest_vertices(low, ids, high);
    if (std::set<int>(twins.begin(), twins.end()).size() != twins.size()) continue;  // two snapped together
    const auto result = build_consistent_layout(low, handles(ids), high, handles(twins));
    test::expect_consistent(result.layout,
                            "spot seed " + std::to_string(seed) + ", " + std::to_string(n) + " anchors");
    ++laid_out;
  }
  EXPECT_GE(laid_out, 120);
}

TEST(LayoutRandom, HumansOfDifferentConnectivity) {
  const Mesh man = test::load(test::data_path("human_man.obj"));
  const Mesh woman = test::load(test::data_path("human_woman.obj"));
  for (std::uint32_t seed = 1001; seed <= 1100; ++seed) {
    const int n = 4 + static_cast<int>(seed * 13 % 57);
    const std::vector<int> ids = random_anchors(man, seed, n);
    ConsistentLayoutSettings settings;
    settings.greedy_diagonals = seed % 5 != 0;
    const auto result = build_consistent_layout(man, handles(ids), woman, handles(ids), settings);
    test::expect_consistent(result.layout,
                            "humans seed " + std::to_string(seed) + ", " + std::to_string(n) + " anchors");
  }
}

}  // namespace
}  // namespace xparam
