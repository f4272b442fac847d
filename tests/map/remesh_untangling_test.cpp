#include "map/remesh_untangling.h"

#include "core/anchors.h"
#include "core/errors.h"
#include "core/planar.h"
#include "core/provenance.h"
#include "io/anchor_reader.h"
#include "io/mesh_loader.h"
#include "map/pair_mapping.h"
#include "support/test_data.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <tuple>
#include <variant>

namespace xparam {
namespace {

// An n x n grid of squares over [-1, 1]^2 in the plane z = 0, each square cut along the
// diagonal that alternates, faces counter-clockwise seen from +z.
Mesh planar_grid(int n) {
  Mesh mesh;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) mesh.add_vertex({-1.0 + 2.0 * i / n, -1.0 + 2.0 * j / n, 0.0});
  }
  auto id = [n](int i, int j) { return VertexHandle(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      if ((i + j) % 2 == 0) {
        mesh.add_face(id(i, j), id(i + 1, j), id(i + 1, j + 1));
        mesh.add_face(id(i, j), id(i + 1, j + 1), id(i, j + 1));
      } else {
        mesh.add_face(id(i, j), id(i + 1, j), id(i, j + 1));
        mesh.add_face(id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
      }
    }
  }
  return mesh;
}

// A swirl of the plane: rotation about the origin by an angle that decays with the radius.
// A bijection of the plane (every circle rotates onto itself) and the identity near the
// square's boundary.
Eigen::Vector2d swirl(const Eigen::Vector2d& p, double turns) {
  const double angle = 2.0 * std::numbers::pi * turns * std::exp(-p.squaredNorm() / 0.16);
  return Eigen::Vector2d(std::cos(angle) * p.x() - std::sin(angle) * p.y(),
                         std::sin(angle) * p.x() + std::cos(angle) * p.y());
}

// The point of the flat target grid (z = 0) at y.
MappedPoint flat_target_point(const Mesh& target, const Eigen::Vector2d& y) {
  MappedPoint image;
  double best = -std::numeric_limits<double>::infinity();
  for (FaceHandle f : target.faces()) {
    Eigen::Vector3d x[3];
    int c = 0;
    for (VertexHandle v : target.fv_range(f)) x[c++] = position(target, v);
    const Eigen::Vector3d bary = barycentric(Eigen::Vector3d(y.x(), y.y(), 0.0), x[0], x[1], x[2]);
    if (bary.minCoeff() > best) {
      best = bary.minCoeff();
      image.on_input = SurfacePoint{f.idx(), bary};
    }
  }
  image.position = position(target, image.on_input);
  return image;
}

// Gamma of the constructed case: template point -> swirled -> located on the target grid.
MappedPoint swirl_map(const Mesh& source, const Mesh& target, const SurfacePoint& point, double turns) {
  return flat_target_point(target, swirl(position(source, point).head<2>(), turns));
}

struct SwirlCase {
  Mesh source = planar_grid(8);
  Mesh target = planar_grid(8);
  double turns = 0.6;  // strong enough that the remesh folds (4 faces)
  SurfaceMap gamma = [this](const SurfacePoint& p) { return swirl_map(source, target, p, turns); };

  std::vector<MappedPoint> vertex_images() const {
    std::vector<MappedPoint> images;
    for (VertexHandle v : source.vertices()) {
      const FaceHandle f = *source.vf_range(v).begin();
      SurfacePoint point;
      point.face = f.idx();
      int c = 0;
      for (VertexHandle w : source.fv_range(f)) point.bary[c++] = (w == v) ? 1.0 : 0.0;
      images.push_back(gamma(point));
    }
    return images;
  }

  std::vector<std::array<int, 3>> faces() const { return triangles_of(source); }
};

// Both fan centres of a move strictly inside the kernel of its flattened star.
void expect_in_kernel(const StarMove& move) {
  const int k = static_cast<int>(move.ring.size());
  for (int j = 0; j < k; ++j) {
    const Eigen::Vector2d& a = move.ring[j];
    const Eigen::Vector2d& b = move.ring[(j + 1) % k];
    EXPECT_GT(cross2(a - move.from, b - move.from), 0.0) << "vertex " << move.center << " wedge " << j;
    EXPECT_GT(cross2(a - move.to, b - move.to), 0.0) << "vertex " << move.center << " wedge " << j;
  }
}

TEST(RemeshUntangling, SwirlFoldsTheRemeshAndSlidingVerticesUnfoldsIt) {
  const SwirlCase swirl_case;
  const std::vector<std::array<int, 3>> faces = swirl_case.faces();
  const std::vector<MappedPoint> images = swirl_case.vertex_images();
  const RemeshQualityResult before = measure_remesh_quality(faces, images, swirl_case.target);
  ASSERT_GE(before.flipped_faces.size(), 1u);

  const UntangleResult r =
      untangle_remesh(swirl_case.source, images, swirl_case.gamma, swirl_case.target, {});
  EXPECT_EQ(r.flipped_before, static_cast<int>(before.flipped_faces.size()));
  EXPECT_EQ(r.flipped_after, 0);
  EXPECT_TRUE(measure_remesh_quality(faces, r.images, swirl_case.target).flipped_faces.empty());
  EXPECT_GE(r.moved_vertices, 1);
  EXPECT_GT(r.max_move, 0.0);
  // A vertex moves inside its star: less than the longest spoke of the grid (the diagonal).
  EXPECT_LT(r.max_move, 2.0 * std::sqrt(2.0) / 8.0);

  // phi is a homeomorphism: every move re-fans its star from a kernel point to a kernel point.
  ASSERT_FALSE(r.warp.moves.empty());
  for (const auto& move : r.warp.moves) {
    if (const StarMove* star = std::get_if<StarMove>(&move)) expect_in_kernel(*star);
  }
  // The reported points are phi of the vertices, their images Gamma of those points, on the target.
  for (VertexHandle v : swirl_case.source.vertices()) {
    SurfacePoint at_v;
    at_v.face = (*swirl_case.source.vf_range(v).begin()).idx();
    int c = 0;
    for (VertexHandle w : swirl_case.source.fv_range(swirl_case.source.face_handle(at_v.face)))
      at_v.bary[c++] = (w == v) ? 1.0 : 0.0;
    const Eigen::Vector3d moved = position(swirl_case.source, r.warp(at_v));
    EXPECT_LT((moved - position(swirl_case.source, r.template_points[v.idx()])).norm(), 1e-12) << v.idx();
    const MappedPoint image = swirl_case.gamma(r.template_points[v.idx()]);
    EXPECT_LT((image.position - r.images[v.idx()].position).norm(), 1e-12) << v.idx();
    EXPECT_LT((position(swirl_case.target, r.images[v.idx()].on_input) - r.images[v.idx()].position).norm(),
              1e-12);
  }
  // The square's boundary is where no vertex can move: phi fixes it.
  for (VertexHandle v : swirl_case.source.vertices()) {
    if (!swirl_case.source.is_boundary(v)) continue;
    EXPECT_LT(
        (position(swirl_case.source, r.template_points[v.idx()]) - position(swirl_case.source, v)).norm(),
        1e-15);
  }
}

TEST(RemeshUntangling, WarpKeepsPointsOfTheSurfaceOnItAndMovesOnlyInsideStars) {
  // phi of many points of the square: outside the moved stars nothing changes, and phi is
  // injective on a dense sample (distinct points stay distinct).
  const SwirlCase swirl_case;
  const UntangleResult r =
      untangle_remesh(swirl_case.source, swirl_case.vertex_images(), swirl_case.gamma, swirl_case.target, {});
  ASSERT_FALSE(r.warp.moves.empty());
  std::vector<bool> in_moved_star(swirl_case.source.n_faces(), false);
  for (const auto& move : r.warp.moves) {
    for (int f : std::visit([](const auto& m) { return m.faces; }, move)) in_moved_star[f] = true;
  }
  std::vector<Eigen::Vector3d> images;
  for (FaceHandle f : swirl_case.source.faces()) {
    for (int a = 1; a < 7; ++a) {
      for (int b = 1; a + b < 8; ++b) {
        SurfacePoint p;
        p.face = f.idx();
        p.bary = Eigen::Vector3d(a, b, 8 - a - b) / 8.0;
        const SurfacePoint q = r.warp(p);
        EXPECT_NEAR(q.bary.sum(), 1.0, 1e-12);
        EXPECT_GE(q.bary.minCoeff(), 0.0);
        if (!in_moved_star[f.idx()]) {
          EXPECT_EQ(q.face, p.face);
          EXPECT_LT((q.bary - p.bary).norm(), 1e-15);
        }
        images.push_back(position(swirl_case.source, q));
      }
    }
  }
  // Sample spacing is about 0.25 / 8 of the square; images closer than 1e-9 would be a fold.
  std::sort(images.begin(), images.end(), [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return std::tie(a.x(), a.y()) < std::tie(b.x(), b.y());
  });
  for (std::size_t i = 1; i < images.size(); ++i) EXPECT_GT((images[i] - images[i - 1]).norm(), 1e-9);
}

// Exactly where template vertex v is (phi(x_v) == x_v, not merely close).
bool at_own_vertex(const Mesh& mesh, const SurfacePoint& point, int v) {
  int corner = 0;
  for (VertexHandle w : mesh.fv_range(mesh.face_handle(point.face))) {
    if (point.bary[corner++] != (w.idx() == v ? 1.0 : 0.0)) return false;
  }
  return true;
}

TEST(RemeshUntangling, AnchoredVerticesNeverMove) {
  const SwirlCase swirl_case;
  const Mesh& mesh = swirl_case.source;
  const UntangleResult free =
      untangle_remesh(mesh, swirl_case.vertex_images(), swirl_case.gamma, swirl_case.target, {});
  ASSERT_FALSE(free.warp.moves.empty());
  // Anchor (at the vertex itself) every vertex that moved: then none of them may move.
  std::vector<SurfacePoint> anchors;
  std::vector<int> anchored;
  for (VertexHandle v : mesh.vertices()) {
    if (at_own_vertex(mesh, free.template_points[v.idx()], v.idx())) continue;
    anchored.push_back(v.idx());
    anchors.push_back(vertex_surface_point(mesh, v));
  }
  ASSERT_FALSE(anchored.empty());
  const UntangleResult fixed =
      untangle_remesh(mesh, swirl_case.vertex_images(), swirl_case.gamma, swirl_case.target, anchors);
  for (std::size_t a = 0; a < anchored.size(); ++a) {
    EXPECT_TRUE(at_own_vertex(mesh, fixed.template_points[anchored[a]], anchored[a])) << anchored[a];
    const SurfacePoint image = fixed.warp(anchors[a]);
    EXPECT_EQ(image.face, anchors[a].face);
    EXPECT_TRUE(image.bary == anchors[a].bary) << anchored[a];
  }
}

// A squeeze of the directions about an anchored vertex: the anchor at grid vertex (4, 3)
// (valence 4, its one-ring 90 degrees apart) stays, and every direction theta about it turns to
// theta0 + 2 atan(k tan((theta - theta0) / 2)) (the boundary map of a hyperbolic disc
// automorphism: monotone, a bijection of the circle), blended into the identity between radii
// 0.3 and 0.7. With theta0 = 45 degrees and k = 8 the wedge between the anchor's ring vertices
// E and N opens to 293 degrees and the other three wedges share the rest: the remesh face
// (anchor, E, N) folds, and no single ring vertex can slide far enough into the narrow band
// about theta0 that would open the wedge below 180 degrees without folding its other faces.
struct SqueezeCase : SwirlCase {
  Eigen::Vector2d anchor{0.0, -0.25};
  double theta0 = std::numbers::pi / 4.0;
  double k = 8.0;
  SqueezeCase() {
    gamma = [this](const SurfacePoint& p) {
      const Eigen::Vector2d d = position(source, p).head<2>() - anchor;
      const double r = d.norm();
      const double t = std::clamp((r - 0.3) / 0.4, 0.0, 1.0);
      const double blend = 1.0 - t * t * (3.0 - 2.0 * t);
      const double theta = std::atan2(d.y(), d.x());
      const double turned =
          theta0 +
          2.0 * std::atan(k * std::tan(0.5 * std::remainder(theta - theta0, 2.0 * std::numbers::pi)));
      const double angle = theta + blend * std::remainder(turned - theta, 2.0 * std::numbers::pi);
      return flat_target_point(target, anchor + r * Eigen::Vector2d(std::cos(angle), std::sin(angle)));
    };
  }
  int centre() const { return 3 * 9 + 4; }  // vertex (4, 3) of the 8 x 8 grid
};

// The ring move on its own (star moves off; on this small case they too find a way, while on
// the SMPL man -> man_flipped pair they do not: tests/map/pair_mapping_test.cpp).
TEST(RemeshUntangling, RingMovesUnfoldAFoldAtAnAnchorAndFixIt) {
  const SqueezeCase squeeze;
  const Mesh& mesh = squeeze.source;
  const std::vector<std::array<int, 3>> faces = squeeze.faces();
  const std::vector<MappedPoint> images = squeeze.vertex_images();
  const SurfacePoint anchor = vertex_surface_point(mesh, mesh.vertex_handle(squeeze.centre()));
  ASSERT_LT((position(mesh, anchor).head<2>() - squeeze.anchor).norm(), 1e-15);
  ASSERT_EQ(mesh.valence(mesh.vertex_handle(squeeze.centre())), 4u);
  auto has_anchor_corner = [&](int f) {
    return std::find(faces[f].begin(), faces[f].end(), squeeze.centre()) != faces[f].end();
  };
  const RemeshQualityResult before = measure_remesh_quality(faces, images, squeeze.target);
  ASSERT_TRUE(std::any_of(before.flipped_faces.begin(), before.flipped_faces.end(), has_anchor_corner));

  UntangleSettings rings_only;
  rings_only.star_moves = false;
  const UntangleResult r = untangle_remesh(mesh, images, squeeze.gamma, squeeze.target, {anchor}, rings_only);
  EXPECT_EQ(r.flipped_before, static_cast<int>(before.flipped_faces.size()));
  EXPECT_EQ(r.flipped_after, 0);
  EXPECT_TRUE(measure_remesh_quality(faces, r.images, squeeze.target).flipped_faces.empty());
  ASSERT_GE(r.ring_moves, 1);
  EXPECT_EQ(r.ring_moves, static_cast<int>(r.warp.moves.size()));
  // The anchor is fixed exactly, as a vertex and as a point.
  EXPECT_TRUE(at_own_vertex(mesh, r.template_points[squeeze.centre()], squeeze.centre()));
  const SurfacePoint fixed = r.warp(anchor);
  EXPECT_EQ(fixed.face, anchor.face);
  EXPECT_TRUE(fixed.bary == anchor.bary);
  for (const auto& move : r.warp.moves) {
    const RingMove* ring = std::get_if<RingMove>(&move);
    if (ring == nullptr) continue;
    // Both triangulations of the flat disc are embeddings with the same boundary, and the
    // centre does not move: the move is a homeomorphism of the disc fixing its boundary.
    for (std::size_t j = 0; j < ring->faces.size(); ++j) {
      const std::array<int, 3>& c = ring->corners[j];
      EXPECT_GT(cross2(ring->rest[c[1]] - ring->rest[c[0]], ring->rest[c[2]] - ring->rest[c[0]]), 0.0);
      EXPECT_GT(cross2(ring->from[c[1]] - ring->from[c[0]], ring->from[c[2]] - ring->from[c[0]]), 0.0);
      EXPECT_GT(cross2(ring->to[c[1]] - ring->to[c[0]], ring->to[c[2]] - ring->to[c[0]]), 0.0);
    }
    const int n_ring = static_cast<int>(mesh.valence(mesh.vertex_handle(ring->center)));
    for (std::size_t u = 0; u < ring->vertices.size(); ++u) {
      if (u >= 1 && static_cast<int>(u) <= n_ring) continue;
      EXPECT_TRUE(ring->from[u] == ring->rest[u] && ring->to[u] == ring->rest[u]) << ring->vertices[u];
    }
  }
  // The images are Gamma of the moved points.
  for (VertexHandle v : mesh.vertices()) {
    EXPECT_LT((squeeze.gamma(r.template_points[v.idx()]).position - r.images[v.idx()].position).norm(), 1e-12)
        << v.idx();
  }
  // phi is injective on a dense sample and keeps points on the square.
  std::vector<Eigen::Vector3d> moved;
  for (FaceHandle f : mesh.faces()) {
    for (int a = 1; a < 7; ++a) {
      for (int b = 1; a + b < 8; ++b) {
        const SurfacePoint q = r.warp(SurfacePoint{f.idx(), Eigen::Vector3d(a, b, 8 - a - b) / 8.0});
        EXPECT_NEAR(q.bary.sum(), 1.0, 1e-12);
        EXPECT_GE(q.bary.minCoeff(), 0.0);
        moved.push_back(position(mesh, q));
      }
    }
  }
  std::sort(moved.begin(), moved.end(), [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return std::tie(a.x(), a.y()) < std::tie(b.x(), b.y());
  });
  for (std::size_t i = 1; i < moved.size(); ++i) EXPECT_GT((moved[i] - moved[i - 1]).norm(), 1e-9);
}

TEST(RemeshUntangling, RejectsImagesOfTheWrongSize) {
  const SwirlCase swirl_case;
  std::vector<MappedPoint> images = swirl_case.vertex_images();
  images.pop_back();
  EXPECT_THROW(untangle_remesh(swirl_case.source, images, swirl_case.gamma, swirl_case.target, {}),
               ParamError);
}

}  // namespace
}  // namespace xparam
