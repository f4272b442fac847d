#include "geodesic/straighten_path.h"

#include "core/errors.h"
#include "core/provenance.h"
#include "geodesic/locally_shortest.h"
#include "geodesic/test_meshes.h"
#include "geodesic/vertex_fan.h"
#include "support/test_data.h"

#include <gtest/gtest.h>

#include <set>

namespace xparam {
namespace {

using test::grid_vertex;
using test::grid_walk;

std::vector<bool> whole_mesh(const Mesh& mesh) { return std::vector<bool>(mesh.n_faces(), true); }

// Distance from p to the segment a-b.
double distance_to_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const double t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
  return (p - (a + t * (b - a))).norm();
}

// Invariants every straightened curve must meet: ends kept, a simple edge chain, mask grown
// with the mesh, every new vertex inside the region and located on the input mesh. `before`
// is the mesh the curve was inserted into, `input` the mesh provenance started on.
void expect_valid_result(const Mesh& input, const Mesh& before, const Mesh& mesh,
                         const std::vector<bool>& region, const std::vector<VertexHandle>& path,
                         const StraightenResult& result) {
  ASSERT_GE(result.chain.size(), 2u);
  EXPECT_EQ(result.chain.front(), path.front());
  EXPECT_EQ(result.chain.back(), path.back());
  EXPECT_EQ(region.size(), mesh.n_faces());
  std::set<int> seen;
  for (std::size_t k = 0; k < result.chain.size(); ++k) {
    EXPECT_TRUE(seen.insert(result.chain[k].idx()).second)
        << "vertex " << result.chain[k].idx() << " repeats";
    if (k > 0) {
      EXPECT_TRUE(mesh.find_halfedge(result.chain[k - 1], result.chain[k]).is_valid());
    }
  }
  EXPECT_EQ(static_cast<int>(mesh.n_vertices() - before.n_vertices()), result.vertices_added);
  EXPECT_LE(result.length, result.input_length * (1.0 + 1e-12));
  EXPECT_NEAR(result.length, chain_length(mesh, result.chain), 1e-12 * result.length);
  for (auto v : mesh.vertices()) {
    if (v.idx() < static_cast<int>(before.n_vertices())) continue;
    // New vertices lie on split edges strictly inside the region...
    EXPECT_TRUE(test::inside_region(mesh, region, v))
        << "new vertex " << v.idx() << " touches a face outside";
    // ...and every face around them locates them on the input mesh.
    for (FaceHandle f : mesh.vf_range(v)) {
      const SurfacePoint located = to_input_point(mesh, input, f, position(mesh, v));
      EXPECT_LT((position(input, located) - position(mesh, v)).norm(), 1e-9);
    }
  }
}

TEST(StraightenPath, ZigZagOnAFlatGridBecomesTheStraightSegment) {
  const int n = 12;
  const Mesh input = test::flat_grid(n, n, 0.2);
  Mesh mesh = input;
  std::vector<bool> region = whole_mesh(mesh);
  // A zig-zag from (1, 1) to (10, 7) that crosses the straight line several times.
  const std::vector<VertexHandle> path =
      grid_walk(n, {{1, 1}, {1, 3}, {3, 3}, {3, 2}, {5, 2}, {5, 4}, {8, 4}, {8, 5}, {10, 5}, {10, 7}});
  const StraightenResult result = straighten_path(mesh, region, path);
  expect_valid_result(input, input, mesh, region, path, result);
  EXPECT_TRUE(result.converged);
  const Eigen::Vector3d a = position(mesh, path.front());
  const Eigen::Vector3d b = position(mesh, path.back());
  EXPECT_NEAR(result.length, (b - a).norm(), 1e-9);
  double along = -1.0;
  for (VertexHandle v : result.chain) {
    const Eigen::Vector3d p = position(mesh, v);
    EXPECT_LT(distance_to_segment(p, a, b), 1e-9) << "chain vertex " << v.idx();
    const double t = (p - a).dot(b - a);
    EXPECT_GT(t, along);  // monotone along the segment
    along = t;
  }
  // Only a and b are original vertices (the jitter keeps grid vertices off the line).
  EXPECT_EQ(result.vertices_added + 2, static_cast<int>(result.chain.size()));
  std::string why;
  EXPECT_TRUE(is_locally_shortest(mesh, region, result.chain, 1e-9, &why)) << why;
}

TEST(StraightenPath, LoopAroundTheWrongSideIsPulledStraight) {
  const int n = 10;
  const Mesh input = test::flat_grid(n, n, 0.15, 11);
  Mesh mesh = input;
  std::vector<bool> region = whole_mesh(mesh);
  // Up, right and back down: the straight line lies below the whole walk.
  const std::vector<VertexHandle> path = grid_walk(n, {{2, 3}, {2, 8}, {7, 8}, {7, 3}});
  const StraightenResult result = straighten_path(mesh, region, path);
  expect_valid_result(input, input, mesh, region, path, result);
  const Eigen::Vector3d a = position(mesh, path.front());
  const Eigen::Vector3d b = position(mesh, path.back());
  EXPECT_NEAR(result.length, (b - a).norm(), 1e-9);
  for (VertexHandle v : result.chain) EXPECT_LT(distance_to_segment(position(mesh, v), a, b), 1e-9);
}

TEST(StraightenPath, PathOverACubeEdgeUnfoldsStraight) {
  const int n = 8;
  std::map<std::array<int, 3>, VertexHandle> index;
  const Mesh input = test::subdivided_cube(n, &index);
  Mesh mesh = input;
  std::vector<bool> region = whole_mesh(mesh);
  // From (1/8, 5/8) on the top side to (7/8, 2/8) on the front side (y = 0). Unfolding the
  // front side up about their shared edge puts (x, 0, z) at (x, z - 1) in the top's plane.
  // Over the top to its front edge, down the front side, then across it (a shortest edge
  // path could instead go round the cube's corner over the x = 1 side: another geodesic).
  const std::vector<VertexHandle> path = test::cube_walk(index, {{1, 5, n}, {1, 0, n}, {1, 0, 2}, {7, 0, 2}});
  const StraightenResult result = straighten_path(mesh, region, path);
  expect_valid_result(input, input, mesh, region, path, result);
  const auto unfold = [](const Eigen::Vector3d& p) {
    return p.z() > 1.0 - 1e-12 ? Eigen::Vector2d(p.x(), p.y()) : Eigen::Vector2d(p.x(), p.z() - 1.0);
  };
  const Eigen::Vector2d ua(0.125, 0.625);
  const Eigen::Vector2d ub(0.875, -0.75);
  EXPECT_NEAR(result.length, (ub - ua).norm(), 1e-9);
  for (VertexHandle v : result.chain) {
    const Eigen::Vector3d p = position(mesh, v);
    ASSERT_TRUE(p.z() > 1.0 - 1e-12 || p.y() < 1e-12) << "vertex " << v.idx() << " is off the two sides";
    const Eigen::Vector2d q = unfold(p) - ua;
    const Eigen::Vector2d d = ub - ua;
    EXPECT_LT(std::abs(q.x() * d.y() - q.y() * d.x()) / d.norm(), 1e-9) << "vertex " << v.idx();
  }
  std::string why;
  EXPECT_TRUE(is_locally_shortest(mesh, region, result.chain, 1e-9, &why)) << why;
}

// A wall of faces left out of the region between a and b: the curve must go over its top and
// bends at the wall's two top corners, where only the region side spans pi.
TEST(StraightenPath, BendsAroundTheRegionBoundaryWithoutCrossingIt) {
  const int n = 10;
  const Mesh input = test::flat_grid(n, n);
  Mesh mesh = input;
  std::vector<bool> region = whole_mesh(mesh);
  // The wall: squares with x in [4, 5] and y in [0, 6]; two faces per square, row-major.
  for (int j = 0; j < 6; ++j) region[2 * (j * n + 4)] = region[2 * (j * n + 4) + 1] = false;
  const std::vector<VertexHandle> path = grid_walk(n, {{2, 2}, {2, 8}, {7, 8}, {7, 2}});
  const int region_faces_before = static_cast<int>(std::count(region.begin(), region.end(), true));
  const StraightenResult result = straighten_path(mesh, region, path);
  expect_valid_result(input, input, mesh, region, path, result);
  EXPECT_TRUE(result.converged);
  // Each split edge lies between two region faces, which are cut in two.
  EXPECT_EQ(std::count(region.begin(), region.end(), true), region_faces_before + 2 * result.vertices_added);
  EXPECT_NEAR(result.length, 2.0 * std::sqrt(20.0) + 1.0, 1e-9);
  const VertexHandle corner_left = grid_vertex(n, 4, 6);
  const VertexHandle corner_right = grid_vertex(n, 5, 6);
  const auto at = std::find(result.chain.begin(), result.chain.end(), corner_left);
  ASSERT_NE(at, result.chain.end());
  ASSERT_NE(at + 1, result.chain.end());
  EXPECT_EQ(*(at + 1), corner_right);
  EXPECT_EQ(result.boundary_contacts, 2);
  for (auto it = at; it != at + 2; ++it) {
    const CurveSides sides = curve_sides(mesh, *(it - 1), *it, *(it + 1));
    // Left of the walk (which runs left to right over the wall) is the open side above.
    EXPECT_GE(fan_angle(mesh, *sides.left, *it), M_PI - 1e-9);
    EXPECT_LT(fan_angle(mesh, *sides.right, *it), M_PI - 0.1);
    EXPECT_TRUE(
        std::any_of(sides.right->begin(), sides.right->end(), [&](FaceHandle f) { return !region[f.idx()]; }))
        << "the short side at vertex " << it->idx() << " holds no wall face";
  }
  // No chain edge runs inside the wall.
  for (std::size_t k = 1; k < result.chain.size(); ++k) {
    const HalfedgeHandle h = mesh.find_halfedge(result.chain[k - 1], result.chain[k]);
    EXPECT_TRUE(region[mesh.face_handle(h).idx()] || region[mesh.opposite_face_handle(h).idx()]);
  }
  std::string why;
  EXPECT_TRUE(is_locally_shortest(mesh, region, result.chain, 1e-9, &why)) << why;
}

TEST(StraightenPath, CrossingsNearAVertexSnapToIt) {
  const int n = 8;
  const VertexHandle target = grid_vertex(n, 7, 4);
  // The line from (1, 1) to (7, 4) passes through grid vertices (3, 2) and (5, 3); lifting
  // its end by 1e-7 makes it miss them by less than the snap tolerance.
  const auto run = [&](double snap, StraightenResult* result) {
    Mesh mesh = test::flat_grid(n, n);
    mesh.point(target)[1] += 1e-7;
    std::vector<bool> region = whole_mesh(mesh);
    StraightenSettings settings;
    settings.snap_tolerance = snap;
    *result = straighten_path(mesh, region, grid_walk(n, {{1, 1}, {7, 1}, {7, 4}}), settings);
    return mesh;
  };
  StraightenResult snapped;
  const Mesh mesh = run(1e-4, &snapped);
  EXPECT_GE(snapped.snapped_crossings, 2);
  const auto passes = [&](const StraightenResult& r, int i, int j) {
    return std::find(r.chain.begin(), r.chain.end(), grid_vertex(n, i, j)) != r.chain.end();
  };
  EXPECT_TRUE(passes(snapped, 3, 2));
  EXPECT_TRUE(passes(snapped, 5, 3));
  // No new vertex sits next to an old one.
  for (VertexHandle v : snapped.chain) {
    if (v.idx() < (n + 1) * (n + 1)) continue;
    for (VertexHandle w : mesh.vv_range(v)) EXPECT_GT((mesh.point(v) - mesh.point(w)).norm(), 1e-4);
  }
  StraightenResult exact;
  run(0.0, &exact);
  EXPECT_EQ(exact.snapped_crossings, 0);
  EXPECT_FALSE(passes(exact, 3, 2));
  EXPECT_GT(exact.vertices_added, snapped.vertices_added);
}

TEST(StraightenPath, RoundLimitStopsEarlyWithAValidShorterCurve) {
  const int n = 10;
  const Mesh input = test::flat_grid(n, n, 0.2);
  Mesh mesh = input;
  std::vector<bool> region = whole_mesh(mesh);
  const std::vector<VertexHandle> path = grid_walk(n, {{2, 3}, {2, 8}, {7, 8}, {7, 3}});
  StraightenSettings settings;
  settings.max_rounds = 1;
  const StraightenResult result = straighten_path(mesh, region, path, settings);
  expect_valid_result(input, input, mesh, region, path, result);
  EXPECT_FALSE(result.converged);
  EXPECT_EQ(result.rounds, 1);
  EXPECT_LT(result.length, result.input_length);
  EXPECT_FALSE(is_locally_shortest(mesh, region, result.chain, 1e-6));
}

TEST(StraightenPath, SingleEdgeIsLeftAlone) {
  Mesh mesh = test::flat_grid(3, 3);
  std::vector<bool> region = whole_mesh(mesh);
  const std::vector<VertexHandle> path = {grid_vertex(3, 1, 1), grid_vertex(3, 2, 1)};
  const StraightenResult result = straighten_path(mesh, region, path);
  EXPECT_EQ(result.chain, path);
  EXPECT_EQ(result.vertices_added, 0);
  EXPECT_EQ(mesh.n_vertices(), 16u);
}

TEST(StraightenPath, RejectsPathsThatBreakThePreconditions) {
  Mesh mesh = test::flat_grid(6, 6);
  std::vector<bool> region = whole_mesh(mesh);
  // Not along edges.
  EXPECT_THROW(straighten_path(mesh, region, {grid_vertex(6, 1, 1), grid_vertex(6, 3, 1)}), LayoutError);
  // An interior vertex on the mesh boundary.
  EXPECT_THROW(straighten_path(mesh, region, grid_walk(6, {{1, 1}, {1, 0}, {2, 0}, {2, 1}})), LayoutError);
  // An interior vertex next to a face outside the region.
  std::vector<bool> holed = region;
  holed[2 * (1 * 6 + 2) + 1] = false;  // the face of square (2, 1) at vertices (2, 2) and (3, 2)
  EXPECT_THROW(straighten_path(mesh, holed, grid_walk(6, {{1, 2}, {4, 2}})), LayoutError);
  // A vertex twice.
  EXPECT_THROW(straighten_path(mesh, region, grid_walk(6, {{1, 1}, {3, 1}, {2, 1}})), LayoutError);
  // A mask of the wrong size.
  std::vector<bool> short_mask(3, true);
  EXPECT_THROW(straighten_path(mesh, short_mask, grid_walk(6, {{1, 1}, {3, 1}})), LayoutError);
  // No provenance.
  Mesh bare;
  for (auto v : mesh.vertices()) bare.add_vertex(mesh.point(v));
  for (auto f : mesh.faces()) {
    std::vector<VertexHandle> corners(mesh.fv_range(f).begin(), mesh.fv_range(f).end());
    bare.add_face(corners);
  }
  EXPECT_THROW(straighten_path(bare, region, grid_walk(6, {{1, 1}, {3, 1}})), LayoutError);
  EXPECT_EQ(mesh.n_vertices(), 49u);  // nothing was split on the way
}

// Shortest edge paths between spread-out vertex pairs on a real mesh, straightened one after
// another on the same (growing) mesh, over the whole surface.
void straighten_many(const std::string& file, int curves) {
  const Mesh input = test::load_mesh_with_provenance(test::data_path(file).string());
  Mesh mesh = input;
  const int n = static_cast<int>(input.n_vertices());
  for (int k = 0; k < curves; ++k) {
    std::vector<bool> region = whole_mesh(mesh);
    const VertexHandle a((k * 7919) % n);
    const VertexHandle b((k * 7919 + n / 3) % n);
    const std::vector<VertexHandle> path = test::shortest_edge_path(mesh, region, a, b);
    ASSERT_GE(path.size(), 2u);
    const Mesh before = mesh;
    const StraightenResult result = straighten_path(mesh, region, path);
    SCOPED_TRACE(file + " curve " + std::to_string(k));
    expect_valid_result(input, before, mesh, region, path, result);
    EXPECT_TRUE(result.converged);
    EXPECT_LT(result.length, result.input_length);
    std::string why;
    EXPECT_TRUE(is_locally_shortest(mesh, region, result.chain, 1e-8, &why)) << why;
    ::testing::Test::RecordProperty(file + "_curve" + std::to_string(k) + "_vertices_added",
                                    result.vertices_added);
  }
}

TEST(StraightenPath, CurvesOnHumanManAreLocallyShortest) { straighten_many("human_man.obj", 6); }

TEST(StraightenPath, CurvesOnSpotAreLocallyShortest) { straighten_many("spot.ply", 6); }

// A region hugging the input path (faces within a few rings of it) on a curved mesh: the
// curve stays in it and is locally shortest where the region leaves it room.
TEST(StraightenPath, StaysInsideANarrowRegionOnACurvedMesh) {
  const Mesh input = test::load_mesh_with_provenance(test::data_path("spot.ply").string());
  Mesh mesh = input;
  const std::vector<bool> everything = whole_mesh(mesh);
  const std::vector<VertexHandle> path =
      test::shortest_edge_path(mesh, everything, VertexHandle(100), VertexHandle(2500));
  ASSERT_GE(path.size(), 3u);
  std::vector<int> rings(mesh.n_vertices(), -1);
  std::vector<VertexHandle> front = path;
  for (VertexHandle v : path) rings[v.idx()] = 0;
  for (int ring = 1; ring <= 3; ++ring) {
    std::vector<VertexHandle> next;
    for (VertexHandle v : front) {
      for (VertexHandle w : mesh.vv_range(v)) {
        if (rings[w.idx()] < 0) {
          rings[w.idx()] = ring;
          next.push_back(w);
        }
      }
    }
    front = next;
  }
  std::vector<bool> region(mesh.n_faces(), false);
  for (FaceHandle f : mesh.faces()) {
    bool near = true;
    for (VertexHandle v : mesh.fv_range(f)) near = near && rings[v.idx()] >= 0;
    region[f.idx()] = near;
  }
  const std::vector<bool> region_before = region;
  const StraightenResult result = straighten_path(mesh, region, path);
  expect_valid_result(input, input, mesh, region, path, result);
  EXPECT_TRUE(result.converged);
  EXPECT_LT(result.length, result.input_length);
  // Old faces keep their flags; every chain edge has the region on at least one side.
  for (std::size_t f = 0; f < region_before.size(); ++f) EXPECT_EQ(region[f], region_before[f]);
  for (std::size_t k = 1; k < result.chain.size(); ++k) {
    const HalfedgeHandle h = mesh.find_halfedge(result.chain[k - 1], result.chain[k]);
    EXPECT_TRUE(region[mesh.face_handle(h).idx()] || region[mesh.opposite_face_handle(h).idx()]);
  }
  std::string why;
  EXPECT_TRUE(is_locally_shortest(mesh, region, result.chain, 1e-8, &why)) << why;
  RecordProperty("boundary_contacts", result.boundary_contacts);
}

// Many curves straightened over one another on a small mesh: the refinement piles up needle
// triangles, and every curve must still be inserted, simple and locally shortest within the
// documented 2.5 * snap_tolerance.
TEST(StraightenPath, RepeatedRefinementStaysSound) {
  const Mesh input = test::load_mesh_with_provenance(test::data_path("spot_low_resolution.obj").string());
  Mesh mesh = input;
  const int n = static_cast<int>(input.n_vertices());
  const StraightenSettings settings;
  int added = 0;
  for (int k = 0; k < 60; ++k) {
    std::vector<bool> region = whole_mesh(mesh);
    const VertexHandle a((k * 7919) % n);
    const VertexHandle b((k * 7919 + n / 3) % n);
    const std::vector<VertexHandle> path = test::shortest_edge_path(mesh, region, a, b);
    const Mesh before = mesh;
    const StraightenResult result = straighten_path(mesh, region, path, settings);
    SCOPED_TRACE("curve " + std::to_string(k));
    expect_valid_result(input, before, mesh, region, path, result);
    EXPECT_TRUE(result.converged);
    std::string why;
    EXPECT_TRUE(is_locally_shortest(mesh, region, result.chain, 2.5 * settings.snap_tolerance, &why)) << why;
    added += result.vertices_added;
  }
  RecordProperty("vertices_added", added);
}

}  // namespace
}  // namespace xparam
