#include "geodesic/locally_shortest.h"

#include "geodesic/test_meshes.h"

#include <gtest/gtest.h>

namespace xparam {
namespace {

using test::grid_walk;

TEST(LocallyShortest, StraightGridLineIsAndCornerIsNot) {
  const Mesh mesh = test::flat_grid(6, 6);
  const std::vector<bool> everything(mesh.n_faces(), true);
  EXPECT_TRUE(is_locally_shortest(mesh, everything, grid_walk(6, {{1, 2}, {5, 2}}), 1e-12));
  // The diagonal of the grid's squares is an edge line too.
  EXPECT_TRUE(is_locally_shortest(mesh, everything, grid_walk(6, {{1, 1}, {5, 5}}), 1e-12));
  std::string why;
  EXPECT_FALSE(is_locally_shortest(mesh, everything, grid_walk(6, {{1, 2}, {4, 2}, {4, 5}}), 1e-6, &why));
  EXPECT_NE(why.find(std::to_string(test::grid_vertex(6, 4, 2).idx())), std::string::npos) << why;
  EXPECT_NE(why.find("left"), std::string::npos) << why;  // the walk turns left there
}

TEST(LocallyShortest, ASideOutsideTheRegionIsNotChecked) {
  const Mesh mesh = test::flat_grid(6, 6);
  std::vector<bool> region(mesh.n_faces(), true);
  const std::vector<VertexHandle> corner = grid_walk(6, {{1, 2}, {4, 2}, {4, 5}});
  // Take the faces of square (3, 2) (inside the corner, left of the walk) out of the region.
  region[2 * (2 * 6 + 3)] = region[2 * (2 * 6 + 3) + 1] = false;
  EXPECT_TRUE(is_locally_shortest(mesh, region, corner, 1e-6));
}

TEST(LocallyShortest, CubeCornerSpansLessThanPiOnItsThreeFaceSide) {
  std::map<std::array<int, 3>, VertexHandle> index;
  const Mesh cube = test::subdivided_cube(2, &index);
  const std::vector<bool> everything(cube.n_faces(), true);
  // Along two cube edges into and out of the corner (1, 1, 1): the top side spans pi / 2,
  // the other (two side faces) pi.
  const std::vector<VertexHandle> bent = {index.at({2, 1, 2}), index.at({2, 2, 2}), index.at({1, 2, 2})};
  EXPECT_FALSE(is_locally_shortest(cube, everything, bent, 1e-6));
  // A straight line across the top through its centre is a geodesic.
  const std::vector<VertexHandle> straight = {index.at({0, 1, 2}), index.at({1, 1, 2}), index.at({2, 1, 2})};
  EXPECT_TRUE(is_locally_shortest(cube, everything, straight, 1e-12));
  EXPECT_NEAR(chain_length(cube, straight), 1.0, 1e-15);
}

TEST(LocallyShortest, BrokenChainsAreReported) {
  const Mesh mesh = test::flat_grid(4, 4);
  const std::vector<bool> everything(mesh.n_faces(), true);
  std::string why;
  EXPECT_FALSE(is_locally_shortest(mesh, everything, {test::grid_vertex(4, 1, 1), test::grid_vertex(4, 3, 1)},
                                   1e-6, &why));
  EXPECT_NE(why.find("not joined"), std::string::npos);
  EXPECT_FALSE(
      is_locally_shortest(mesh, std::vector<bool>(2, true), grid_walk(4, {{1, 1}, {3, 1}}), 1e-6, &why));
}

}  // namespace
}  // namespace xparam
