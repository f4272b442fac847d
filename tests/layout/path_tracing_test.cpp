// Path tracing and refinement on hand-checkable meshes: wedges, shortest paths, blocked
// vertices, and the splits that give paths room.
#include "layout/path_tracing.h"
#include "core/provenance.h"
#include "layout/refinement.h"
#include "layout/vertex_labels.h"
#include "layout_fixtures.h"
#include "support/test_data.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace xparam {
namespace {

using test::vertex_at;

constexpr int kOctahedronDivisions = 4;

// An octahedron subdivision with the six corners as anchors and no chains yet.
Layout bare_octahedron() {
  Layout layout;
  layout.n_anchors = 6;
  for (LayoutSide& side : layout.sides) {
    side.mesh = test::subdivided_octahedron(kOctahedronDivisions);
    for (int k = 0; k < 6; ++k) side.anchor_vertices.emplace_back(k);
  }
  return layout;
}

// Add layout edge a -> b to side 0 with the given chain.
void add_chain(Layout& layout, int a, int b, std::vector<VertexHandle> chain) {
  layout.edges.push_back({{a, b}});
  layout.sides[0].chains.push_back(std::move(chain));
}

TEST(PathTracing, ShortestPathBetweenFreeAnchorsIsTheOctahedronEdge) {
  const Layout layout = bare_octahedron();
  const LayoutSide& side = layout.sides[0];
  const VertexLabels labels = label_vertices(layout, 0);
  TraceScratch scratch;
  const auto first = wedge_vertices(side, labels, corner_wedge(layout, 0, 0, -1));
  const auto last = wedge_vertices(side, labels, corner_wedge(layout, 0, 2, -1));
  EXPECT_EQ(first.size(), 4u);  // +x has valence 4 on the subdivision
  const TracedPath path =
      trace_path(side.mesh, labels, VertexHandle(0), first, VertexHandle(2), last, scratch);
  ASSERT_TRUE(path.found());
  EXPECT_NEAR(path.length, std::sqrt(2.0), 1e-12);
  ASSERT_EQ(path.vertices.size(), static_cast<std::size_t>(kOctahedronDivisions + 1));
  for (int t = 0; t <= kOctahedronDivisions; ++t) {
    const Eigen::Vector3d expected =
        Eigen::Vector3d(1, 0, 0) + Eigen::Vector3d(-1, 1, 0) * t / kOctahedronDivisions;
    EXPECT_LT((position(side.mesh, path.vertices[t]) - expected).norm(), 1e-12) << "vertex " << t;
  }
}

TEST(PathTracing, WedgesFollowTheCounterClockwiseRotation) {
  Layout layout = bare_octahedron();
  const Mesh& mesh = layout.sides[0].mesh;
  // Chains +x -> +y and +x -> -y along the octahedron edges split the ring of +x in two.
  std::vector<VertexHandle> to_py, to_ny;
  for (int t = 0; t <= kOctahedronDivisions; ++t) {
    to_py.push_back(
        vertex_at(mesh, Eigen::Vector3d(1, 0, 0) + Eigen::Vector3d(-1, 1, 0) * t / kOctahedronDivisions));
    to_ny.push_back(
        vertex_at(mesh, Eigen::Vector3d(1, 0, 0) + Eigen::Vector3d(-1, -1, 0) * t / kOctahedronDivisions));
  }
  add_chain(layout, 0, 2, to_py);
  add_chain(layout, 0, 3, to_ny);
  const LayoutSide& side = layout.sides[0];
  const VertexLabels labels = label_vertices(layout, 0);
  // Seen from outside (+x), counter-clockwise from +y comes +z: the wedge after halfedge 0
  // holds the neighbour towards +z, the wedge after halfedge 2 the one towards -z.
  const auto upper = wedge_vertices(side, labels, corner_wedge(layout, 0, 0, 0));
  const auto lower = wedge_vertices(side, labels, corner_wedge(layout, 0, 0, 2));
  ASSERT_EQ(upper.size(), 1u);
  ASSERT_EQ(lower.size(), 1u);
  EXPECT_EQ(upper[0], vertex_at(mesh, Eigen::Vector3d(0.75, 0, 0.25)));
  EXPECT_EQ(lower[0], vertex_at(mesh, Eigen::Vector3d(0.75, 0, -0.25)));
  EXPECT_EQ(wedge_of(side, labels, mesh.find_halfedge(VertexHandle(0), upper[0])), 0);
  EXPECT_EQ(wedge_of(side, labels, mesh.find_halfedge(VertexHandle(0), lower[0])), 2);

  // Leaving +x through the upper wedge, the path to -x stays in the upper half (z >= 0).
  TraceScratch scratch;
  const auto at_nx = wedge_vertices(side, labels, corner_wedge(layout, 0, 1, -1));
  const TracedPath path =
      trace_path(side.mesh, labels, VertexHandle(0), upper, VertexHandle(1), at_nx, scratch);
  ASSERT_TRUE(path.found());
  for (VertexHandle v : path.vertices) EXPECT_GE(position(mesh, v).z(), 0.0);
  for (std::size_t i = 1; i + 1 < path.vertices.size(); ++i) EXPECT_FALSE(labels.blocked(path.vertices[i]));
  // The straight way over the +z pole is 2 sqrt(2); nothing in the upper half is shorter.
  EXPECT_NEAR(path.length, 2.0 * std::sqrt(2.0), 1e-12);
}

TEST(PathTracing, NoPathWhenTheWedgeIsWalledIn) {
  Layout layout = bare_octahedron();
  const Mesh& mesh = layout.sides[0].mesh;
  // Block the whole ring x = 0.5 around +x by hand: no path can leave the cap.
  VertexLabels labels = label_vertices(layout, 0);
  for (VertexHandle v : mesh.vertices()) {
    const Eigen::Vector3d p = position(mesh, v);
    if (std::abs(p.x() - 0.5) < 1e-12) labels.edge[v.idx()] = 0;
  }
  TraceScratch scratch;
  const auto first = wedge_vertices(layout.sides[0], labels, corner_wedge(layout, 0, 0, -1));
  const auto last = wedge_vertices(layout.sides[0], labels, corner_wedge(layout, 0, 1, -1));
  EXPECT_FALSE(trace_path(mesh, labels, VertexHandle(0), first, VertexHandle(1), last, scratch).found());
}

TEST(Refinement, SplitsTheEdgeBetweenNeighbouringAnchors) {
  Mesh input = test::load(test::data_path("spot_low_resolution.obj"));
  Layout layout;
  layout.n_anchors = 2;
  LayoutSide& side = layout.sides[0];
  side.mesh = input;
  const VertexHandle a(10);
  const VertexHandle b = *input.vv_range(a).begin();
  side.anchor_vertices = {a, b};
  VertexLabels labels = label_vertices(layout, 0);
  EXPECT_EQ(make_room(side, labels, side.anchor_vertices), 1);
  EXPECT_FALSE(side.mesh.find_halfedge(a, b).is_valid());
  const VertexHandle m(static_cast<int>(input.n_vertices()));
  EXPECT_TRUE(side.mesh.find_halfedge(a, m).is_valid());
  EXPECT_TRUE(side.mesh.find_halfedge(b, m).is_valid());
  EXPECT_LT((position(side.mesh, m) - 0.5 * (position(input, a) + position(input, b))).norm(), 1e-15);
  EXPECT_FALSE(labels.blocked(m));
  // The four faces around the midpoint lie in the two input faces beside the old edge.
  const HalfedgeHandle old = input.find_halfedge(a, b);
  const std::set<int> beside = {input.face_handle(old).idx(), input.opposite_face_handle(old).idx()};
  for (FaceHandle f : side.mesh.vf_range(m)) EXPECT_TRUE(beside.count(input_face(side.mesh, f))) << f.idx();
  test::expect_provenance(side.mesh, input, "midpoint");
  // Nothing left to split.
  EXPECT_EQ(make_room(side, labels, side.anchor_vertices), 0);
}

TEST(Refinement, SplitsEdgesBetweenTwoChainsButNotChainEdges) {
  Layout layout = bare_octahedron();
  const Mesh input = layout.sides[0].mesh;
  // Two chains +x -> +y in face (+x, +y, +z): along the octahedron edge (weights (4-t, t, 0)/4)
  // and one lattice row inside ((3-t, t, 1)/4 between the anchors).
  std::vector<VertexHandle> edge_chain, row_chain = {VertexHandle(0)};
  for (int t = 0; t <= kOctahedronDivisions; ++t)
    edge_chain.push_back(vertex_at(input, Eigen::Vector3d(4 - t, t, 0) / kOctahedronDivisions));
  for (int t = 0; t <= 3; ++t)
    row_chain.push_back(vertex_at(input, Eigen::Vector3d(3 - t, t, 1) / kOctahedronDivisions));
  row_chain.push_back(VertexHandle(2));
  add_chain(layout, 0, 2, edge_chain);
  add_chain(layout, 0, 2, row_chain);
  VertexLabels labels = label_vertices(layout, 0);
  // Rungs between the rows: row vertex (3-t, t, 1) touches (4-t, t, 0) and (3-t, t+1, 0); of
  // these 8, the two at the anchors are edges of the row chain, the other 6 are split.
  EXPECT_EQ(make_room(layout.sides[0], labels, edge_chain), 6);
  EXPECT_EQ(layout.sides[0].mesh.n_vertices(), input.n_vertices() + 6);
  for (const auto& chain : layout.sides[0].chains) {
    for (std::size_t i = 0; i + 1 < chain.size(); ++i) {
      EXPECT_TRUE(layout.sides[0].mesh.find_halfedge(chain[i], chain[i + 1]).is_valid());
    }
  }
  test::expect_provenance(layout.sides[0].mesh, input, "rungs");
  EXPECT_EQ(make_room(layout.sides[0], labels, row_chain), 0);
}

}  // namespace
}  // namespace xparam
