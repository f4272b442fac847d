// The whole pair mapped twice to compare thread counts: long under the sanitizers, which cannot
// see a race anyway, so it runs in the Release pass only (label `slow`).
#include "map/pair_mapping.h"

#include "io/anchor_reader.h"
#include "io/curve_reader.h"
#include "io/mesh_loader.h"
#include "support/test_data.h"

#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <vector>

namespace xparam {
namespace {

TEST(PairMapping, UntanglingIsTheSameAtOneAndTwoThreads) {
  const LoadedMesh man = load_mesh(test::data_path("human_man.obj"));
  const AnchorSet anchors = read_anchors(test::data_path("human.anchors.json"));
  // man_flipped: both kinds of move (star and ring) take part.
  const LoadedMesh target = load_mesh(test::data_path("sample_targets/man_flipped.obj"));
  const std::vector<FeatureCurve> curves =
      validate_curves(read_curves(test::data_path("human_man.curves.json")), man.mesh);
  auto run = [&](int threads) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    return map_pair(man.mesh, anchors, target.mesh, anchors, curves);
  };
  const PairMapping one = run(1);
  const PairMapping two = run(2);
  ASSERT_GE(one.untangling.moved_vertices, 1);
  EXPECT_EQ(one.untangling.moved_vertices, two.untangling.moved_vertices);
  EXPECT_EQ(one.untangling.star_moves, two.untangling.star_moves);
  EXPECT_TRUE(one.remesh_vertices == two.remesh_vertices);
  ASSERT_EQ(one.correspondence.size(), two.correspondence.size());
  for (std::size_t v = 0; v < one.correspondence.size(); ++v) {
    EXPECT_EQ(one.correspondence[v].face, two.correspondence[v].face);
    EXPECT_TRUE(one.correspondence[v].bary == two.correspondence[v].bary);
  }
  ASSERT_EQ(one.curves.size(), two.curves.size());
  for (std::size_t c = 0; c < one.curves.size(); ++c)
    EXPECT_TRUE(one.curves[c].positions == two.curves[c].positions);
}

}  // namespace
}  // namespace xparam
