#include "map/remesh_untangling.h"

#include "core/errors.h"
#include "core/provenance.h"
#include "io/anchor_reader.h"
#include "io/mesh_loader.h"
#include "map/pair_mapping.h"
#include "support/test_data.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <cstdio>
#include <limits>
#include <numbers>

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
  return Eigen::Vector2d(std::cos(angle) * p.x() - std::sin(angle) * p.y(), std::sin(angle) * p.x() + std::cos(angle) * p.y());
}

// Gamma of the constructed case: template point -> swirled -> located on the target grid.
MappedPoint swirl_map(const Mesh& source, const Mesh& target, const SurfacePoint& point, double turns) {
  const Eigen::Vector3d p = position(source, point);
  const Eigen::Vector2d q = swirl(p.head<2>(), turns);
  MappedPoint image;
  double best = -std::numeric_limits<double>::infinity();
  for (FaceHandle f : target.faces()) {
    Eigen::Vector3d x[3];
    int c = 0;
    for (VertexHandle v : target.fv_range(f)) x[c++] = position(target, v);
    const Eigen::Vector3d bary = barycentric(Eigen::Vector3d(q.x(), q.y(), 0.0), x[0], x[1], x[2]);
    if (bary.minCoeff() > best) {
      best = bary.minCoeff();
      image.on_input.face = f.idx();
      image.on_input.bary = bary;
    }
  }
  image.position = position(target, image.on_input);
  return image;
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

  std::vector<std::array<int, 3>> faces() const {
    std::vector<std::array<int, 3>> list;
    for (FaceHandle f : source.faces()) {
      std::array<int, 3> t{};
      int c = 0;
      for (VertexHandle v : source.fv_range(f)) t[c++] = v.idx();
      list.push_back(t);
    }
    return list;
  }
};

RemeshQualityResult quality_of(const std::vector<std::array<int, 3>>& faces, const std::vector<MappedPoint>& images,
                               const Mesh& target) {
  std::vector<Eigen::Vector3d> positions;
  std::vector<SurfacePoint> locations;
  for (const MappedPoint& image : images) {
    positions.push_back(image.position);
    locations.push_back(image.on_input);
  }
  return measure_remesh_quality(faces, positions, locations, target);
}

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

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
  const RemeshQualityResult before = quality_of(faces, images, swirl_case.target);
  ASSERT_GE(before.flipped_faces.size(), 1u);

  const UntangleResult r = untangle_remesh(swirl_case.source, images, swirl_case.gamma, swirl_case.target, {});
  EXPECT_EQ(r.flipped_before, static_cast<int>(before.flipped_faces.size()));
  EXPECT_EQ(r.flipped_after, 0);
  EXPECT_TRUE(quality_of(faces, r.images, swirl_case.target).flipped_faces.empty());
  EXPECT_GE(r.moved_vertices, 1);
  EXPECT_GT(r.max_move, 0.0);
  // A vertex moves inside its star: less than the longest spoke of the grid (the diagonal).
  EXPECT_LT(r.max_move, 2.0 * std::sqrt(2.0) / 8.0);

  // phi is a homeomorphism: every move re-fans its star from a kernel point to a kernel point.
  ASSERT_FALSE(r.warp.moves.empty());
  for (const StarMove& move : r.warp.moves) expect_in_kernel(move);
  // The reported points are phi of the vertices, their images Gamma of those points, on the target.
  for (VertexHandle v : swirl_case.source.vertices()) {
    SurfacePoint at_v;
    at_v.face = (*swirl_case.source.vf_range(v).begin()).idx();
    int c = 0;
    for (VertexHandle w : swirl_case.source.fv_range(swirl_case.source.face_handle(at_v.face))) at_v.bary[c++] = (w == v) ? 1.0 : 0.0;
    const Eigen::Vector3d moved = position(swirl_case.source, r.warp(at_v));
    EXPECT_LT((moved - position(swirl_case.source, r.template_points[v.idx()])).norm(), 1e-12) << v.idx();
    const MappedPoint image = swirl_case.gamma(r.template_points[v.idx()]);
    EXPECT_LT((image.position - r.images[v.idx()].position).norm(), 1e-12) << v.idx();
    EXPECT_LT((position(swirl_case.target, r.images[v.idx()].on_input) - r.images[v.idx()].position).norm(), 1e-12);
  }
  // The square's boundary is where no vertex can move: phi fixes it.
  for (VertexHandle v : swirl_case.source.vertices()) {
    if (!swirl_case.source.is_boundary(v)) continue;
    EXPECT_LT((position(swirl_case.source, r.template_points[v.idx()]) - position(swirl_case.source, v)).norm(), 1e-15);
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
  for (const StarMove& move : r.warp.moves) {
    for (int f : move.faces) in_moved_star[f] = true;
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

TEST(RemeshUntangling, AnchoredVerticesNeverMove) {
  const SwirlCase swirl_case;
  const UntangleResult free = untangle_remesh(swirl_case.source, swirl_case.vertex_images(), swirl_case.gamma,
                                              swirl_case.target, {});
  ASSERT_FALSE(free.warp.moves.empty());
  // Anchor the vertices that moved: with an anchor in every star they used, none may move.
  std::vector<SurfacePoint> anchors;
  for (const StarMove& move : free.warp.moves) {
    SurfacePoint p;
    p.face = move.faces.front();
    p.bary[move.center_slot.front()] = 1.0;
    anchors.push_back(p);
  }
  const UntangleResult fixed = untangle_remesh(swirl_case.source, swirl_case.vertex_images(), swirl_case.gamma,
                                               swirl_case.target, anchors);
  for (const StarMove& move : fixed.warp.moves) {
    for (const StarMove& anchored : free.warp.moves) EXPECT_NE(move.center, anchored.center);
  }
}

TEST(RemeshUntangling, RejectsImagesOfTheWrongSize) {
  const SwirlCase swirl_case;
  std::vector<MappedPoint> images = swirl_case.vertex_images();
  images.pop_back();
  EXPECT_THROW(untangle_remesh(swirl_case.source, images, swirl_case.gamma, swirl_case.target, {}), ParamError);
}

}  // namespace
}  // namespace xparam
