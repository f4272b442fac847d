// The region helpers of the curve operators (layout/chain_edit.h) on a real layout: they visit
// only the faces they reach from the curve, so they must reach all of them.
#include "layout/chain_edit.h"

#include "layout_fixtures.h"

#include <gtest/gtest.h>

#include <array>
#include <string>
#include <vector>

namespace xparam {
namespace {

// Every face whose patch is one of `patches`, by reading every face's label.
std::vector<bool> labelled(const Mesh& mesh, const std::array<int, 2>& patches) {
  const auto handle = patch_property(mesh);
  std::vector<bool> mask(mesh.n_faces(), false);
  for (const FaceHandle f : mesh.faces()) {
    const int p = mesh.property(handle, f);
    mask[f.idx()] = p == patches[0] || p == patches[1];
  }
  return mask;
}

TEST(ChainEdit, PatchMaskReachesEveryFaceOfTheCurvesTwoPatches) {
  const Layout& layout = test::human_layout();
  for (int side = 0; side < 2; ++side) {
    const Mesh& mesh = layout.sides[side].mesh;
    for (int e = 0; e < static_cast<int>(layout.edges.size()); ++e) {
      const std::array<int, 2> patches = patches_of_edge(layout, e);
      EXPECT_EQ(patch_mask(mesh, patches, layout.sides[side].chains[e]), labelled(mesh, patches))
          << "side " << side << ", layout edge " << e;
    }
  }
}

// Re-labelling a region through the curve that divides it gives every face its label back, from
// a region labelled all one patch and all the other: the floods from either side of the curve
// reach their whole patch, and nothing beyond.
TEST(ChainEdit, RelabellingThroughTheDividingCurveRestoresEveryLabel) {
  const Layout& layout = test::human_layout();
  for (int side = 0; side < 2; ++side) {
    Mesh mesh = layout.sides[side].mesh;
    const auto handle = patch_property(mesh);
    std::vector<int> before;
    for (const FaceHandle f : mesh.faces()) before.push_back(mesh.property(handle, f));
    for (int e = 0; e < static_cast<int>(layout.edges.size()); ++e) {
      const std::array<int, 2> patches = patches_of_edge(layout, e);
      const std::vector<VertexHandle>& chain = layout.sides[side].chains[e];
      const std::vector<bool> region = patch_mask(mesh, patches, chain);
      int in_left_patch = 0;
      for (const FaceHandle f : mesh.faces()) in_left_patch += before[f.idx()] == patches[0];
      for (const int scrambled : patches) {
        for (const FaceHandle f : mesh.faces()) {
          if (region[f.idx()]) mesh.property(handle, f) = scrambled;
        }
        EXPECT_EQ(relabel_region(mesh, region, chain, patches), in_left_patch)
            << "side " << side << ", layout edge " << e;
        for (const FaceHandle f : mesh.faces()) {
          ASSERT_EQ(mesh.property(handle, f), before[f.idx()])
              << "side " << side << ", layout edge " << e << ", face " << f.idx();
        }
      }
    }
  }
}

}  // namespace
}  // namespace xparam
