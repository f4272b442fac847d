#include "core/anchor_placement.h"

#include "core/closest_point.h"
#include "core/errors.h"
#include "core/provenance.h"
#include "support/expect_error.h"
#include "support/small_meshes.h"
#include "support/test_data.h"

#include <gtest/gtest.h>
#include <OpenMesh/Core/IO/MeshIO.hh>

#include <limits>
#include <random>
#include <set>

namespace xparam {
namespace {

Mesh load(const std::string& name) {
  Mesh mesh;
  OpenMesh::IO::Options options;
  EXPECT_TRUE(OpenMesh::IO::read_mesh(mesh, test::data_path(name).string(), options)) << name;
  return mesh;
}

Mesh with_provenance(const Mesh& input) {
  Mesh refined = input;
  init_provenance(refined);
  return refined;
}

AnchorSet one_anchor(std::variant<AnchorVertex, AnchorPosition, SurfacePoint> location) {
  return {"t.json", {{"A", location, "t.json", 3}}};
}

// Every refined face lies in the input face it claims: its centroid, located on the input
// mesh, is the centroid itself, with barycentrics inside the triangle.
void expect_provenance_consistent(const Mesh& refined, const Mesh& input) {
  for (FaceHandle f : refined.faces()) {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (VertexHandle v : refined.fv_range(f)) centroid += position(refined, v) / 3.0;
    Eigen::Vector3d corners[3];
    int k = 0;
    for (VertexHandle v : input.fv_range(input.face_handle(input_face(refined, f))))
      corners[k++] = position(input, v);
    const Eigen::Vector3d bary = barycentric(centroid, corners[0], corners[1], corners[2]);
    ASSERT_GT(bary.minCoeff(), -1e-9) << "refined face " << f.idx();
    const SurfacePoint located = to_input_point(refined, input, f, centroid);
    ASSERT_LT((position(input, located) - centroid).norm(), 1e-12) << "refined face " << f.idx();
  }
}

// ----------------------------------------------------------------------------------------
// Nearest points.

TEST(ClosestPoint, TriangleRegionsByHand) {
  const Eigen::Vector3d a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
  // Above the interior: straight down.
  TrianglePoint p = closest_point_on_triangle({0.5, 0.25, 3}, a, b, c);
  EXPECT_EQ(p.point, Eigen::Vector3d(0.5, 0.25, 0));
  EXPECT_NEAR((p.bary - Eigen::Vector3d(0.625, 0.25, 0.125)).norm(), 0.0, 1e-15);
  // Beyond corner b.
  p = closest_point_on_triangle({3, -1, 1}, a, b, c);
  EXPECT_EQ(p.point, b);
  EXPECT_EQ(p.bary, Eigen::Vector3d(0, 1, 0));
  // Beside edge ab: foot at x = 1.5.
  p = closest_point_on_triangle({1.5, -2, 0}, a, b, c);
  EXPECT_EQ(p.point, Eigen::Vector3d(1.5, 0, 0));
  EXPECT_EQ(p.bary, Eigen::Vector3d(0.25, 0.75, 0));
  // Beside the hypotenuse bc: (2, 2, 0) projects to its midpoint.
  p = closest_point_on_triangle({2, 2, 0}, a, b, c);
  EXPECT_NEAR((p.point - Eigen::Vector3d(1, 1, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((p.bary - Eigen::Vector3d(0, 0.5, 0.5)).norm(), 0.0, 1e-15);
  // A degenerate (collinear) triangle still answers with its nearest edge point.
  p = closest_point_on_triangle({1, 1, 0}, a, b, Eigen::Vector3d(1, 0, 0));
  EXPECT_EQ(p.point, Eigen::Vector3d(1, 0, 0));
}

TEST(ClosestPoint, TreeEqualsBruteForceOnRealMeshes) {
  for (const std::string name :
       {"spot_low_resolution.obj", "human_man.obj", "bob_small.ply", "cat_head.obj"}) {
    const Mesh mesh = load(name);
    const ClosestPointIndex index(mesh);
    ASSERT_EQ(index.n_faces(), static_cast<int>(mesh.n_faces()));
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d hi = -lo;
    for (VertexHandle v : mesh.vertices()) {
      lo = lo.cwiseMin(position(mesh, v));
      hi = hi.cwiseMax(position(mesh, v));
    }
    std::mt19937 random(7);
    std::uniform_real_distribution<double> unit(-0.2, 1.2);
    for (int query = 0; query < 200; ++query) {
      const Eigen::Vector3d p =
          lo + (hi - lo).cwiseProduct(Eigen::Vector3d(unit(random), unit(random), unit(random)));
      double best = std::numeric_limits<double>::infinity();
      int best_face = -1;
      for (FaceHandle f : mesh.faces()) {
        Eigen::Vector3d t[3];
        int k = 0;
        for (VertexHandle v : mesh.fv_range(f)) t[k++] = position(mesh, v);
        const double d = (closest_point_on_triangle(p, t[0], t[1], t[2]).point - p).squaredNorm();
        if (d < best) {
          best = d;
          best_face = f.idx();
        }
      }
      const ClosestPoint found = index.closest(p);
      ASSERT_EQ(found.location.face, best_face) << name << " query " << query;
      ASSERT_EQ(found.distance, std::sqrt(best)) << name << " query " << query;
      ASSERT_LT((position(mesh, found.location) - found.point).norm(), 1e-12);
    }
  }
}

// ----------------------------------------------------------------------------------------
// Placement by hand on the tetrahedron.

TEST(AnchorPlacement, VertexIndexIsThatVertex) {
  const Mesh input = test::tetrahedron_mesh();
  Mesh mesh = with_provenance(input);
  const PlacedAnchors placed = place_anchors(mesh, input, one_anchor(AnchorVertex{3}));
  ASSERT_EQ(placed.anchors.size(), 1u);
  EXPECT_EQ(placed.anchors[0].vertex.idx(), 3);
  EXPECT_EQ(placed.anchors[0].insertion, AnchorInsertion::ExistingVertex);
  EXPECT_EQ(placed.anchors[0].snap_distance, 0.0);
  EXPECT_EQ(placed.vertices_inserted, 0);
  EXPECT_EQ(mesh.n_vertices(), 4u);
  EXPECT_NEAR((position(input, placed.anchors[0].input_point) - Eigen::Vector3d(0, 0, 1)).norm(), 0.0, 1e-15);
  EXPECT_DOUBLE_EQ(placed.bbox_diagonal, std::sqrt(3.0));
}

TEST(AnchorPlacement, PositionOnAnEdgeSplitsTheEdge) {
  const Mesh input = test::tetrahedron_mesh();
  Mesh mesh = with_provenance(input);
  // 0.3 above edge (a, b) = the x axis, on the outside of both faces beside it (y < 0, z < 0).
  const Eigen::Vector3d on_edge(0.25, 0.0, 0.0);
  const PlacedAnchors placed =
      place_anchors(mesh, input, one_anchor(AnchorPosition{on_edge + Eigen::Vector3d(0, -0.3, -0.4)}));
  const PlacedAnchor& anchor = placed.anchors[0];
  EXPECT_EQ(anchor.insertion, AnchorInsertion::EdgeSplit);
  EXPECT_DOUBLE_EQ(anchor.snap_distance, 0.5);
  EXPECT_EQ(position(mesh, anchor.vertex), on_edge);
  EXPECT_EQ(mesh.n_vertices(), 5u);
  EXPECT_EQ(mesh.n_faces(), 6u);
  EXPECT_EQ(mesh.valence(anchor.vertex), 4u);
  EXPECT_NEAR((position(input, anchor.input_point) - on_edge).norm(), 0.0, 1e-15);
  expect_provenance_consistent(mesh, input);
  // 0.5 is 29% of the diagonal: far above the 1% warning threshold.
  ASSERT_EQ(placed.warnings.size(), 1u);
  EXPECT_NE(placed.warnings[0].find("t.json:3: anchor \"A\" is 0.5 from the surface"), std::string::npos)
      << placed.warnings[0];
}

TEST(AnchorPlacement, PositionInsideAFaceSplitsTheFace) {
  const Mesh input = test::tetrahedron_mesh();
  Mesh mesh = with_provenance(input);
  const Eigen::Vector3d inside(0.2, 0.3, 0.0);  // face 0, z = 0
  const PlacedAnchors placed =
      place_anchors(mesh, input, one_anchor(AnchorPosition{inside + Eigen::Vector3d(0, 0, -1e-3)}));
  const PlacedAnchor& anchor = placed.anchors[0];
  EXPECT_EQ(anchor.insertion, AnchorInsertion::FaceSplit);
  EXPECT_DOUBLE_EQ(anchor.snap_distance, 1e-3);
  EXPECT_TRUE(placed.warnings.empty());
  EXPECT_NEAR((position(mesh, anchor.vertex) - inside).norm(), 0.0, 1e-15);
  EXPECT_EQ(mesh.n_faces(), 6u);
  EXPECT_EQ(mesh.valence(anchor.vertex), 3u);
  EXPECT_EQ(anchor.input_point.face, 0);
  EXPECT_NEAR((position(input, anchor.input_point) - inside).norm(), 0.0, 1e-15);
  expect_provenance_consistent(mesh, input);
}

TEST(AnchorPlacement, PositionWithinToleranceOfAVertexIsThatVertex) {
  const Mesh input = test::tetrahedron_mesh();
  Mesh mesh = with_provenance(input);
  const double diagonal = std::sqrt(3.0);
  const PlacedAnchors placed =
      place_anchors(mesh, input, one_anchor(AnchorPosition{{1.0 - 0.5e-6 * diagonal, 0.0, 0.0}}));
  EXPECT_EQ(placed.anchors[0].vertex.idx(), 1);
  EXPECT_EQ(placed.anchors[0].insertion, AnchorInsertion::ExistingVertex);
  EXPECT_EQ(mesh.n_vertices(), 4u);
  // Just beyond the tolerance it is an edge split instead.
  const PlacedAnchors split =
      place_anchors(mesh, input, one_anchor(AnchorPosition{{1.0 - 2e-6 * diagonal, 0.0, 0.0}}));
  EXPECT_EQ(split.anchors[0].insertion, AnchorInsertion::EdgeSplit);
}

TEST(AnchorPlacement, FaceAndBarycentricsInsertExactly) {
  const Mesh input = test::tetrahedron_mesh();
  Mesh mesh = with_provenance(input);
  // Face 1 = (a, b, d): (0.2, 0.3, 0.5) is (0.3, 0, 0.5); (0, 0.5, 0.5) is the midpoint of
  // edge (b, d); (0, 0, 1) is d itself.
  const AnchorSet set{"f.json",
                      {{"inside", SurfacePoint{1, {0.2, 0.3, 0.5}}, "f.json", 2},
                       {"edge", SurfacePoint{1, {0.0, 0.5, 0.5}}, "f.json", 3},
                       {"corner", SurfacePoint{1, {0.0, 0.0, 1.0}}, "f.json", 4}}};
  const PlacedAnchors placed = place_anchors(mesh, input, set);
  ASSERT_EQ(placed.anchors.size(), 3u);
  EXPECT_EQ(placed.anchors[0].insertion, AnchorInsertion::FaceSplit);
  EXPECT_NEAR((position(mesh, placed.anchors[0].vertex) - Eigen::Vector3d(0.3, 0, 0.5)).norm(), 0.0, 1e-15);
  EXPECT_EQ(placed.anchors[1].insertion, AnchorInsertion::EdgeSplit);
  EXPECT_NEAR((position(mesh, placed.anchors[1].vertex) - Eigen::Vector3d(0.5, 0, 0.5)).norm(), 0.0, 1e-15);
  EXPECT_EQ(placed.anchors[2].insertion, AnchorInsertion::ExistingVertex);
  EXPECT_EQ(placed.anchors[2].vertex.idx(), 3);
  EXPECT_EQ(placed.vertices_inserted, 2);
  EXPECT_EQ(mesh.n_vertices(), 6u);
  for (const PlacedAnchor& anchor : placed.anchors) EXPECT_EQ(anchor.snap_distance, 0.0);
  // The edge (b, d) lies between input faces 1 and 2; its split vertex is found on both.
  for (FaceHandle f : mesh.vf_range(placed.anchors[1].vertex)) {
    const SurfacePoint p = to_input_point(mesh, input, f, position(mesh, placed.anchors[1].vertex));
    EXPECT_TRUE(p.face == 1 || p.face == 2);
    EXPECT_NEAR((position(input, p) - Eigen::Vector3d(0.5, 0, 0.5)).norm(), 0.0, 1e-15);
  }
  expect_provenance_consistent(mesh, input);
}

TEST(AnchorPlacement, LaterAnchorsFindTheirPieceOfAnAlreadySplitFace) {
  const Mesh input = test::tetrahedron_mesh();
  Mesh mesh = with_provenance(input);
  // Three points in face 0 (z = 0), then one on the edge between the first two splits' pieces.
  const std::vector<Eigen::Vector3d> points = {{0.2, 0.2, 0}, {0.1, 0.6, 0}, {0.6, 0.1, 0}, {0.15, 0.4, 0}};
  AnchorSet set{"p.txt", {}};
  for (int i = 0; i < static_cast<int>(points.size()); ++i) {
    set.anchors.push_back(
        {std::string("p").append(std::to_string(i)), AnchorPosition{points[i]}, "p.txt", i + 1});
  }
  const PlacedAnchors placed = place_anchors(mesh, input, set);
  for (int i = 0; i < static_cast<int>(points.size()); ++i) {
    EXPECT_NEAR((position(mesh, placed.anchors[i].vertex) - points[i]).norm(), 0.0, 1e-15) << i;
    EXPECT_EQ(placed.anchors[i].input_point.face, 0);
  }
  // (0.15, 0.4) lies on the spoke from (0.2, 0.2) to (0.1, 0.6): an edge split of a refined edge.
  EXPECT_EQ(placed.anchors[3].insertion, AnchorInsertion::EdgeSplit);
  EXPECT_EQ(mesh.n_vertices(), 8u);
  expect_provenance_consistent(mesh, input);
}

TEST(AnchorPlacement, TwoAnchorsOnOneVertexNameBothAndLeaveTheMeshAlone) {
  const Mesh input = test::tetrahedron_mesh();
  Mesh mesh = with_provenance(input);
  const AnchorSet set{"s.pp",
                      {{"first", AnchorPosition{{0.2, 0.3, 0.0}}, "s.pp", 4},
                       {"second", AnchorPosition{{0.2, 0.3, 1e-9}}, "s.pp", 5}}};
  const std::string message = test::error_message_of([&] { place_anchors(mesh, input, set); });
  EXPECT_NE(
      message.find("s.pp:5: anchor \"second\": lands on the same vertex (4) as anchor \"first\" (s.pp:4)"),
      std::string::npos)
      << message;
  EXPECT_EQ(mesh.n_vertices(), 4u);
  EXPECT_EQ(mesh.n_faces(), 4u);
}

TEST(AnchorPlacement, OutOfRangeAndInvalidAnchorsAreInputErrors) {
  const Mesh input = test::tetrahedron_mesh();
  Mesh mesh = with_provenance(input);
  EXPECT_EQ(test::error_message_of([&] { place_anchors(mesh, input, one_anchor(AnchorVertex{4})); }),
            "t.json:3: anchor \"A\": vertex index 4 out of range (the mesh has 4 vertices)");
  EXPECT_EQ(test::error_message_of([&] {
              place_anchors(mesh, input, one_anchor(SurfacePoint{4, {1, 0, 0}}));
            }),
            "t.json:3: anchor \"A\": face 4 out of range (the mesh has 4 faces)");
  EXPECT_NE(test::error_message_of([&] {
              place_anchors(mesh, input, one_anchor(SurfacePoint{0, {0.5, 0.5, 0.5}}));
            }).find("barycentric coordinates sum to 1.5"),
            std::string::npos);
  EXPECT_NE(test::error_message_of([&] {
              place_anchors(mesh, input, one_anchor(SurfacePoint{0, {-0.5, 1.0, 0.5}}));
            }).find("negative"),
            std::string::npos);
  EXPECT_NE(test::error_message_of([&] {
              place_anchors(mesh, input, one_anchor(AnchorVertex{-1}));
            }).find("negative vertex index"),
            std::string::npos);
  EXPECT_EQ(mesh.n_vertices(), 4u);
}

TEST(AnchorPlacement, VertexIndicesReferToTheInputEvenAfterRefinement) {
  const Mesh input = test::tetrahedron_mesh();
  Mesh mesh = with_provenance(input);
  split_face_keeping_provenance(mesh, mesh.face_handle(0), {0.2, 0.3, 0.0});
  ASSERT_EQ(mesh.n_vertices(), 5u);
  // Vertex 4 exists in the refined mesh but not in the input.
  EXPECT_NE(test::error_message_of([&] {
              place_anchors(mesh, input, one_anchor(AnchorVertex{4}));
            }).find("out of range"),
            std::string::npos);
}

// ----------------------------------------------------------------------------------------
// Placement on real meshes.

TEST(AnchorPlacement, ManyRandomSurfacePointsOnRealMeshes) {
  for (const std::string name : {"spot_low_resolution.obj", "fox.ply", "cat_head.obj", "bob_small.ply"}) {
    const Mesh input = load(name);
    Mesh mesh = with_provenance(input);
    const int euler_before = static_cast<int>(input.n_vertices()) - static_cast<int>(input.n_edges()) +
                             static_cast<int>(input.n_faces());
    std::mt19937 random(11);
    std::uniform_int_distribution<int> face(0, static_cast<int>(input.n_faces()) - 1);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    AnchorSet set{name, {}};
    std::vector<Eigen::Vector3d> targets;
    for (int i = 0; i < 60; ++i) {
      const std::string anchor_name = std::string("a").append(std::to_string(i));
      if (i % 15 == 0) {
        // A vertex given by its position (distinct vertices, so no two anchors share one).
        targets.push_back(position(input, input.vertex_handle(i)));
        set.anchors.push_back({anchor_name, AnchorPosition{targets.back()}, name, i + 1});
        continue;
      }
      Eigen::Vector3d bary(unit(random), unit(random), unit(random));
      if (i % 10 == 0) bary[i % 3] = 0.0;  // on an edge
      const SurfacePoint point{face(random), bary / bary.sum()};
      targets.push_back(position(input, point));
      // Alternate the kinds: face + barycentrics, and the same place as a 3-D position.
      if (i % 2 == 0) {
        set.anchors.push_back({anchor_name, point, name, i + 1});
      } else {
        set.anchors.push_back({anchor_name, AnchorPosition{targets.back()}, name, i + 1});
      }
    }
    const PlacedAnchors placed = place_anchors(mesh, input, set);
    ASSERT_EQ(placed.anchors.size(), targets.size());
    std::set<int> vertices;
    int existing = 0;
    for (int i = 0; i < static_cast<int>(targets.size()); ++i) {
      const PlacedAnchor& anchor = placed.anchors[i];
      vertices.insert(anchor.vertex.idx());
      existing += anchor.insertion == AnchorInsertion::ExistingVertex;
      EXPECT_LT((position(mesh, anchor.vertex) - targets[i]).norm(), 1e-12) << name << " anchor " << i;
      EXPECT_LT((position(input, anchor.input_point) - targets[i]).norm(), 1e-12) << name << " anchor " << i;
      EXPECT_LT(anchor.snap_distance, 1e-12);
    }
    EXPECT_EQ(existing, 4) << name;  // exactly the four vertex positions
    EXPECT_EQ(vertices.size(), targets.size()) << name;
    EXPECT_EQ(static_cast<int>(mesh.n_vertices()),
              static_cast<int>(input.n_vertices()) + placed.vertices_inserted);
    const int euler_after = static_cast<int>(mesh.n_vertices()) - static_cast<int>(mesh.n_edges()) +
                            static_cast<int>(mesh.n_faces());
    EXPECT_EQ(euler_after, euler_before) << name;
    for (VertexHandle v : input.vertices()) ASSERT_EQ(mesh.point(v), input.point(v));  // nothing moved
    expect_provenance_consistent(mesh, input);
  }
}

// A caller that places anchors on one mesh again and again gives its nearest-point index; the
// anchors land where the placer's own index puts them.
TEST(AnchorPlacement, PositionsSnapThroughTheCallersIndexAsThroughItsOwn) {
  const Mesh input = load("spot_low_resolution.obj");
  std::mt19937 random(5);
  std::uniform_int_distribution<int> vertex(0, static_cast<int>(input.n_vertices()) - 1);
  std::normal_distribution<double> off(0.0, 0.01);
  AnchorSet set{"spot", {}};
  for (int i = 0; i < 20; ++i) {
    const Eigen::Vector3d near = position(input, input.vertex_handle(vertex(random)));
    set.anchors.push_back({"a" + std::to_string(i),
                           AnchorPosition{near + Eigen::Vector3d(off(random), off(random), off(random))},
                           "spot", i + 1});
  }
  ASSERT_TRUE(has_position_anchor(set));
  EXPECT_FALSE(has_position_anchor(one_anchor(AnchorVertex{3})));
  Mesh own = with_provenance(input);
  Mesh given = with_provenance(input);
  const ClosestPointIndex index(input);
  const PlacedAnchors by_own = place_anchors(own, input, set);
  const PlacedAnchors by_given = place_anchors(given, input, set, {}, &index);
  ASSERT_EQ(by_given.anchors.size(), by_own.anchors.size());
  for (std::size_t i = 0; i < by_own.anchors.size(); ++i) {
    EXPECT_GT(by_own.anchors[i].snap_distance, 0.0) << i;
    EXPECT_EQ(by_given.anchors[i].snap_distance, by_own.anchors[i].snap_distance) << i;
    EXPECT_EQ(by_given.anchors[i].vertex, by_own.anchors[i].vertex) << i;
    EXPECT_EQ(position(given, by_given.anchors[i].vertex), position(own, by_own.anchors[i].vertex)) << i;
  }
  EXPECT_EQ(given.n_vertices(), own.n_vertices());
}

}  // namespace
}  // namespace xparam
