// Construction of the consistent layout on the bundled meshes: the checker passes, counts are
// right, refinement keeps provenance, results are deterministic, bad inputs are refused.
#include "layout/consistent_layout.h"
#include "core/errors.h"
#include "layout/layout_check.h"
#include "layout_fixtures.h"
#include "support/test_data.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

namespace xparam {
namespace {

using test::data_path;
using test::expect_consistent;
using test::handles;

struct HumanPair {
  Mesh man = test::load(data_path("human_man.obj"));
  Mesh woman = test::load(data_path("human_woman.obj"));
};

const HumanPair& humans() {
  static const HumanPair pair;
  return pair;
}

void expect_good_layout(const ConsistentLayoutResult& result, const Mesh& source, const Mesh& target, int n,
                        const std::string& what) {
  const Layout& layout = result.layout;
  EXPECT_EQ(layout.n_anchors, n) << what;
  EXPECT_EQ(static_cast<int>(layout.edges.size()), 3 * n - 6) << what;
  EXPECT_EQ(static_cast<int>(layout.patches.size()), 2 * n - 4) << what;
  EXPECT_EQ(result.tree_edges, n - 1) << what;
  EXPECT_EQ(result.tree_edges + result.greedy_edges + result.completion_edges, 3 * n - 6) << what;
  expect_consistent(layout, what);
  test::expect_provenance(layout.sides[0].mesh, source, what + " (source)");
  test::expect_provenance(layout.sides[1].mesh, target, what + " (target)");
  // Refinement only adds: the input vertices keep their places.
  for (int side = 0; side < 2; ++side) {
    const Mesh& input = side == 0 ? source : target;
    const Mesh& refined = layout.sides[side].mesh;
    EXPECT_EQ(refined.n_vertices(), input.n_vertices() + result.refined_vertices[side]) << what;
    for (VertexHandle v : input.vertices()) ASSERT_EQ(position(refined, v), position(input, v)) << what;
  }
}

TEST(ConsistentLayout, HumansWithSpreadAnchors) {
  const auto& [man, woman] = humans();
  for (int n : {4, 8, 20}) {
    const std::vector<int> ids = test::farthest_points(man, n, 412);
    const auto result = build_consistent_layout(man, handles(ids), woman, handles(ids));
    expect_good_layout(result, man, woman, n, "man/woman " + std::to_string(n) + " anchors");
  }
}

TEST(ConsistentLayout, HumansWithTheAnthropometryLandmarks) {
  const auto dir = test::shared_data_dir();
  if (dir.empty()) GTEST_SKIP() << "shared data absent";
  const auto& [man, woman] = humans();
  const std::vector<int> ids =
      test::landmark_ids(dir / "faust_landmarks" / "smpl_anthropometry_landmark_indices.json");
  ASSERT_EQ(ids.size(), 29u);
  const auto result = build_consistent_layout(man, handles(ids), woman, handles(ids));
  expect_good_layout(result, man, woman, 29, "man/woman anthropometry");
}

TEST(ConsistentLayout, SpotAgainstItsOtherTriangulation) {
  const Mesh low = test::load(data_path("spot_low_resolution.obj"));
  const Mesh high = test::load(data_path("spot.ply"));
  for (int n : {4, 12, 30}) {
    const std::vector<int> ids = test::farthest_points(low, n);
    const std::vector<int> twins = test::nearest_vertices(low, ids, high);
    const auto result = build_consistent_layout(low, handles(ids), high, handles(twins));
    expect_good_layout(result, low, high, n, "spot " + std::to_string(n) + " anchors");
  }
}

TEST(ConsistentLayout, AMeshAgainstItselfGetsTheSameChainsOnBothSides) {
  const Mesh spot = test::load(data_path("spot_low_resolution.obj"));
  const std::vector<int> ids = test::farthest_points(spot, 15);
  const auto result = build_consistent_layout(spot, handles(ids), spot, handles(ids));
  expect_good_layout(result, spot, spot, 15, "spot against itself");
  // Same mesh, same anchors: every target path is forced through the corners the source path
  // took, and the shortest path there is the source path itself.
  EXPECT_EQ(result.layout.sides[0].chains, result.layout.sides[1].chains);
  EXPECT_EQ(result.refined_vertices[0], result.refined_vertices[1]);
}

TEST(ConsistentLayout, AnchorsThatAreMeshNeighbours) {
  const auto& [man, woman] = humans();
  std::vector<int> ids = test::farthest_points(man, 10, 412);
  // Every anchor gets a mesh neighbour as a second anchor; a triangle of three neighbours too.
  const std::size_t spread = ids.size();
  for (std::size_t k = 0; k < spread; ++k) {
    for (VertexHandle w : man.vv_range(VertexHandle(ids[k]))) {
      if (std::find(ids.begin(), ids.end(), w.idx()) == ids.end()) {
        ids.push_back(w.idx());
        break;
      }
    }
  }
  const FaceHandle f = *man.vf_range(VertexHandle(3500)).begin();
  for (VertexHandle v : man.fv_range(f)) ids.push_back(v.idx());
  const auto result = build_consistent_layout(man, handles(ids), woman, handles(ids));
  expect_good_layout(result, man, woman, static_cast<int>(ids.size()), "neighbour anchors");
  EXPECT_GT(result.refined_vertices[0], 0);
}

TEST(ConsistentLayout, AnchorsAllOnOneLimb) {
  const auto& [man, woman] = humans();
  // 20 anchors within 25 cm of the left wrist (SMPL vertex 2241), plus the head top.
  const Eigen::Vector3d wrist = position(man, VertexHandle(2241));
  std::vector<int> ids = test::farthest_points(
      man, 20, 2241, [&](int v) { return (position(man, VertexHandle(v)) - wrist).norm() < 0.25; });
  ids.push_back(412);
  const auto result = build_consistent_layout(man, handles(ids), woman, handles(ids));
  expect_good_layout(result, man, woman, 21, "one limb");
}

TEST(ConsistentLayout, CompletionAloneTriangulatesEveryFace) {
  const auto& [man, woman] = humans();
  const std::vector<int> ids = test::farthest_points(man, 25, 412);
  ConsistentLayoutSettings settings;
  settings.greedy_diagonals = false;
  const auto result = build_consistent_layout(man, handles(ids), woman, handles(ids), settings);
  EXPECT_EQ(result.greedy_edges, 0);
  EXPECT_EQ(result.completion_edges, 3 * 25 - 6 - 24);
  expect_good_layout(result, man, woman, 25, "completion only");
}

TEST(ConsistentLayout, GreedyDiagonalsAreShorterThanCompletionAlone) {
  const auto& [man, woman] = humans();
  const std::vector<int> ids = test::farthest_points(man, 25, 412);
  ConsistentLayoutSettings completion_only;
  completion_only.greedy_diagonals = false;
  const auto greedy = build_consistent_layout(man, handles(ids), woman, handles(ids));
  const auto plain = build_consistent_layout(man, handles(ids), woman, handles(ids), completion_only);
  EXPECT_LT(greedy.total_path_length[0] + greedy.total_path_length[1],
            plain.total_path_length[0] + plain.total_path_length[1]);
}

TEST(ConsistentLayout, SameResultAtAnyThreadCount) {
  const auto& [man, woman] = humans();
  const std::vector<int> ids = test::farthest_points(man, 20, 100);
  const auto parallel = build_consistent_layout(man, handles(ids), woman, handles(ids));
  const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  const auto serial = build_consistent_layout(man, handles(ids), woman, handles(ids));
  for (int side = 0; side < 2; ++side) {
    EXPECT_EQ(parallel.layout.sides[side].chains, serial.layout.sides[side].chains);
    EXPECT_EQ(parallel.layout.sides[side].mesh.n_vertices(), serial.layout.sides[side].mesh.n_vertices());
  }
  EXPECT_EQ(parallel.layout.patches, serial.layout.patches);
}

TEST(ConsistentLayout, SameLayoutTellsARepeatFromAnotherLayout) {
  const auto& [man, woman] = humans();
  const std::vector<int> ids = test::farthest_points(man, 20, 100);
  const Layout first = build_consistent_layout(man, handles(ids), woman, handles(ids)).layout;
  const Layout again = build_consistent_layout(man, handles(ids), woman, handles(ids)).layout;
  EXPECT_TRUE(same_layout(first, again));
  EXPECT_TRUE(same_layout(again, first));

  // One refined vertex of the target moved a hair: another embedding.
  Layout moved = again;
  Mesh& target = moved.sides[1].mesh;
  const VertexHandle v(static_cast<int>(target.n_vertices()) - 1);
  target.set_point(v, target.point(v) + Mesh::Point(1e-9, 0.0, 0.0));
  EXPECT_FALSE(same_layout(first, moved));

  // One anchor fewer: other combinatorics.
  const std::vector<int> fewer(ids.begin(), ids.end() - 1);
  EXPECT_FALSE(
      same_layout(first, build_consistent_layout(man, handles(fewer), woman, handles(fewer)).layout));
}

// The octahedron's faces (outward), optionally without the last and/or twice (a second copy
// shifted away): an open mesh and a two-component mesh.
Mesh octahedron_variant(bool drop_a_face, bool two_copies) {
  Mesh mesh;
  const int faces[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                           {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (int copy = 0; copy < (two_copies ? 2 : 1); ++copy) {
    const Eigen::Vector3d shift(3.0 * copy, 0, 0);
    std::vector<VertexHandle> v;
    for (const Eigen::Vector3d& c :
         {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(-1, 0, 0), Eigen::Vector3d(0, 1, 0),
          Eigen::Vector3d(0, -1, 0), Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0, 0, -1)}) {
      v.push_back(mesh.add_vertex(to_point(c + shift)));
    }
    for (int f = 0; f < (drop_a_face ? 7 : 8); ++f)
      mesh.add_face(v[faces[f][0]], v[faces[f][1]], v[faces[f][2]]);
  }
  return mesh;
}

TEST(ConsistentLayout, RefusesInputsThatCannotBeLaidOut) {
  const Mesh spot = test::load(data_path("spot_low_resolution.obj"));
  const Mesh torus = test::load(data_path("bob_small.ply"));
  const std::vector<int> ids = {0, 100, 200, 300, 400};
  const auto message = [&](const Mesh& a, const std::vector<int>& ia, const Mesh& b,
                           const std::vector<int>& ib) {
    try {
      build_consistent_layout(a, handles(ia), b, handles(ib));
    } catch (const LayoutError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message(spot, ids, torus, ids),
            "target mesh has genus 1 (Euler characteristic 0); the layout needs genus 0");
  EXPECT_EQ(message(octahedron_variant(true, false), {0, 1, 2, 3}, spot, {0, 1, 2, 3}),
            "source mesh has 3 boundary edges; a layout needs a closed mesh");
  EXPECT_EQ(message(spot, {0, 1, 2, 3}, octahedron_variant(false, true), {0, 1, 2, 3}),
            "target mesh has 2 connected components; a layout needs one");
  EXPECT_EQ(message(spot, ids, spot, {0, 100, 200, 300}), "source has 5 anchors but target has 4");
  EXPECT_EQ(message(spot, {0, 1, 2}, spot, {0, 1, 2}), "a layout needs at least 4 anchors; got 3");
  EXPECT_EQ(message(spot, {0, 100, 200, 100}, spot, {0, 100, 200, 300}),
            "source anchors 1 and 3 are the same vertex 100");
  EXPECT_EQ(message(spot, ids, spot, {0, 100, 200, 300, 99999}),
            "target anchor 4: vertex 99999 is not a vertex of the mesh (829 vertices)");
}

}  // namespace
}  // namespace xparam
