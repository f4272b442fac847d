// The quad workspace (domain/quad_workspace.h) on stretched layouts of the bundled meshes: every
// quad's workspace is a faithful, closed copy of its two patches, and try_swap measured there
// agrees with apply_swap on the full layout.
#include "domain/quad_workspace.h"

#include "core/errors.h"
#include "core/provenance.h"
#include "domain/boundary_swap.h"
#include "domain/stretched_layouts.h"
#include "geodesic/locally_shortest.h"
#include "geodesic/vertex_fan.h"
#include "layout/chain_edit.h"
#include "layout/consistent_layout.h"
#include "layout/layout_check.h"
#include "support/test_data.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <string>

namespace xparam {
namespace {

double face_area(const Mesh& mesh, FaceHandle f) {
  auto corner = mesh.cfv_begin(f);
  const Eigen::Vector3d x = position(mesh, *corner++);
  const Eigen::Vector3d y = position(mesh, *corner++);
  const Eigen::Vector3d z = position(mesh, *corner);
  return 0.5 * (y - x).cross(z - x).norm();
}

// Surface area of the faces carrying each of two patch ids, summed in face order.
std::array<double, 2> areas(const Mesh& mesh, const std::array<int, 2>& patches) {
  std::array<double, 2> area{};
  for (const FaceHandle f : mesh.faces()) {
    const int p = patch_of(mesh, f);
    if (p == patches[0]) area[0] += face_area(mesh, f);
    if (p == patches[1]) area[1] += face_area(mesh, f);
  }
  return area;
}

std::vector<Eigen::Vector3d> points(const Mesh& mesh, const std::vector<VertexHandle>& chain) {
  std::vector<Eigen::Vector3d> result;
  for (const VertexHandle v : chain) result.push_back(position(mesh, v));
  return result;
}

// The structural check of one workspace against the layout it was cut from.
void expect_faithful(const Layout& layout, const SwapQuad& quad, const QuadWorkspace& ws,
                     const std::string& what) {
  SCOPED_TRACE(what);
  LayoutCheckSettings polygons;
  polygons.triangles = false;
  const LayoutCheck check = check_layout(ws.layout, polygons);
  EXPECT_TRUE(check.consistent()) << check.violations.front();
  EXPECT_EQ(ws.layout.n_anchors, 4);
  ASSERT_EQ(ws.layout.edges.size(), 5u);
  ASSERT_EQ(ws.layout.patches.size(), 3u);
  EXPECT_EQ(ws.anchors, (std::array<int, 4>{quad.a, quad.b, quad.l, quad.r}));
  EXPECT_EQ(ws.patches, (std::array<int, 2>{quad.left_patch, quad.right_patch}));
  EXPECT_EQ(ws.edges[0], quad.edge);
  for (int k = 0; k < 5; ++k) {
    // Each workspace edge joins the workspace anchors of its full edge's anchors.
    for (int end = 0; end < 2; ++end)
      EXPECT_EQ(ws.anchors[ws.layout.edges[k].anchors[end]], layout.edges[ws.edges[k]].anchors[end]);
  }
  for (int side = 0; side < 2; ++side) {
    const Mesh& full = layout.sides[side].mesh;
    const Mesh& local = ws.layout.sides[side].mesh;
    const std::vector<int>& vertices = ws.vertices[side];
    const std::vector<int>& faces = ws.faces[side];
    // Relative order kept: the maps to the full mesh are strictly increasing.
    EXPECT_TRUE(std::is_sorted(vertices.begin(), vertices.end()) &&
                std::adjacent_find(vertices.begin(), vertices.end()) == vertices.end());
    EXPECT_TRUE(std::is_sorted(faces.begin(), faces.end()) &&
                std::adjacent_find(faces.begin(), faces.end()) == faces.end());
    EXPECT_EQ(ws.apex[side].idx(), static_cast<int>(vertices.size()));
    ASSERT_EQ(local.n_vertices(), vertices.size() + 1);

    // Every face of the two patches present once (faces is sorted and distinct, so equal
    // counts mean equal sets), with its patch, provenance and corners in the same order.
    int in_quad = 0;
    for (const FaceHandle f : full.faces()) {
      const int p = patch_of(full, f);
      in_quad += p == quad.left_patch || p == quad.right_patch;
    }
    ASSERT_EQ(static_cast<int>(faces.size()), in_quad);
    for (int k = 0; k < static_cast<int>(faces.size()); ++k) {
      const FaceHandle f(faces[k]);
      const FaceHandle g(k);
      ASSERT_EQ(ws.patches[patch_of(local, g)], patch_of(full, f)) << "face " << k;
      ASSERT_EQ(input_face(local, g), input_face(full, f)) << "face " << k;
      auto corner = local.cfv_begin(g);
      for (const VertexHandle v : full.fv_range(f))
        ASSERT_EQ(vertices[(corner++)->idx()], v.idx()) << "face " << k;
    }
    // The cap: one face per boundary edge of the quad, closing the mesh into a sphere.
    int boundary_edges = 0;
    for (int k = 1; k < 5; ++k)
      boundary_edges += static_cast<int>(layout.sides[side].chains[ws.edges[k]].size()) - 1;
    ASSERT_EQ(local.n_faces(), faces.size() + boundary_edges);
    for (std::size_t k = faces.size(); k < local.n_faces(); ++k) {
      const FaceHandle cap(static_cast<int>(k));
      EXPECT_EQ(patch_of(local, cap), QuadWorkspace::kCapPatch);
      EXPECT_EQ(input_face(local, cap), kCapInputFace);
      EXPECT_TRUE(face_has_vertex(local, cap, ws.apex[side]));
    }
    for (const HalfedgeHandle h : local.halfedges()) ASSERT_FALSE(local.is_boundary(h));
    EXPECT_EQ(static_cast<int>(local.n_vertices()) - static_cast<int>(local.n_edges()) +
                  static_cast<int>(local.n_faces()),
              2);

    // Chains and anchors: the same points as in the full layout.
    for (int k = 0; k < 5; ++k) {
      EXPECT_EQ(points(local, ws.layout.sides[side].chains[k]),
                points(full, layout.sides[side].chains[ws.edges[k]]))
          << "edge " << k;
    }
    for (int k = 0; k < 4; ++k) {
      EXPECT_EQ(position(local, ws.layout.sides[side].anchor_vertices[k]),
                position(full, layout.sides[side].anchor_vertices[ws.anchors[k]]));
    }
    // The quad's surface area is the two patches' area of the full layout.
    const std::array<double, 2> full_area = areas(full, {quad.left_patch, quad.right_patch});
    const std::array<double, 2> local_area = areas(local, {0, 1});
    for (int k = 0; k < 2; ++k) EXPECT_NEAR(local_area[k], full_area[k], 1e-12 * full_area[k]);
  }
}

TEST(QuadWorkspace, EveryQuadOfTheHumansIsCopiedFaithfully) {
  const Layout& layout = test::stretched_human_layout();
  int checked = 0;
  for (int e = 0; e < static_cast<int>(layout.edges.size()); ++e) {
    const SwapQuad quad = swap_quad(layout, e).value();
    if (quad.l == quad.r) continue;
    expect_faithful(layout, quad, make_quad_workspace(layout, quad), "human pair, edge " + std::to_string(e));
    ++checked;
  }
  EXPECT_EQ(checked, static_cast<int>(layout.edges.size()));
}

// try_swap on the workspace against apply_swap on the full layout, for every edge of `layout`:
// the same refusals, and lengths and areas within test::kTrialTolerance; the trial's `after` is a
// consistent layout whose new patches hold the faces apply_swap gives them.
void expect_trials_match(const Layout& layout, const std::string& what) {
  double worst = 0.0;
  int possible = 0, refused = 0, same_chains = 0;
  double seconds = 0.0;
  for (int e = 0; e < static_cast<int>(layout.edges.size()); ++e) {
    SCOPED_TRACE(what + ", edge " + std::to_string(e));
    const auto start = std::chrono::steady_clock::now();
    const SwapTrial trial = try_swap(layout, e);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    Layout applied = layout;
    if (!trial.possible) {
      ++refused;
      try {
        apply_swap(applied, e);
        ADD_FAILURE() << "try_swap refused (" << trial.refusal << ") but apply_swap did not";
      } catch (const LayoutError& error) {
        EXPECT_EQ(std::string(error.what()),
                  "boundary swap of layout edge " + std::to_string(e) + " refused: " + trial.refusal);
      }
      continue;
    }
    ++possible;
    apply_swap(applied, e);
    const std::array<int, 2> patches = {trial.quad.left_patch, trial.quad.right_patch};
    LayoutCheckSettings polygons;
    polygons.triangles = false;
    const LayoutCheck check = check_layout(trial.after, polygons);
    EXPECT_TRUE(check.consistent()) << check.violations.front();
    for (int side = 0; side < 2; ++side) {
      const Mesh& full = applied.sides[side].mesh;
      const Mesh& after = trial.after.sides[side].mesh;
      const double length = chain_length(full, applied.sides[side].chains[e]);
      EXPECT_NEAR(trial.length[side], length, test::kTrialTolerance * length);
      worst = std::max(worst, std::abs(trial.length[side] - length) / length);
      const std::array<double, 2> area = areas(full, patches);
      const std::array<double, 2> after_area = areas(after, trial.after_patches);
      for (int k = 0; k < 2; ++k) {
        EXPECT_NEAR(trial.area[side][k], area[k], test::kTrialTolerance * area[k]);
        EXPECT_NEAR(after_area[k], area[k], test::kTrialTolerance * area[k]);
        worst = std::max(worst, std::abs(trial.area[side][k] - area[k]) / area[k]);
      }
      // The new curve in `after`: the chain of the new patches' shared edge.
      const int lr = layout_edge_of(trial.after.patches[trial.after_patches[0]].front());
      EXPECT_EQ(trial.after.edges[lr].anchors, (std::array<int, 2>{2, 3}));  // l -> r
      same_chains +=
          points(after, trial.after.sides[side].chains[lr]) == points(full, applied.sides[side].chains[e]);
    }
  }
  EXPECT_GT(possible, 0) << what;
  EXPECT_GT(refused, 0) << what;
  std::cout << what << ": " << possible << " swaps possible, " << refused << " refused; largest relative "
            << "difference try_swap vs apply_swap " << worst << "; " << same_chains << " of " << 2 * possible
            << " new chains point-identical; one try_swap " << 1e3 * seconds / layout.edges.size() << " ms ("
            << layout.sides[0].mesh.n_vertices() << " + " << layout.sides[1].mesh.n_vertices()
            << " vertices)\n";
}

TEST(QuadWorkspace, TrySwapAgreesWithApplySwapOnTheHumans) {
  expect_trials_match(test::stretched_human_layout(), "human pair");
}

TEST(QuadWorkspace, TrySwapAgreesWithApplySwapOnSpot) {
  expect_trials_match(test::stretched_spot_layout(), "spot pair");
}

// try_swap of every edge, once in edge order on one thread and once in parallel on two: the
// same refusals and bit-identical numbers (the optimizer evaluates candidates in parallel).
TEST(QuadWorkspace, TrialsDoNotDependOnTheThreadCount) {
  const Layout& layout = test::stretched_human_layout();
  const int n = static_cast<int>(layout.edges.size());
  std::vector<SwapTrial> serial(n), parallel(n);
  for (int e = 0; e < n; ++e) serial[e] = try_swap(layout, e);
  {
    const tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 2);
    tbb::parallel_for(0, n, [&](int e) { parallel[e] = try_swap(layout, e); });
  }
  for (int e = 0; e < n; ++e) {
    EXPECT_EQ(serial[e].possible, parallel[e].possible) << "edge " << e;
    EXPECT_EQ(serial[e].refusal, parallel[e].refusal) << "edge " << e;
    EXPECT_EQ(serial[e].length, parallel[e].length) << "edge " << e;
    EXPECT_EQ(serial[e].area, parallel[e].area) << "edge " << e;
  }
}

}  // namespace
}  // namespace xparam
