#include "map/extremity_anchors.h"

#include "layout/anchor_voronoi.h"
#include "layout/layout_fixtures.h"
#include "map/tip_rows.h"
#include "support/test_data.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
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
  EXPECT_EQ(extremities(mesh, tip_distances(mesh, 5, {5}), 0.5).tips, (std::vector<int>{0, 4}));
  EXPECT_EQ(extremities(mesh, tip_distances(mesh, 5, {5, 4}), 0.5).tips, (std::vector<int>{0}));
}

// Anchors nearer each other than 0.05 sqrt(area) on both meshes hold one limb, transitively; an
// anchor near another on one mesh only stays apart.
TEST(LimbGroups, JoinLandmarksNearOnBothMeshesTransitively) {
  const Mesh mesh = test::subdivided_octahedron(24);  // sqrt(area) 2.63: 0.05 of it is 0.13
  const int a = 5;                                    // the -z corner
  const int b = test::vertex_at(mesh, {1.0 / 12, 0.0, -11.0 / 12}).idx();  // 0.118 from a
  const int c = test::vertex_at(mesh, {1.0 / 6, 0.0, -5.0 / 6}).idx();     // 0.118 from b, 0.236 from a
  const Extremities none;
  const std::vector<int> anchors = {a, b, c, 4};
  const TipsAndAnchors side{mesh, none, anchors, 0.025};
  EXPECT_EQ(limb_groups(side, side), (std::vector<int>{0, 0, 0, 3}));
  const std::vector<int> b_apart = {a, 0, c, 4};  // b's landmark on the +x corner of the other mesh
  const TipsAndAnchors other{mesh, none, b_apart, 0.025};
  EXPECT_EQ(limb_groups(side, other), (std::vector<int>{0, 1, 2, 3}));
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
    EXPECT_NEAR(matched[k].mismatch(), 0.0, 1e-12);
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

// The spiked octahedron with landmarks at its -z and +y corners, and a first map that draws the
// spike's tip into the landmark whose cell holds it (a hand squeezed into the wrist), leaving the
// rest in place.
class SqueezedSpike : public ::testing::Test {
 protected:
  SqueezedSpike()
      : mesh(spiked_octahedron()),
        ends(extremities(mesh, tip_distances(mesh, 5, anchors), 0.5)),
        faces(triangles_of(mesh)) {
    const int spike_cell = anchor_voronoi(mesh, {VertexHandle(5), VertexHandle(2)}).cell[0];
    for (VertexHandle v : mesh.vertices()) images.push_back(position(mesh, v));
    images[0] = position(mesh, VertexHandle(anchors[spike_cell])) + Eigen::Vector3d(0.05, 0.0, 0.0);
  }

  const Mesh mesh;
  const std::vector<int> anchors = {5, 2};
  const Extremities ends;
  const std::vector<std::array<int, 3>> faces;
  std::vector<Eigen::Vector3d> images;
  const double reach = 0.5 / std::sqrt(surface_area(mesh));
};

// No tip pair is near through the squeezing map, and the cell matches the spike's tip with itself;
// the +z corner, which the map leaves in place, is matched through the map, not by its cell.
TEST_F(SqueezedSpike, TheLandmarksCellMatchesTheSqueezedTip) {
  ASSERT_EQ(ends.tips, (std::vector<int>{0, 4}));
  const TipsAndAnchors side{mesh, ends, anchors, reach};
  const std::vector<ExtremityAnchor> through_map =
      match_extremities(mesh, ends.tips, mesh, ends.tips, {images, faces}, {}, 0.1);
  ASSERT_EQ(through_map.size(), 1u);
  EXPECT_EQ(std::get<AnchorVertex>(through_map[0].specs[0].location).index, 4);
  const std::vector<ExtremityAnchor> by_cell = match_extremities_by_cell(side, side, {images, faces}, {}, {"tip 1"});
  ASSERT_EQ(by_cell.size(), 1u);
  EXPECT_EQ(std::get<AnchorVertex>(by_cell[0].specs[0].location).index, 0);
  EXPECT_EQ(std::get<AnchorVertex>(by_cell[0].specs[1].location).index, 0);
  EXPECT_EQ(by_cell[0].specs[0].name, "tip 1'");
  EXPECT_GT(by_cell[0].mismatch(), 0.1);

  // A matched tip nearer the landmark than the spike's tip (the octahedron is small beside its
  // spike) says the limb has its helper already; through the identity nothing is squeezed.
  EXPECT_TRUE(match_extremities_by_cell(side, side, {images, faces}, through_map, {}).empty());
  for (VertexHandle v : mesh.vertices()) images[v.idx()] = position(mesh, v);
  EXPECT_TRUE(match_extremities_by_cell(side, side, {images, faces}, {}, {}).empty());
}

// A pair matched through a map that squeezes the spike into its landmark is dropped: its cell's
// farthest tip, the spike's, lies nearer the landmark through the map than half as far as on the
// template. The +z corner's pair, in the other cell, stands; through the identity both stand.
TEST_F(SqueezedSpike, PairsThroughTheMapInASqueezedCellAreDropped) {
  std::vector<Eigen::Vector3d> identity;
  for (VertexHandle v : mesh.vertices()) identity.push_back(position(mesh, v));
  const std::vector<ExtremityAnchor> pairs =
      match_extremities(mesh, ends.tips, mesh, ends.tips, {identity, faces}, {}, 0.1);
  ASSERT_EQ(pairs.size(), 2u);
  const TipsAndAnchors side{mesh, ends, anchors, reach};
  ASSERT_NE(ends.cells.cell[0], ends.cells.cell[4]);
  const std::vector<ExtremityAnchor> kept = outside_squeezed_cells(side, side, {images, faces}, pairs);
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_EQ(std::get<AnchorVertex>(kept[0].specs[0].location).index, 4);
  EXPECT_EQ(outside_squeezed_cells(side, side, {identity, faces}, pairs).size(), 2u);
}

// Where the target's limb ends in a blob (an end without a tip: a fist), the cell's farthest end
// stands in for the tip of the template's squeezed spike; without the end, nothing is matched.
TEST_F(SqueezedSpike, ABlobsEndStandsInForATip) {
  const TipsAndAnchors spiked{mesh, ends, anchors, reach};
  Extremities blob_ends = ends;
  blob_ends.tips.clear();  // every end seen as a blob's: no tip on this mesh at all
  const TipsAndAnchors blob{mesh, blob_ends, anchors, reach};
  const std::vector<ExtremityAnchor> by_cell = match_extremities_by_cell(spiked, blob, {images, faces}, {}, {});
  ASSERT_EQ(by_cell.size(), 1u);
  EXPECT_EQ(std::get<AnchorVertex>(by_cell[0].specs[0].location).index, 0);
  EXPECT_EQ(std::get<AnchorVertex>(by_cell[0].specs[1].location).index, 0);

  Extremities no_end = blob_ends;
  no_end.ends = {4};  // the +z corner's end only
  const TipsAndAnchors bare{mesh, no_end, anchors, reach};
  EXPECT_TRUE(match_extremities_by_cell(spiked, bare, {images, faces}, {}, {}).empty());
}

// Two spikes in the -z landmark's cell, +x and -y, squeezed into the landmark by the first map; on
// the template +x is the longer, on the target -y, by a little. The cell matches the farthest tip on
// each mesh, +x with -y, and names the target's +x tip, nearly as far, its rival; matched with the
// rival instead, the template's +x tip keeps its name.
TEST(CellMatch, ATipNearlyAsFarFromTheLandmarkIsTheMatchsRival) {
  const auto two_spikes = [](double x_spike, double y_spike) {
    Mesh mesh = test::subdivided_octahedron(6);
    mesh.set_point(VertexHandle(0), to_point(Eigen::Vector3d(x_spike, 0.0, 0.0)));
    mesh.set_point(VertexHandle(3), to_point(Eigen::Vector3d(0.0, -y_spike, 0.0)));
    return mesh;
  };
  const Mesh source = two_spikes(3.0, 2.5);
  const Mesh target = two_spikes(2.9, 3.0);
  const std::vector<int> anchors = {5, 2};
  const double reach = 0.5;
  const Extremities on_source = extremities(source, tip_distances(source, 5, anchors), reach);
  const Extremities on_target = extremities(target, tip_distances(target, 5, anchors), reach);
  ASSERT_EQ(on_source.tips, (std::vector<int>{0, 3, 4}));
  ASSERT_EQ(on_target.tips, (std::vector<int>{0, 3, 4}));
  ASSERT_EQ(on_source.cells.cell[0], on_source.cells.cell[3]);
  ASSERT_EQ(on_target.cells.cell[0], on_target.cells.cell[3]);
  const std::vector<std::array<int, 3>> faces = triangles_of(source);
  std::vector<Eigen::Vector3d> images;
  for (VertexHandle v : target.vertices()) images.push_back(position(target, v));
  images[0] = images[3] = position(target, VertexHandle(5)) + Eigen::Vector3d(0.05, 0.0, 0.0);
  const FirstMap squeezing{images, faces};
  const std::vector<ExtremityAnchor> by_cell = match_extremities_by_cell(
      {source, on_source, anchors, reach / std::sqrt(surface_area(source))},
      {target, on_target, anchors, reach / std::sqrt(surface_area(target))}, squeezing, {}, {});
  ASSERT_EQ(by_cell.size(), 1u);
  EXPECT_EQ(std::get<AnchorVertex>(by_cell[0].specs[0].location).index, 0);
  EXPECT_EQ(std::get<AnchorVertex>(by_cell[0].specs[1].location).index, 3);
  EXPECT_EQ(by_cell[0].rival_target, 0);

  const ExtremityAnchor rival = matched_with_rival(by_cell[0], source, target, squeezing);
  EXPECT_EQ(std::get<AnchorVertex>(rival.specs[0].location).index, 0);
  EXPECT_EQ(std::get<AnchorVertex>(rival.specs[1].location).index, 0);
  EXPECT_EQ(rival.specs[1].name, by_cell[0].specs[1].name);
  EXPECT_EQ(rival.matched_by, TipMatching::by_cell);
  EXPECT_EQ(rival.rival_target, -1);

  // A target whose -y spike is clearly the longer (2.5 against 3.5) gives the match no rival.
  const Mesh clear = two_spikes(2.5, 3.5);
  const Extremities on_clear = extremities(clear, tip_distances(clear, 5, anchors), reach);
  std::vector<Eigen::Vector3d> clear_images;
  for (VertexHandle v : clear.vertices()) clear_images.push_back(position(clear, v));
  clear_images[0] = clear_images[3] = position(clear, VertexHandle(5)) + Eigen::Vector3d(0.05, 0.0, 0.0);
  const std::vector<ExtremityAnchor> unambiguous = match_extremities_by_cell(
      {source, on_source, anchors, reach / std::sqrt(surface_area(source))},
      {clear, on_clear, anchors, reach / std::sqrt(surface_area(clear))}, {clear_images, faces}, {}, {});
  ASSERT_EQ(unambiguous.size(), 1u);
  EXPECT_EQ(std::get<AnchorVertex>(unambiguous[0].specs[1].location).index, 3);
  EXPECT_EQ(unambiguous[0].rival_target, -1);
}

// A hand on one face of the octahedron (sqrt(area) 2.63, so tips 0.53 apart are near): the +x
// corner a matched tip (the thumb), a landmark at the wrist, and three unmatched tips. The target
// is the same mesh turned and twice the size; the first map draws every vertex to one point, so
// only the distances can match the tips.
class HandOfTips : public ::testing::Test {
 protected:
  HandOfTips() : mesh(test::subdivided_octahedron(12)), target(mesh), faces(triangles_of(mesh)) {
    const Eigen::Matrix3d turn = Eigen::AngleAxisd(1.0, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    for (VertexHandle v : target.vertices()) target.set_point(v, to_point(2.0 * (turn * position(mesh, v))));
    images.assign(mesh.n_vertices(), Eigen::Vector3d::Zero());
    thumb.specs[0] = {"tip 1", AnchorVertex{0}, "", 0};
    thumb.specs[1] = {"tip 1", AnchorVertex{0}, "", 0};
  }

  int at(double x, double y, double z) const { return test::vertex_at(mesh, Eigen::Vector3d(x, y, z)).idx(); }

  // Template tip -> target tip of each match, in the order made.
  static std::vector<std::pair<int, int>> pairs(const std::vector<ExtremityAnchor>& matched) {
    std::vector<std::pair<int, int>> result;
    for (const ExtremityAnchor& tip : matched)
      result.push_back({std::get<AnchorVertex>(tip.specs[0].location).index,
                        std::get<AnchorVertex>(tip.specs[1].location).index});
    return result;
  }

  const Mesh mesh;
  Mesh target;
  const std::vector<std::array<int, 3>> faces;
  std::vector<Eigen::Vector3d> images;
  ExtremityAnchor thumb;
};

// Tip a lies 0.35 from the thumb and from the wrist landmark, tip b 0.24 and 0.42; tip d 0.35
// from the wrist and from a but 0.71 from the thumb, so it has a matched tip near only once a is
// matched: each is matched with itself, d in the second round.
TEST_F(HandOfTips, AreMatchedByTheirDistancesToTheMatchedTipsAndLandmarks) {
  const int a = at(0.75, 0.0, 0.25), b = at(10.0 / 12, 2.0 / 12, 0.0), d = at(0.5, 0.0, 0.5);
  Extremities on_source, on_target;
  on_source.tips = {a, b, d};
  on_target.tips = {d, b, a};
  const std::vector<int> wrist = {at(0.5, 0.25, 0.25)};
  const std::vector<ExtremityAnchor> matched =
      match_extremities_by_distances({mesh, on_source, wrist, 0.1}, {target, on_target, wrist, 0.1},
                                     {images, faces}, {thumb}, {"tip 2"});
  EXPECT_EQ(pairs(matched), (std::vector<std::pair<int, int>>{{a, a}, {b, b}, {d, d}}));
  ASSERT_EQ(matched.size(), 3u);
  EXPECT_EQ(matched[0].specs[0].name, "tip 2'");
  EXPECT_EQ(matched[1].specs[1].name, "tip 3");

  EXPECT_EQ(matched[2].matched_by, TipMatching::by_distances);

  // Without a matched tip nothing tells the fingers apart.
  EXPECT_TRUE(match_extremities_by_distances({mesh, on_source, wrist, 0.1}, {target, on_target, wrist, 0.1},
                                             {images, faces}, {}, {})
                  .empty());
}

// Tips a and b mirror each other across the plane through the thumb, the wrist landmark and the
// surface's normal there: their distances to both are the same, so distances alone cannot tell
// them apart (an index and a ring fingertip about the middle one), but they lie on opposite sides
// of that plane, a at sine -0.5 and b at +0.5 (worked by hand), on both meshes. Each is matched
// with itself, and never with the other's mirror image; a second landmark off the plane tells them
// apart by distances too.
TEST_F(HandOfTips, MirrorTipsAreToldApartByTheirSideOfTheWristAndThumb) {
  const int a = at(0.75, 0.0, 0.25), b = at(0.75, 0.25, 0.0);
  Extremities both, only_a, only_b;
  both.tips = {a, b};
  only_a.tips = {a};
  only_b.tips = {b};
  const std::vector<int> on_axis = {at(0.5, 0.25, 0.25)};
  EXPECT_EQ(pairs(match_extremities_by_distances({mesh, both, on_axis, 0.1}, {target, both, on_axis, 0.1},
                                                 {images, faces}, {thumb}, {})),
            (std::vector<std::pair<int, int>>{{a, a}, {b, b}}));
  EXPECT_TRUE(match_extremities_by_distances({mesh, only_a, on_axis, 0.1}, {target, only_b, on_axis, 0.1},
                                             {images, faces}, {thumb}, {})
                  .empty());
  EXPECT_EQ(pairs(match_extremities_by_distances({mesh, only_a, on_axis, 0.1}, {target, only_a, on_axis, 0.1},
                                                 {images, faces}, {thumb}, {})),
            (std::vector<std::pair<int, int>>{{a, a}}));
  const std::vector<int> off_axis = {on_axis[0], at(0.5, 0.5, 0.0)};
  EXPECT_EQ(pairs(match_extremities_by_distances({mesh, both, off_axis, 0.1}, {target, both, off_axis, 0.1},
                                                 {images, faces}, {thumb}, {})),
            (std::vector<std::pair<int, int>>{{a, a}, {b, b}}));
}

// Three vertices in a row, r, p and q, 1/12 apart along an edge direction of the face (0.118 on the
// template, 0.236 on the target, under 0.05 of sqrt(area), 0.13 and 0.26): r a landmark (the middle
// fingertip), p and q found tips (the ring and little ones). A pair of the template's p with the
// target's q, both neighbours unmatched, is one finger over: the template's neighbour q lies beyond
// p from the landmark, the target's neighbour p short of q. The pairs one over are p with p (the
// pair's name) and q with q (named anew). A matched tip nearer p than q is passed over for q. A
// pair of p with p, both q's unmatched beyond it, is in place; so is a pair whose only near
// neighbour is matched, or lies farther than a next finger.
TEST_F(HandOfTips, APairWhoseNeighboursLieOnOppositeSidesIsTriedOneOver) {
  const int r = at(6.0 / 12, 3.0 / 12, 3.0 / 12), p = at(7.0 / 12, 2.0 / 12, 3.0 / 12),
            q = at(8.0 / 12, 1.0 / 12, 3.0 / 12);
  Extremities found;
  found.tips = {p, q};
  const std::vector<int> landmark = {r};
  const TipsAndAnchors source{mesh, found, landmark, 0.1};
  const TipsAndAnchors on_target{target, found, landmark, 0.1};
  const auto tip_pair = [](int s, int t, const std::string& name) {
    ExtremityAnchor pair;
    pair.specs[0] = {name, AnchorVertex{s}, "", 0};
    pair.specs[1] = {name, AnchorVertex{t}, "", 0};
    return pair;
  };
  const ExtremityAnchor ring_on_little = tip_pair(p, q, "tip 1");
  const std::optional<std::array<ExtremityAnchor, 2>> over =
      one_over(source, on_target, {images, faces}, ring_on_little, {ring_on_little}, {"tip 2"});
  ASSERT_TRUE(over.has_value());
  EXPECT_EQ(pairs({(*over)[0], (*over)[1]}), (std::vector<std::pair<int, int>>{{p, p}, {q, q}}));
  EXPECT_EQ((*over)[0].specs[0].name, "tip 1");
  EXPECT_EQ((*over)[1].specs[0].name, "tip 2'");
  EXPECT_EQ((*over)[1].specs[1].name, "tip 2'");
  EXPECT_EQ((*over)[0].matched_by, TipMatching::one_over);
  EXPECT_EQ((*over)[1].matched_by, TipMatching::one_over);

  // A matched tip w moved a tenth nearer p on the template than q is: the tip beside p is still q.
  const int w = at(7.0 / 12, 3.0 / 12, 2.0 / 12);
  Mesh nearer_w = mesh;
  nearer_w.set_point(VertexHandle(w),
                     to_point(0.9 * position(mesh, VertexHandle(w)) + 0.1 * position(mesh, VertexHandle(p))));
  Extremities with_matched;
  with_matched.tips = {p, w, q};
  const ExtremityAnchor middle = tip_pair(w, w, "tip 3");
  const std::optional<std::array<ExtremityAnchor, 2>> past_matched =
      one_over({nearer_w, with_matched, landmark, 0.1}, {target, with_matched, landmark, 0.1},
               {images, faces}, ring_on_little, {ring_on_little, middle}, {"tip 2"});
  ASSERT_TRUE(past_matched.has_value());
  EXPECT_EQ(pairs({(*past_matched)[0], (*past_matched)[1]}),
            (std::vector<std::pair<int, int>>{{p, p}, {q, q}}));

  const ExtremityAnchor ring_on_ring = tip_pair(p, p, "tip 1");
  EXPECT_FALSE(one_over(source, on_target, {images, faces}, ring_on_ring, {ring_on_ring}, {}).has_value());
  const ExtremityAnchor little = tip_pair(q, p, "tip 2");  // the target's neighbour matched
  EXPECT_FALSE(
      one_over(source, on_target, {images, faces}, ring_on_little, {ring_on_little, little}, {}).has_value());
  Extremities far;  // the template's next tip two steps beyond p: 0.236, over 0.13
  far.tips = {p, at(9.0 / 12, 0.0, 3.0 / 12)};
  EXPECT_FALSE(
      one_over({mesh, far, landmark, 0.1}, on_target, {images, faces}, ring_on_little, {ring_on_little}, {})
          .has_value());
}

// Two rows of positions, the second with a spurious item between its first two: paired by rank
// every item after it would slide by one; aligned, it is left out and the rest pair exactly.
TEST(AlignRows, LeavesOutASpuriousItemRatherThanSlidingTheRestByOne) {
  const std::vector<double> first = {0.10, 0.20, 0.30};
  const std::vector<double> second = {0.10, 0.15, 0.20, 0.30};
  const auto cost = [&](int i, int j) { return std::abs(first[i] - second[j]); };
  EXPECT_EQ(align_rows(3, 4, cost, 0.02), (std::vector<std::pair<int, int>>{{0, 0}, {1, 2}, {2, 3}}));
  // Rows of one length, the second lacking the last item and with the spurious one: aligning
  // leaves out two items where ranking leaves out none, so it pays only while leaving out is cheap.
  const std::vector<double> lacking = {0.10, 0.15, 0.20};
  const auto lacking_cost = [&](int i, int j) { return std::abs(first[i] - lacking[j]); };
  EXPECT_EQ(align_rows(3, 3, lacking_cost, 0.02), (std::vector<std::pair<int, int>>{{0, 0}, {1, 2}}));
  EXPECT_EQ(align_rows(3, 3, lacking_cost, 1.0), (std::vector<std::pair<int, int>>{{0, 0}, {1, 1}, {2, 2}}));
  // A pair of infinite cost is never made, however dear leaving out is.
  const auto never_first = [&](int i, int j) {
    return i == 0 ? std::numeric_limits<double>::infinity() : lacking_cost(i, j);
  };
  EXPECT_EQ(align_rows(3, 3, never_first, 1.0), (std::vector<std::pair<int, int>>{{1, 1}, {2, 2}}));
  EXPECT_TRUE(align_rows(0, 4, cost, 0.02).empty());
}

// Short tips in a row beside the thumb (the +x corner), through the identity map: the target has
// one more, a bump between the template's first two. The rows pair each short tip with itself and
// leave the bump out.
TEST_F(HandOfTips, ShortTipsInARowBesideAMatchedTipAreAlignedThroughTheMap) {
  const int a = at(0.75, 0.0, 0.25), b = at(10.0 / 12, 2.0 / 12, 0.0), d = at(0.5, 0.0, 0.5);
  const int bump = at(9.0 / 12, 1.0 / 12, 2.0 / 12);  // 0.31 from the thumb: between b (0.24) and a (0.35)
  std::vector<Eigen::Vector3d> identity;
  for (VertexHandle v : mesh.vertices()) identity.push_back(position(mesh, v));
  const Extremities none;
  const std::vector<int> no_anchors;
  const TipsAndAnchors source{mesh, none, no_anchors, 0.1};
  const TipsAndAnchors target{mesh, none, no_anchors, 0.1};
  const std::vector<ExtremityAnchor> rows = match_short_tip_rows(source, {a, b, d}, target, {d, bump, a, b},
                                                                 {identity, faces}, {thumb}, {"tip 2"}, 0.1);
  EXPECT_EQ(pairs(rows), (std::vector<std::pair<int, int>>{{b, b}, {a, a}, {d, d}}));
  ASSERT_EQ(rows.size(), 3u);
  for (const ExtremityAnchor& tip : rows) {
    EXPECT_EQ(tip.matched_by, TipMatching::in_row);
    EXPECT_NEAR(tip.mismatch(), 0.0, 1e-12);
  }
  EXPECT_EQ(rows[0].specs[0].name, "tip 2'");  // names avoid those taken
  // Without a matched tip there is no row.
  EXPECT_TRUE(match_short_tip_rows(source, {a, b, d}, target, {d, bump, a, b}, {identity, faces}, {}, {}, 0.1)
                  .empty());
}

// The bundled man (SMPL's vertex order) as the template, and moved rigidly as the target: its
// true map is the identity. The first map moves the left forefoot's images 2.5 cm sideways, as FAUST
// first maps turned feet by a toe, and its tip (3306) was matched with the toe beside its own
// (3229). The rigid fit lays the forefoot back, and pairs the tip and the toes of its row each with
// itself, the tip keeping its name. (Fitted from the first map alone, the forefoot settles a toe
// over and the test fails: the fits started from each of the target's toes find the right one.)
class TurnedForefoot : public ::testing::Test {
 protected:
  TurnedForefoot()
      : mesh(test::load(test::data_path("human_man.obj"))), target(mesh), faces(triangles_of(mesh)) {
    const Eigen::Matrix3d turn =
        Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    const Eigen::Vector3d shift(0.3, -0.2, 0.5);
    for (VertexHandle v : target.vertices()) target.set_point(v, to_point(turn * position(mesh, v) + shift));
    const Eigen::Vector3d toe = position(mesh, VertexHandle(3306));
    for (VertexHandle v : mesh.vertices()) {
      const Eigen::Vector3d p = position(mesh, v);
      const Eigen::Vector3d sideways =
          (p - toe).norm() < 0.15 ? Eigen::Vector3d(0.025, 0.0, 0.0) : Eigen::Vector3d::Zero();
      images.push_back(turn * (p + sideways) + shift);
    }
    tip.specs[0] = {"tip 1", AnchorVertex{3306}, "", 0};
    tip.specs[1] = {"tip 1", AnchorVertex{3229}, "", 0};
  }

  const Mesh mesh;
  Mesh target;
  const std::vector<std::array<int, 3>> faces;
  std::vector<Eigen::Vector3d> images;
  ExtremityAnchor tip;
  const std::vector<int> toes = {3220, 3306, 3229, 3225, 3360, 3295};
  const Extremities none;
  const std::vector<int> no_anchors;
};

TEST_F(TurnedForefoot, TheRigidFitPairsEachToeWithItself) {
  const std::vector<FittedRow> rows =
      fit_tip_rows({mesh, none, no_anchors, 0.025}, toes, {target, none, no_anchors, 0.025}, toes,
                   {images, faces}, {tip}, {"tip 2"}, ClosestPointIndex(target));
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].tip, 0);
  EXPECT_EQ(rows[0].source.front(), 3306);
  EXPECT_EQ(rows[0].target.front(), 3229);
  ASSERT_EQ(rows[0].pairs.size(), toes.size());
  for (const ExtremityAnchor& pair : rows[0].pairs) {
    EXPECT_EQ(std::get<AnchorVertex>(pair.specs[0].location).index,
              std::get<AnchorVertex>(pair.specs[1].location).index);
    EXPECT_EQ(pair.specs[0].name, pair.specs[1].name);
  }
  EXPECT_EQ(rows[0].pairs[0].specs[0].name, "tip 1");  // the tip, paired anew
  EXPECT_EQ(std::get<AnchorVertex>(rows[0].pairs[0].specs[0].location).index, 3306);
  EXPECT_EQ(rows[0].pairs[1].matched_by, TipMatching::in_row);
  EXPECT_EQ(rows[0].pairs[1].specs[0].name, "tip 2'");  // names avoid those taken
  // Aligned through the first map instead, the row's toes lie beside the wrong tip: not every toe
  // is paired with itself.
  const std::vector<ExtremityAnchor> aligned =
      match_short_tip_rows({mesh, none, no_anchors, 0.025}, toes, {target, none, no_anchors, 0.025}, toes,
                           {images, faces}, {tip}, {}, 0.15);
  EXPECT_TRUE(std::any_of(aligned.begin(), aligned.end(), [](const ExtremityAnchor& pair) {
    return std::get<AnchorVertex>(pair.specs[0].location).index !=
           std::get<AnchorVertex>(pair.specs[1].location).index;
  }));
}

// A target whose toes are bent up by 30 degrees about the ball of the foot (5 cm behind the tip)
// lies farther than kFitFarthest from any rigid motion of the template's forefoot: the fit does not
// hold (as on a hand whose fingers bend), and no row is paired by it.
TEST_F(TurnedForefoot, AForefootNoRigidMotionLaysOntoTheTargetIsNotPairedByIt) {
  Mesh bent = mesh;
  const Eigen::Vector3d ball = position(mesh, VertexHandle(3306)) - Eigen::Vector3d(0.0, 0.0, 0.05);
  const Eigen::Matrix3d bend = Eigen::AngleAxisd(-0.52, Eigen::Vector3d::UnitX()).toRotationMatrix();
  for (VertexHandle v : bent.vertices()) {
    const Eigen::Vector3d p = position(mesh, v);
    if (p.z() > ball.z() && std::abs(p.x() - ball.x()) < 0.1)
      bent.set_point(v, to_point(ball + bend * (p - ball)));
  }
  std::vector<Eigen::Vector3d> identity;
  for (VertexHandle v : bent.vertices()) identity.push_back(position(bent, v));
  EXPECT_TRUE(fit_tip_rows({mesh, none, no_anchors, 0.025}, toes, {bent, none, no_anchors, 0.025}, toes,
                           {identity, faces}, {tip}, {}, ClosestPointIndex(bent))
                  .empty());
}

}  // namespace
}  // namespace xparam
