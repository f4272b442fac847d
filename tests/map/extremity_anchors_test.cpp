#include "map/extremity_anchors.h"

#include "layout/layout_fixtures.h"

#include <gtest/gtest.h>

#include <variant>

namespace xparam {
namespace {

// The subdivided octahedron (corners 0..5: +x, -x, +y, -y, +z, -z) with the +x corner drawn
// out into a spike of length 2 and the +y corner raised by a bump of 0.05.
Mesh spiked_octahedron() {
  Mesh mesh = test::subdivided_octahedron(6);
  mesh.set_point(VertexHandle(0), to_point(Eigen::Vector3d(3.0, 0.0, 0.0)));
  mesh.set_point(VertexHandle(2), to_point(Eigen::Vector3d(0.0, 1.05, 0.0)));
  return mesh;
}

// From the -z corner, distance grows towards +z and out along the spike: their ends are the
// protrusions; the bump is not the farthest point round it, and a corner with an anchor needs
// no helper.
TEST(ProtrusionTips, AreTheEndsOfProtrusionsWithoutAnchors) {
  const Mesh mesh = spiked_octahedron();
  EXPECT_EQ(protrusion_tips(mesh, 5, {5}, 0.5), (std::vector<int>{0, 4}));
  EXPECT_EQ(protrusion_tips(mesh, 5, {5, 4}, 0.5), (std::vector<int>{0}));
}

// Through the identity map each tip is matched with itself, at no mismatch, and helper names
// avoid the names already taken.
TEST(MatchExtremities, TheIdentityMatchesEachTipWithItself) {
  const Mesh mesh = spiked_octahedron();
  std::vector<Eigen::Vector3d> images;
  for (VertexHandle v : mesh.vertices()) images.push_back(position(mesh, v));
  const std::vector<std::array<int, 3>> faces = triangles_of(mesh);
  const std::vector<int> tips = {0, 4};
  const std::vector<ExtremityAnchor> matched =
      match_extremities(mesh, tips, mesh, tips, {images, faces}, {"tip 1"}, 0.1);
  ASSERT_EQ(matched.size(), 2u);
  EXPECT_EQ(matched[0].specs[0].name, "tip 1'");
  EXPECT_EQ(matched[1].specs[0].name, "tip 2");
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(std::get<AnchorVertex>(matched[k].specs[0].location).index, tips[k]);
    EXPECT_EQ(std::get<AnchorVertex>(matched[k].specs[1].location).index, tips[k]);
    EXPECT_EQ(matched[k].specs[0].name, matched[k].specs[1].name);
    EXPECT_NEAR(matched[k].mismatch, 0.0, 1e-12);
  }
  // Through a map that swaps the two tips' images, each template tip is matched with the other.
  std::vector<Eigen::Vector3d> swapped = images;
  std::swap(swapped[0], swapped[4]);
  const std::vector<ExtremityAnchor> crossed = match_extremities(mesh, tips, mesh, tips, {swapped, faces}, {}, 0.1);
  ASSERT_EQ(crossed.size(), 2u);
  EXPECT_EQ(std::get<AnchorVertex>(crossed[0].specs[0].location).index, 0);
  EXPECT_EQ(std::get<AnchorVertex>(crossed[0].specs[1].location).index, 4);
  EXPECT_EQ(std::get<AnchorVertex>(crossed[1].specs[0].location).index, 4);
  EXPECT_EQ(std::get<AnchorVertex>(crossed[1].specs[1].location).index, 0);
}

}  // namespace
}  // namespace xparam
